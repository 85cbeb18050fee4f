"""Command line: python -m reference run --help

(LAMMPS against the reference, make validate, is python -m bench.validation:
it runs LAMMPS, which the reference does not.)"""

from __future__ import annotations

import sys

from analysis.text_table import format_table
from builder.cli import OneLineParser
from ground.checks import InPath
from ground.errors import InputError

from .integrators import SCHEMES
from .run import DT, ReferenceOptions, Unstable, run_reference


def parser() -> OneLineParser:
    """python -m reference's options."""
    parser = OneLineParser(
        prog="python -m reference", description="The reference implementation of the model (numpy)."
    )
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="run a scene folder (python -m builder scene)")
    run.add_argument(
        "scene",
        type=InPath("folder", ("scene.data", "scene.json")),
        help="folder with scene.data and scene.json",
    )
    run.add_argument("--integrator", choices=list(SCHEMES), default="forest-ruth")
    run.add_argument(
        "--dt", type=DT, default=1e-3, help=f"time step, {DT.describe()} (default: 1e-3)"
    )
    run.add_argument("--contact", choices=("segment", "pair"), default="segment")
    run.add_argument(
        "--rule",
        choices=("lever", "gradient"),
        default=None,
        help="segment contact only: lever rule (default) or explicit gradient",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        if args.rule is not None and args.contact != "segment":
            raise InputError(f"--rule applies to --contact segment only, got {args.contact}")
        options = ReferenceOptions(
            dt=args.dt,
            integrator=args.integrator,
            contact=args.contact,
            rule=args.rule or "lever",
        )
        result = run_reference(args.scene, options)
        print(format_table([result]))
    except (InputError, Unstable) as error:
        print(f"python -m reference: error: {error}", file=sys.stderr)
        return 2 if isinstance(error, InputError) else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
