"""Benchmarks of the tool: its speed, accuracy and stability. Each module
prints a table and, with --docs, writes its page into docs/benchmarks/:

    python -m bench.loop_floor --docs
"""
