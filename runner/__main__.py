"""Command line: python -m runner {impact,run,study,page,tilt} --help (runner/cli/parser.py)."""

import sys

from .cli.parser import main, parser  # noqa: F401 (python -m runner's parser, for the tests)

if __name__ == "__main__":
    sys.exit(main())
