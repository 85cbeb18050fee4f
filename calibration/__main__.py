"""Command line: python -m calibration {run,strip} --help"""

from __future__ import annotations

import sys
from pathlib import Path

from builder.cli import OneLineParser
from builder.materials import TABLE
from builder.scene import K2_OVER_K1, SEED
from builder.strips import StripSpec
from ground import gate
from ground.checks import OutFolder, Range, require_out_folder
from ground.errors import InputError, clipped
from ground.gate import runs_folder
from ground.paths import DOCS

from .stretch import run_stretch
from .table import calibrate, markdown

DOC = DOCS / "calibration" / "materials.md"
STRIPS = Range(2, 1_000, integer=True)
PULL_ANGLE = Range(-180.0, 180.0, unit="degrees")


def write_doc(table: dict, path: Path = DOC) -> None:
    gate.write_text(
        path,
        "# Materials\n\n"
        f"Measured by `{table['command']}` ({table['date']}, LAMMPS {table['lammps']}, "
        f"revision {table['git_revision']}); the numbers are in `calibration/materials.json`, "
        "which the builder reads. How they are measured: docs/calibration.md.\n\n"
        f"{markdown(table)}\n\n"
        "c^2 and nu of the inner part of each strip (the bulk), +- the standard error of the "
        "mean over strips, sd the spread between strips. E = c^2 rho with rho the number "
        "density from Voronoi cells. Theory: exact for the triangular lattice, the continuum "
        "limit (docs/model.md's formula for nu) for the square lattice. Nonlinearity: the "
        "quadratic term of stress against strain, relative to the linear one, at the largest "
        "strain.\n\n"
        "The second table: shear modulus G and 2-D bulk modulus B in units of ka (force per "
        "length), measured (the closed form in parentheses). A strip pulled at angle a gives "
        "E / (2 (1 + nu)), the shear modulus of the frame turned by a + 45 degrees, and "
        "E / (2 (1 - nu)) = B: exact for pulls along the mirror lines of a lattice whose "
        "elastic constants repeat every 90 degrees, and for an isotropic one. So the strip at "
        "45 degrees gives G of the axes' frame (shear along the axes: C66 = k2 for the square "
        "lattice), the axial strip G of the 45-degree frame ((C11 - C12) / 2 = k1 / 2). The "
        "random lattice is pulled along x only: its sampler has no direction, so it is "
        "isotropic by construction and has one G (+- the standard error over its strips). "
        "c = sqrt(E / rho) along each direction; the study's unit is c along the axes, "
        "which are the wall's normal and tangent, so G / (rho c^2) and B / (rho c^2) are G "
        "and B in the study's units (G / (rho c^2) is the shear wave speed squared over c^2), "
        "beside G of an isotropic solid of the axial nu, 1 / (2 (1 + nu)).\n",
    )


def parser() -> OneLineParser:
    """python -m calibration's options."""
    parser = OneLineParser(
        prog="python -m calibration", description="Stretch lattice strips and measure E, nu and c."
    )
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser(
        "run",
        help="calibrate every lattice of the study: "
        "calibration/materials.json and docs/calibration/materials.md",
    )
    run.add_argument(
        "--seeds",
        type=STRIPS,
        default=12,
        help=f"random strips, {STRIPS.describe()} (default: 12)",
    )
    run.add_argument(
        "--square",
        type=K2_OVER_K1,
        action="append",
        default=[],
        help=f"also calibrate a square lattice with this k2/k1, {K2_OVER_K1.describe()} "
        "(repeatable)",
    )
    run.add_argument(
        "--out",
        type=OutFolder(),
        default=None,
        help="folder for materials.json and materials.md (default: runs/calibration)",
    )
    run.add_argument(
        "--install",
        action="store_true",
        help="write calibration/materials.json, which every scene reads, and "
        "docs/calibration/materials.md instead (make calibrate does)",
    )
    strip = commands.add_parser("strip", help="stretch one strip and print what it gives")
    strip.add_argument("--lattice", choices=("random", "triangular", "square"), default="random")
    strip.add_argument(
        "--seed", type=SEED, default=1, help=f"sample seed, {SEED.describe()} (default: 1)"
    )
    strip.add_argument(
        "--k2-over-k1",
        type=K2_OVER_K1,
        default=None,
        help=f"square lattice only: {K2_OVER_K1.describe()} (default: 3/7)",
    )
    strip.add_argument(
        "--angle",
        type=PULL_ANGLE,
        default=0.0,
        help=f"lattice axes to the pull, {PULL_ANGLE.describe()} (default: 0)",
    )
    strip.add_argument(
        "--out", type=OutFolder(), required=True, help="folder for the strip and its log"
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        if args.command == "run":
            if args.install and args.out is not None:
                raise InputError("--out does not apply to --install, which writes into the clone")
            if not args.install:
                args.out = require_out_folder("--out", args.out or runs_folder() / "calibration")
            table_path, doc = (
                (TABLE, DOC)
                if args.install
                else (args.out / "materials.json", args.out / "materials.md")
            )
            if args.install:  # make calibrate: the committed table and its page, granted
                gate.grant(TABLE, DOC)
            gate.make_folder(table_path.parent, "--out")
            table = calibrate(args.seeds, tuple(args.square), path=table_path)
            write_doc(table, doc)
            print(markdown(table))
            print(f"wrote {table_path} and {doc}")
        else:
            if args.k2_over_k1 is not None and args.lattice != "square":
                raise InputError(
                    f"--k2-over-k1 applies to --lattice square only, got {args.lattice}"
                )
            if args.angle != 0.0 and args.lattice == "random":
                raise InputError("--angle applies to the regular lattices only, got random")
            ratio = args.k2_over_k1 if args.k2_over_k1 is not None else 3.0 / 7.0
            spec = StripSpec(args.lattice, args.seed, ratio, args.angle)
            r = run_stretch(spec, Path(args.out))
            print(
                f"c^2 = {r.c2:.6f} ka d^2/m  nu = {r.nu:.4f}  E = {r.e_modulus:.5f} ka  "
                f"(strip as a whole: c^2 = {r.c2_strip:.5f}, nu = {r.nu_gauge:.4f}; "
                f"nonlinearity {r.nonlinearity:.1e}, grip imbalance {r.imbalance:.1e})"
            )
    except InputError as error:
        print(f"python -m calibration: error: {clipped(str(error))}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
