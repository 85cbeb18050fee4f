"""Command line: python -m builder {scene,table} --help"""

from __future__ import annotations

import sys
from pathlib import Path

from ground.checks import OutFolder, Range
from ground.errors import BuildError, InputError, clipped, os_error_line
from ground.gate import environment_paths, make_folder, write_text

from .assembly import build_scene
from .cli import OneLineParser, add_scene_arguments, spec_from_args, validate_spec
from .contact_table import POINTS, table_name, table_text
from .lammps_data import DEFAULT_SPRINGS, SPRING_STYLES, write_scene

# The table's numbers: a contact whose force has not died out at the table's
# outer end, or has underflowed at its inner one, is not the model's.
TABLE_A = Range(1.0, 10_000.0, unit="per R")
TABLE_V0 = Range(0.0, 1e8, low_open=True, unit="energy, m c^2")
TABLE_POINTS = Range(100, 10_000_000, integer=True)


def parser() -> OneLineParser:
    """python -m builder's options."""
    parser = OneLineParser(
        prog="python -m builder", description="Build lattices and write LAMMPS data files."
    )
    commands = parser.add_subparsers(dest="command", required=True)

    scene = commands.add_parser(
        "scene",
        help="write scene.data, scene.lmp and scene.json",
        description="Build a disk and a wall placed for an oblique "
        "impact and write them for decks/impact.lmp.",
    )
    add_scene_arguments(scene)
    scene.add_argument(
        "--springs",
        choices=SPRING_STYLES,
        default=DEFAULT_SPRINGS,
        help="bond style: harmonic/quartic (the model's quartic springs, the "
        "project's own style; default), class2 (the same springs, LAMMPS's "
        "built-in style) or harmonic (no quartic)",
    )
    scene.add_argument(
        "--out", type=OutFolder(), required=True, help="folder to write into (created if missing)"
    )

    table = commands.add_parser(
        "table",
        help="write the pair-variant contact table",
        description="Tabulate E = V0 exp(-a r) for pair_style table.",
    )
    table.add_argument(
        "--a", type=TABLE_A, default=300.0, help=f"decay rate, {TABLE_A.describe()} (default: 300)"
    )
    table.add_argument(
        "--v0",
        type=TABLE_V0,
        default=150.0,
        help=f"energy scale, {TABLE_V0.describe()} (default: 150)",
    )
    table.add_argument(
        "--points",
        type=TABLE_POINTS,
        default=POINTS,
        help=f"points in the table, {TABLE_POINTS.describe()} (default: {POINTS})",
    )
    table.add_argument(
        "--out", type=OutFolder(), required=True, help="folder to write into (created if missing)"
    )

    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        environment_paths()
        if args.command == "scene":
            spec = spec_from_args(args)
            validate_spec(spec)  # every value checked before anything is built or written
            folder = write_scene(build_scene(spec), args.out, args.springs)
            print(f"wrote {folder}/scene.data, scene.lmp, scene.json")
        else:
            path = Path(args.out) / table_name(args.a, args.v0)
            make_folder(path.parent, "--out")
            write_text(path, table_text(args.a, args.v0, points=args.points))
            print(f"wrote {path}")
    except (InputError, BuildError) as error:
        print(f"python -m builder: error: {clipped(str(error))}", file=sys.stderr)
        return 2
    except OSError as error:  # a full disk, a read-only folder
        print(f"python -m builder: error: {os_error_line(error)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
