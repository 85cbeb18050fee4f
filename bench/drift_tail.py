"""The tail of the energy drift: a study's worst impacts again at other steps.

    python bench/drift_tail.py --impacts runs/paper/impacts.csv [--worst 24]
                               [--dts 0.003 0.002 0.001] [--docs]

make bench chooses the time step on nine scenes; a study has thousands, and a
few of them drift far more than those nine. This takes the impacts of a study
with the largest |energy drift| and runs each again at every step given (the
study's settings otherwise), for how the tail shrinks with the step. The
table gives each impact's drift per step and, per step, the median, the
largest and how many are above 5e-3 (make bench's criterion) and above the
accuracy guard's 0.05. Writes runs/bench/drift_tail.md (--docs: the committed
docs/benchmarks/drift_tail.md).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

from analysis.impact.result import MAX_DRIFT
from bench.common import bench_parser, distinct, markdown_table, refuse, write_report
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import ANGLE, SEED
from ground.checks import InPath, Range
from ground.errors import InputError
from runner.impact import run_scene
from runner.options import DT
from runner.study import LATTICES
from runner.study.studies import load_study

ENERGY_TOLERANCE = 5e-3  # make bench's criterion on rough scenes
WORST = Range(1, 10_000, integer=True)
COLUMNS = ("study_lattice", "seed", "gamma_deg", "energy_drift", "dt")


def read_impacts(path: Path) -> list[dict]:
    """The rows of a study's impacts.csv, worst |energy drift| first; a file that
    is not one (a missing column, an unknown lattice, a value that is not a
    finite number) is refused, naming --impacts."""
    with path.open(newline="") as handle:
        reader = csv.DictReader(handle)
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            raise InputError(f"--impacts: {path} has no column {', '.join(missing)}")
        rows = list(reader)
    for line, row in enumerate(rows, start=2):
        if row["study_lattice"] not in LATTICES:
            raise InputError(
                f"--impacts: {path} line {line}: lattice {row['study_lattice']!r} is not one of "
                + ", ".join(LATTICES)
            )
        try:
            good = (
                SEED.contains(int(row["seed"]))
                and ANGLE.contains(float(row["gamma_deg"]))
                and all(math.isfinite(float(row[c])) for c in ("energy_drift", "dt"))
            )
        except ValueError:
            good = False
        if not good:
            raise InputError(
                f"--impacts: {path} line {line}: its seed, angle, drift or dt is out of range"
            )
    return sorted(rows, key=lambda r: -abs(float(r["energy_drift"])))


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--impacts", type=InPath("file"), required=True, help="a study's impacts.csv"
    )
    parser.add_argument(
        "--worst",
        type=WORST,
        default=24,
        help=f"impacts to rerun, {WORST.describe()}, at most the study's (default: 24)",
    )
    parser.add_argument(
        "--dts",
        type=DT,
        nargs="+",
        default=[0.003, 0.002, 0.001],
        help=f"time steps, each {DT.describe()} (default: 0.003 0.002 0.001)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--dts", args.dts)
        rows = read_impacts(args.impacts)
        if args.worst > len(rows):
            raise InputError(f"--worst must be at most the {len(rows)} impacts of {args.impacts}")
    except InputError as error:
        return refuse(__file__, error)
    worst = rows[: args.worst]
    study = load_study("paper")
    drift = np.zeros((len(worst), len(args.dts)))
    with tempfile.TemporaryDirectory() as tmp:
        for i, row in enumerate(worst):
            job = {
                "lattice": row["study_lattice"],
                "seed": int(row["seed"]),
                "gamma": float(row["gamma_deg"]),
            }
            folder = write_scene(
                build_scene(study.spec(job)), Path(tmp) / "scene", study.options.springs
            )
            for j, dt in enumerate(args.dts):
                result = run_scene(folder, replace(study.options, dt=dt))
                drift[i, j] = abs(result["energy_drift"])
            print(job, " ".join(f"{d:.1e}" for d in drift[i]), flush=True)

    table = [
        [
            r["study_lattice"],
            r["seed"],
            f"{float(r['gamma_deg']):g}",
            *(f"{d:.1e}" for d in drift[i]),
        ]
        for i, r in enumerate(worst)
    ]
    for name, value in (("median", np.median(drift, axis=0)), ("largest", drift.max(axis=0))):
        table.append([f"**{name}**", "", "", *(f"{v:.1e}" for v in value)])
    for name, bound in (
        (f"above {ENERGY_TOLERANCE:g}", ENERGY_TOLERANCE),
        (f"above {MAX_DRIFT:g}", MAX_DRIFT),
    ):
        table.append([f"**{name}**", "", "", *(str(int(n)) for n in (drift > bound).sum(axis=0))])
    study_dts = ", ".join(sorted({f"{float(r['dt']):g}" for r in rows}))
    body = (
        f"The {args.worst} impacts of `{args.impacts}` ({len(rows)} impacts, run at dt = "
        f"{study_dts}) with the largest |energy drift| (the change of the total energy over "
        "the initial kinetic energy), each run again at every step, with the study's other "
        "settings.\n\n"
        + markdown_table(["lattice", "seed", "gamma", *(f"dt = {dt:g}" for dt in args.dts)], table)
    )
    print(body)
    command = (
        f"python bench/drift_tail.py --impacts {args.impacts} --worst {args.worst} --dts "
        + " ".join(f"{dt:g}" for dt in args.dts)
        + (" --docs" if args.docs else "")
    )
    title = "The tail of the energy drift"
    print(f"wrote {write_report('drift_tail', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
