"""The command line: one parser (parser.py) with a subcommand each, the options
of a run, a study and its cluster, and `oblique-impact` (console.py)."""
