"""The command lines: every entry point's options and files refused in one line, the one command."""
