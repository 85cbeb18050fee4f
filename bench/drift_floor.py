"""What sets the energy drift of rough impacts: the kinks of the contact distance.

    python bench/drift_floor.py [--workers 1] [--only verlet suzuki ...]

The nine rough scenes of make bench (reference/validate.py), each run by the
reference (numpy) with velocity Verlet and two fourth-order compositions
(Suzuki, Forest-Ruth) at several steps, recording the total energy at every
step and every change of a disk point's closest feature of the wall's
polyline (reference/trace.py); and by LAMMPS (velocity Verlet) at several
steps, for its drift. Each reference drift is split by the events of the
steps it arose in: kink crossings (two features equally close, over a valley
vertex: the distance has a kink there), smooth switches (a segment's interior
and its end), the cutoff, and steps without an event. For Verlet, each kink
crossing's error is also predicted from where in the step it fell, and the
impulse that those errors put on the disk gives their direct effect on e and
beta. Writes docs/benchmarks/drift_floor.md, .json and .png; the runs and
traces go to --out (resumable: finished runs are kept).
"""

from __future__ import annotations

import argparse
import json
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict
from pathlib import Path

import numpy as np

from bench.common import bench_parser, markdown_table, output_folder, write_report
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from ground.checks import OutFolder
from ground.gate import runs_folder, write_figure
from reference.run import ReferenceOptions
from reference.trace import event_kind, trace
from reference.validate import scenes
from runner.cluster.workers import WORKERS
from runner.impact import run_scene
from runner.options import RunOptions

SETTINGS = [("verlet", dt) for dt in (2e-3, 1e-3, 5e-4, 2.5e-4)]
SETTINGS += [("suzuki", dt) for dt in (2e-3, 1e-3, 5e-4)]
SETTINGS += [("forest-ruth", dt) for dt in (1e-3, 5e-4)]
SETTINGS += [("lammps", dt) for dt in (4e-3, 2e-3, 1e-3, 5e-4)]
FIGURE_SCENE = "random_g5.7"  # the energy against time, panel (a)
FIGURE_SETTING = ("verlet", 1e-3)
# Not chaotic: perturbations of 1e-9 R move e and beta by 1e-7 at most
# (docs/benchmarks/validation_table.md), so their e and beta converge with dt.
REGULAR_SCENES = ("square_g5.7", "square_g45")
CONVERGED = ("suzuki", 5e-4)
GROUPS = {
    "steep": lambda name: not name.endswith("g80.4"),
    "grazing": lambda name: name.endswith("g80.4"),
}


def label(kind: str, dt: float) -> str:
    return f"{'LAMMPS verlet' if kind == 'lammps' else 'reference ' + kind} dt={dt:g}"


def run_one(job: tuple) -> dict:
    """One scene at one setting: its drift, split by cause (reference only)."""
    spec, folder, kind, dt = job
    folder = Path(folder)
    write_scene(build_scene(spec), folder)
    if kind == "lammps":
        result = run_scene(folder, RunOptions(dt=dt))
        return {key: result[key] for key in ("e", "beta", "steps")} | {
            "drift": result["energy_drift"]
        }
    tr = trace(folder, ReferenceOptions(integrator=kind, dt=dt))
    row = tr.split()
    row.update(steps=len(tr.time) - 1, e=tr.e, beta=tr.beta)
    change = np.diff(tr.energy) / tr.ke0
    if tr.kink_predicted:
        steps = np.array([p[0] for p in tr.kink_predicted])
        predicted = np.array([p[1] for p in tr.kink_predicted]) / tr.ke0
        # steps with one kink crossing only, where the prediction is the whole change
        single = np.array([np.count_nonzero(steps == s) == 1 for s in steps])
        row["predicted_corr"] = float(
            np.corrcoef(predicted[single], change[steps[single] - 1])[0, 1]
        )
        row["predicted_kink"] = float(predicted.sum())
        impulse = np.array([p[2] for p in tr.kink_predicted]).sum(axis=0)
        vx, vy = tr.velocity_in
        radius = spec.radius
        row["de_direct"] = float(impulse[1] / (tr.disk_mass * abs(vy)))
        row["dbeta_direct"] = float(
            -(impulse[0] / tr.disk_mass + radius * impulse[2] / tr.disk_inertia) / vx
        )
    if (folder.parent.name, (kind, dt)) == (FIGURE_SCENE, FIGURE_SETTING):
        kink_steps = sorted({s for s, _, o, n in tr.events if event_kind(o, n) == "kink"})
        np.savez(
            folder / "trace.npz",
            time=tr.time,
            change=change,
            kink_steps=np.array(kink_steps, dtype=int),
        )
    return row


def measure(out: Path, workers: int, only: list[str] | None) -> dict:
    specs = scenes()
    partial = out / "rows.partial.json"
    these = {name: asdict(spec) for name, spec in specs.items()}
    saved = json.loads(partial.read_text()) if partial.exists() else {}
    done = saved.get("rows", {}) if saved.get("scenes") == these else {}
    jobs, keys = [], []
    for kind, dt in SETTINGS:
        if only and kind not in only:
            continue
        for name, spec in specs.items():
            key = f"{label(kind, dt)}|{name}"
            if key in done:
                continue
            tag = f"{kind}_dt{dt:g}"
            jobs.append((spec, out / name / tag, kind, dt))
            keys.append(key)
    with ProcessPoolExecutor(workers) as pool:
        for key, row in zip(keys, pool.map(run_one, jobs)):
            done[key] = row
            partial.write_text(json.dumps({"scenes": these, "rows": done}, indent=1))
            print(key, {k: f"{v:.3g}" for k, v in row.items()}, flush=True)
    return done


def rms(values) -> float:
    values = np.asarray(values, float)
    return float(np.sqrt(np.mean(values**2)))


def summary(rows: dict) -> list[dict]:
    out = []
    for kind, dt in SETTINGS:
        named = {k.split("|")[1]: r for k, r in rows.items() if k.split("|")[0] == label(kind, dt)}
        these = list(named.values())
        if not these:
            continue
        entry = {
            "label": label(kind, dt),
            "kind": kind,
            "dt": dt,
            "scenes": len(these),
            "rms_drift": rms([r["drift"] for r in these]),
            "max_drift": float(max(abs(r["drift"]) for r in these)),
        }
        if kind != "lammps":
            entry.update(
                rms_kink=rms([r["kink"] for r in these]),
                rms_walk=rms([r["kink_walk"] for r in these]),
                max_rest=float(max(abs(r["drift"] - r["kink"]) for r in these)),
                max_smooth=float(max(abs(r["smooth"]) for r in these)),
                max_cutoff=float(max(abs(r["cutoff"]) for r in these)),
                max_none=float(max(abs(r["none"]) for r in these)),
                kink_steps=float(np.median([r["kink_steps"] for r in these])),
            )
        # The systematic part: the mean drift of a group of scenes, against the
        # random walk's error of that mean, sqrt(sum of the walks^2) / n.
        for group, pick in GROUPS.items():
            chosen = [r for name, r in named.items() if pick(name)]
            entry[f"mean_{group}"] = float(np.mean([r["drift"] for r in chosen]))
            if kind != "lammps":
                walks = np.array([r["kink_walk"] for r in chosen])
                entry[f"walk_error_{group}"] = float(np.sqrt((walks**2).sum()) / len(chosen))
        if kind == "verlet":
            entry.update(
                min_corr=float(min(r["predicted_corr"] for r in these)),
                max_de=float(max(abs(r["de_direct"]) for r in these)),
                max_dbeta=float(max(abs(r["dbeta_direct"]) for r in these)),
            )
        out.append(entry)
    return out


def order(table: list[dict], kind: str, column: str) -> float:
    """Slope of log(column) against log(dt) over a family's steps."""
    rows = [r for r in table if r["kind"] == kind]
    if len(rows) < 2:
        return float("nan")
    return float(
        np.polyfit(np.log([r["dt"] for r in rows]), np.log([r[column] for r in rows]), 1)[0]
    )


def plot(table: list[dict], trace_file: Path, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    if trace_file.exists():
        data = np.load(trace_file)
        change, time = data["change"], data["time"]
        kink = np.zeros(len(change), bool)
        kink[data["kink_steps"] - 1] = True
        left.plot(time[1:], np.cumsum(change), label="total energy - initial")
        left.plot(
            time[1:],
            np.cumsum(np.where(kink, change, 0.0)),
            "--",
            label="steps with a kink crossing",
        )
        left.plot(time[1:], np.cumsum(np.where(kink, 0.0, change)), ":", label="all other steps")
        left.set_xlabel("time (R/c)")
        left.set_ylabel("energy change / initial kinetic energy")
        kind, dt = FIGURE_SETTING
        left.set_title(f"{FIGURE_SCENE}, reference {kind} dt={dt:g}", fontsize=9)
        left.legend(fontsize=8)
    for kind, marker in (("verlet", "o"), ("suzuki", "s"), ("forest-ruth", "^"), ("lammps", "x")):
        rows = [r for r in table if r["kind"] == kind]
        if rows:
            right.loglog(
                [r["dt"] for r in rows],
                [r["rms_drift"] for r in rows],
                marker + "-",
                label=("LAMMPS verlet" if kind == "lammps" else kind) + ": rms drift",
            )
    walk = [r for r in table if r["kind"] == "verlet"]
    if walk:
        dts = np.array([r["dt"] for r in walk])
        right.loglog(
            dts, [r["rms_walk"] for r in walk], "k.:", label="verlet: sqrt(sum of kink steps^2)"
        )
        scale = walk[0]["rms_walk"] / dts[0]
        right.loglog(dts, scale * dts, color="grey", lw=0.8, label="slope 1")
        right.loglog(
            dts,
            scale * dts[0] * (dts / dts[0]) ** 2,
            color="grey",
            lw=0.8,
            ls="--",
            label="slope 2",
        )
    steps = sorted({r["dt"] for r in table})
    right.set_xticks(steps, [f"{dt:g}" for dt in steps])
    right.minorticks_off()
    right.set_xlabel("dt (R/c)")
    right.set_ylabel("energy drift over nine rough scenes")
    right.legend(fontsize=7)
    fig.tight_layout()
    write_figure(fig, path, 110)


FAMILIES = ("verlet", "suzuki", "forest-ruth", "lammps")


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--out",
        type=OutFolder(),
        default=str(runs_folder() / "drift_floor"),  # a text, so that argparse checks it
        help="folder for the runs and their traces (default: runs/drift_floor)",
    )
    parser.add_argument(
        "--workers",
        type=WORKERS,
        default=1,
        help=f"runs at once, {WORKERS.describe()} (default: 1)",
    )
    parser.add_argument(
        "--only", nargs="+", choices=FAMILIES, default=None, help="only these families"
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = measure(out, args.workers, args.only)
    table = summary(rows)
    pages = output_folder(args.docs)
    (pages / "drift_floor.json").write_text(
        json.dumps({"summary": table, "rows": rows}, indent=1) + "\n"
    )
    plot(
        table,
        out / FIGURE_SCENE / f"{FIGURE_SETTING[0]}_dt{FIGURE_SETTING[1]:g}" / "trace.npz",
        pages / "drift_floor.png",
    )
    print(json.dumps(table, indent=1))
    command = "python bench/drift_floor.py" + (" --docs" if args.docs else "")
    print(
        write_report(
            "drift_floor",
            "What sets the energy drift of rough impacts",
            command,
            body(table, rows),
            args.docs,
        )
    )
    return 0


INTRO = (
    "Nine rough scenes (reference/validate.py: random, triangular and square disks at 5.7, 45 "
    "and 80.4 degrees, seed 1, on the default wall). Drift: the change of the total energy "
    "over the initial kinetic energy, signed; rms and largest over the nine. The reference "
    "books every step's energy change to the events of that step, seen at every force "
    "evaluation (reference/trace.py): *kink* if a disk point's closest feature of the wall's "
    "polyline changed across the medial axis (over a valley vertex: from one segment's "
    "interior to the next's), else *smooth switch* (a segment's interior and its end, where "
    "l is continuously differentiable), else *cutoff* (a point entering or leaving the "
    "range), else *no event*. A run's random-walk scale is the square root of the sum of its "
    "kink steps' squared changes: the size its drift would have if the crossings' errors were "
    "independent and of either sign. The direct |de| and |dbeta| are the impulse that "
    "Verlet's predicted kink errors put on the disk (fx, fy, torque), as a change of e and "
    "beta, before the contact responds to it."
)


def body(table: list[dict], rows: dict) -> str:
    lines = []
    for r in table:
        ref = r["kind"] != "lammps"
        lines.append(
            [
                r["label"],
                f"{r['rms_drift']:.1e}",
                f"{r['max_drift']:.1e}",
                f"{r['rms_kink']:.1e}" if ref else "",
                f"{r['max_rest']:.1e}" if ref else "",
                f"{r['max_smooth']:.0e}, {r['max_cutoff']:.0e}, {r['max_none']:.0e}" if ref else "",
                f"{r['kink_steps']:.0f}" if ref else "",
                f"{r['rms_walk']:.1e}" if ref else "",
            ]
        )
    text = (
        INTRO
        + "\n\n"
        + markdown_table(
            [
                "setting",
                "rms drift",
                "largest drift",
                "rms of the kink steps' sum",
                "largest rest (drift - kink steps)",
                "largest of: smooth switches, cutoff, no event",
                "kink steps (median)",
                "rms random-walk scale",
            ],
            lines,
        )
    )
    slopes = ", ".join(
        f"{kind} {order(table, kind, 'rms_drift'):.2f}"
        for kind in ("verlet", "suzuki", "forest-ruth", "lammps")
    )
    text += (
        f"\n\nOrder (slope of log rms drift against log dt): {slopes}; of the random-walk "
        f"scale, Verlet {order(table, 'verlet', 'rms_walk'):.2f}, Suzuki "
        f"{order(table, 'suzuki', 'rms_walk'):.2f}."
    )
    text += (
        "\n\nThe systematic part: the mean drift of the six scenes at 5.7 and 45 degrees, and "
        "of the three at 80.4, each +- the error that the kink steps' random walks give that "
        "mean (sqrt of the sum of their squared scales, over the number of scenes):\n\n"
    )
    text += markdown_table(
        ["setting", "mean drift, 5.7 and 45 degrees", "mean drift, 80.4 degrees"],
        [
            [r["label"]]
            + [
                f"{r[f'mean_{g}']:+.1e}"
                + (f" +- {r[f'walk_error_{g}']:.1e}" if f"walk_error_{g}" in r else "")
                for g in GROUPS
            ]
            for r in table
        ],
    )
    verlet = [r for r in table if r["kind"] == "verlet"]
    if verlet:
        text += "\n\n" + markdown_table(
            [
                "Verlet dt",
                "smallest correlation, predicted against actual kink-step change",
                "largest direct |de|",
                "largest direct |dbeta|",
            ],
            [
                [
                    f"{r['dt']:g}",
                    f"{r['min_corr']:.3f}",
                    f"{r['max_de']:.1e}",
                    f"{r['max_dbeta']:.1e}",
                ]
                for r in verlet
            ],
        )
    converged = {name: rows.get(f"{label(*CONVERGED)}|{name}") for name in REGULAR_SCENES}
    if all(converged.values()):
        lines = []
        for kind, dt in SETTINGS:
            cells = [label(kind, dt)]
            for name in REGULAR_SCENES:
                row = rows.get(f"{label(kind, dt)}|{name}")
                ref = converged[name]
                cells += (
                    [f"{row['e'] - ref['e']:+.1e}", f"{row['beta'] - ref['beta']:+.1e}"]
                    if row
                    else ["", ""]
                )
            lines.append(cells)
        header = ["setting"]
        for name in REGULAR_SCENES:
            ref = converged[name]
            header += [f"{name}: e - {ref['e']:.5f}", f"beta - {ref['beta']:.5f}"]
        text += (
            f"\n\ne and beta of the two scenes that are not chaotic, against "
            f"{label(*CONVERGED)}:\n\n" + markdown_table(header, lines)
        )
    scenes_ = sorted({k.split("|")[1] for k in rows})
    per = []
    for name in scenes_:
        cells = [name]
        for kind, dt in SETTINGS:
            row = rows.get(f"{label(kind, dt)}|{name}")
            cells.append(f"{row['drift']:+.1e}" if row else "")
        per.append(cells)
    text += "\n\nEach scene's drift:\n\n" + markdown_table(
        ["scene"] + [label(k, d).replace("reference ", "") for k, d in SETTINGS], per
    )
    text += "\n\n![drift against time and step](drift_floor.png)\n"
    return text


if __name__ == "__main__":
    sys.exit(main())
