"""The tail of the energy drift: a study's worst impacts again at other steps.

    python bench/drift_tail.py --impacts runs/paper/impacts.csv [--worst 24]
                               [--dts 0.003 0.002 0.001]

make bench chooses the time step on nine scenes; a study has thousands, and a
few of them drift far more than those nine. This takes the impacts of a study
with the largest |energy drift| and runs each again at every step given (the
study's settings otherwise), for how the tail shrinks with the step. The
table gives each impact's drift per step and, per step, the median, the
largest and how many are above 5e-3 (make bench's criterion) and above the
accuracy guard's 0.05. Writes docs/benchmarks/drift_tail.md.
"""

from __future__ import annotations

import argparse
import csv
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np
from common import markdown_table, write_report

from analysis.result import MAX_DRIFT
from builder.lammps_data import write_scene
from builder.scene import build_scene
from runner.impact import run_scene
from runner.study import PRESETS

ENERGY_TOLERANCE = 5e-3  # make bench's criterion on rough scenes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--impacts", type=Path, required=True, help="a study's impacts.csv")
    parser.add_argument("--worst", type=int, default=24, help="impacts to rerun (default: 24)")
    parser.add_argument("--dts", type=float, nargs="+", default=[0.003, 0.002, 0.001])
    args = parser.parse_args()

    with args.impacts.open() as handle:
        rows = sorted(csv.DictReader(handle), key=lambda r: -abs(float(r["energy_drift"])))
    worst = rows[: args.worst]
    study = PRESETS["paper"]
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
    )
    print(f"wrote {write_report('drift_tail', 'The tail of the energy drift', command, body)}")


if __name__ == "__main__":
    main()
