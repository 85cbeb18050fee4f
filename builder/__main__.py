"""Command line: python -m builder {scene,table} --help"""

from __future__ import annotations

import sys
from pathlib import Path

from .cli import OneLineParser, add_scene_arguments, count, positive_float, spec_from_args
from .contact_table import POINTS, table_name, table_text
from .errors import BuildError, InputError
from .lammps_data import DEFAULT_SPRINGS, SPRING_STYLES, write_scene
from .scene import build_scene


def main(argv: list[str] | None = None) -> int:
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
    scene.add_argument("--out", required=True, help="folder to write into")

    table = commands.add_parser(
        "table",
        help="write the pair-variant contact table",
        description="Tabulate E = V0 exp(-a r) for pair_style table.",
    )
    table.add_argument("--a", type=positive_float, default=300.0, help="decay rate (default: 300)")
    table.add_argument(
        "--v0", type=positive_float, default=150.0, help="energy scale (default: 150)"
    )
    table.add_argument(
        "--points", type=count(100), default=POINTS, help=f"points in the table (default: {POINTS})"
    )
    table.add_argument("--out", required=True, help="folder to write into")

    args = parser.parse_args(argv)
    try:
        if args.command == "scene":
            folder = write_scene(build_scene(spec_from_args(args)), args.out, args.springs)
            print(f"wrote {folder}/scene.data, scene.lmp, scene.json")
        else:
            path = Path(args.out) / table_name(args.a, args.v0)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(table_text(args.a, args.v0, points=args.points))
            print(f"wrote {path}")
    except (InputError, BuildError) as error:
        print(f"python -m builder: error: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
