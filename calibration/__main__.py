"""Command line: python -m calibration {run,strip} --help"""

from __future__ import annotations

import sys
from pathlib import Path

from builder.cli import OneLineParser, count, positive_float
from builder.errors import InputError
from builder.strips import StripSpec

from .stretch import ROOT, run_stretch
from .table import calibrate, markdown

DOC = ROOT / "docs" / "materials.md"


def write_doc(table: dict) -> None:
    DOC.write_text(
        "# Materials\n\n"
        f"Measured by `{table['command']}` ({table['date']}, LAMMPS {table['lammps']}, "
        f"revision {table['git_revision']}); the numbers are in `calibration/materials.json`, "
        "which the builder reads. How they are measured: docs/calibration.md.\n\n"
        f"{markdown(table)}\n\n"
        "c^2 and nu of the inner part of each strip (the bulk), +- the standard error of the "
        "mean over strips, sd the spread between strips. E = c^2 rho with rho the number "
        "density from Voronoi cells. Theory: exact for the triangular lattice, the continuum "
        "limit (MODEL.md's formula for nu) for the square lattice. Nonlinearity: the quadratic "
        "term of stress against strain, relative to the linear one, at the largest strain.\n"
    )


def main(argv: list[str] | None = None) -> int:
    parser = OneLineParser(
        prog="python -m calibration", description="Stretch lattice strips and measure E, nu and c."
    )
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser(
        "run",
        help="calibrate every lattice of the study: "
        "calibration/materials.json and docs/materials.md",
    )
    run.add_argument("--seeds", type=count(2), default=12, help="random strips (default: 12)")
    run.add_argument(
        "--square",
        type=positive_float,
        action="append",
        default=[],
        help="also calibrate a square lattice with this k2/k1 (repeatable)",
    )
    strip = commands.add_parser("strip", help="stretch one strip and print what it gives")
    strip.add_argument("--lattice", choices=("random", "triangular", "square"), default="random")
    strip.add_argument("--seed", type=count(0), default=1)
    strip.add_argument("--k2-over-k1", type=positive_float, default=3.0 / 7.0)
    strip.add_argument("--angle", type=float, default=0.0, help="lattice axes to the pull, degrees")
    strip.add_argument("--out", required=True, help="folder for the strip and its log")
    args = parser.parse_args(argv)
    try:
        if args.command == "run":
            table = calibrate(args.seeds, tuple(args.square))
            write_doc(table)
            print(markdown(table))
        else:
            spec = StripSpec(args.lattice, args.seed, args.k2_over_k1, args.angle)
            r = run_stretch(spec, Path(args.out))
            print(
                f"c^2 = {r.c2:.6f} ka d^2/m  nu = {r.nu:.4f}  E = {r.e_modulus:.5f} ka  "
                f"(strip as a whole: c^2 = {r.c2_strip:.5f}, nu = {r.nu_gauge:.4f}; "
                f"nonlinearity {r.nonlinearity:.1e}, grip imbalance {r.imbalance:.1e})"
            )
    except InputError as error:
        print(f"python -m calibration: error: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
