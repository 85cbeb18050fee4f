"""Run time against error, with the resolution in it (issue 46), from a
resolution study's tables.

    python bench/resolution_error.py --docs
    python bench/resolution_error.py [--study NAME] [--rows CSV] [--timings CSV]
                                     [--out FOLDER] [--docs]

No runs: it reads a study's committed rows (docs/studies/NAME/rows.csv) and
each impact's LAMMPS seconds (timings.csv), the study's coupled reading on
the random disk: resolution_floor's ``profile-floor`` (the default: the model
with the barrier, whose limit exists) or resolution_profile's ``profile``.
For e near normal incidence (e_normal) and Walton's mu (measured way), the
limit Q_limit is analysis.kinds.resolution.limits over every level. Three
estimates at each finest level N, each with its error against Q_limit,
sqrt(bias^2 + stat^2), and the seconds actually spent on the levels it uses:

(a) one resolution alone: Q(N) with its seed error; the seconds of level N;
(b) the extrapolation: analysis.statistics.extrapolation.limit of the levels 800..N
    as measured, each on its own seeds (its statistical error; the forms' band
    is a column of its own); Q_limit for e is the extrapolation of (c)'s levels;
(c) the multilevel estimate: Q(800) + the per-seed differences paired by
    seed and angle up to N (analysis.statistics.levels.coupled_differences), its error
    the terms' errors summed in quadrature; e only (mu, a fit over the
    angles, has no per-seed value); the seconds of the levels 800..N.

For a target error T (analysis.kinds.resolution.TARGETS) the time needed scales the
seeds of every level used: stat ~ 1 / sqrt(seeds), so the time is
seconds * stat^2 / (T^2 - bias^2), and "never" where |bias| >= T.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from analysis.kinds import resolution
from analysis.statistics import extrapolation, levels
from bench.common import bench_parser, markdown_table, page_folder, refuse, write_report
from ground.checks import InPath
from ground.errors import InputError
from ground.gate import write_figure
from ground.paths import study_docs

# study -> (its reading, how loaded the machine was while its seconds were measured)
STUDIES = {
    "resolution_floor": (
        "profile-floor",
        "while the study ran on both cores of a shared 2-core machine, beside other "
        "jobs and benchmarks (load about 2 to 7)",
    ),
    "resolution_profile": ("profile", "on a shared 2-core machine under a load of 10 to 17"),
}
LATTICE = "random"
QUANTITIES = ("e_normal", "mu")


def parser():
    p = bench_parser(__file__, __doc__, out="resolution_error.md and .png")
    p.add_argument(
        "--study", choices=sorted(STUDIES), default="resolution_floor",
        help="the resolution study whose tables are read (default: resolution_floor)",
    )  # fmt: skip
    p.add_argument(
        "--rows", type=InPath("file"), default=None,
        help="the impacts' rows (default: docs/studies/STUDY/rows.csv)",
    )  # fmt: skip
    p.add_argument(
        "--timings", type=InPath("file"), default=None,
        help="each impact's seconds (default: docs/studies/STUDY/timings.csv)",
    )  # fmt: skip
    return p


def read(rows_csv: Path, timings_csv: Path, reading: str) -> list[dict]:
    """The reading's rows, each with its ``wall_seconds`` and ``atom_steps``."""
    key = ("reading", "study_lattice", "seed", "gamma_deg")
    with open(timings_csv) as f:
        seconds = {tuple(r[k] for k in key): float(r["wall_seconds"]) for r in csv.DictReader(f)}
    with open(rows_csv) as f:
        rows = [
            r for r in csv.DictReader(f) if r["limit"] == reading and r["study_lattice"] == LATTICE
        ]
    if not rows:
        raise InputError(f"--rows {rows_csv} has no rows of reading {reading} ({LATTICE})")
    for r in rows:
        r["wall_seconds"] = seconds.get(tuple(r[k] for k in key), 0.0)
        r["atom_steps"] = float(r["steps"]) * (float(r["n_disk"]) + float(r["n_wall_points"]))
    return rows


def spent(rows: list[dict], ns) -> tuple[float, float]:
    """(LAMMPS seconds, atom-steps) of every impact at the levels ``ns``."""
    mine = [r for r in rows if int(r["n_disk"]) in set(ns)]
    return sum(r["wall_seconds"] for r in mine), sum(r["atom_steps"] for r in mine)


def entry(method, n, ns, value, stat, reference, rows, target, band=None) -> dict:
    bias = value - reference
    seconds, atom_steps = spent(rows, ns)
    room = target**2 - bias**2
    return {
        "method": method,
        "n": n,
        "value": value,
        "bias": bias,
        "stat": stat,
        "error": math.hypot(bias, stat),
        "seconds": seconds,
        "atom_steps": atom_steps,
        "to_target": seconds * stat**2 / room if room > 0 else math.inf,
        "band": band,
    }


def estimates(rows: list[dict]) -> dict:
    """quantity -> {"limit": its limit over every level, "rows": the three
    estimates (module docstring) at each finest level}."""
    reading = rows[0]["limit"]  # read() keeps one reading
    summary = resolution.summaries(rows)
    limits = resolution.limits(summary, QUANTITIES, rows)
    out = {}
    for q in QUANTITIES:
        lim = limits[(reading, LATTICE, q)]
        target = resolution.TARGETS[q]
        out[q] = {"limit": lim, "target": target, "rows": []}
        if lim["status"] != "limit":
            continue
        reference = lim["value"]
        found = resolution.levels_of(summary, reading, LATTICE, q)
        ns = [n for n, _, _ in found if n >= extrapolation.FIT_FROM]
        table = out[q]["rows"]
        for n, value, sd in found:
            table.append(entry("one level", n, [n], value, sd, reference, rows, target))
        for i, n in enumerate(ns):
            fit = extrapolation.limit([x for x in found if x[0] in ns[: i + 1]])
            if fit["status"] == "limit":
                table.append(
                    entry(
                        "extrapolation",
                        n,
                        ns[: i + 1],
                        fit["value"],
                        fit["stat"],
                        reference,
                        rows,
                        target,
                        fit["band"],
                    )
                )
        if q in levels.GROUPS:
            steps = {d["n"]: d for d in levels.coupled_differences(resolution.finished(rows), q)}
            value, variance = found[0][1], found[0][2] ** 2
            for i, n in enumerate(ns[1:], start=1):
                if n not in steps:
                    break
                value += steps[n]["mean"]
                variance += steps[n]["se"] ** 2
                table.append(
                    entry(
                        "multilevel",
                        n,
                        ns[: i + 1],
                        value,
                        math.sqrt(variance),
                        reference,
                        rows,
                        target,
                    )
                )
    return out


def page(found: dict, study: str) -> str:
    reading, load = STUDIES[study]
    parts = [
        f"The {reading} reading's committed impacts (docs/studies/{study}/rows.csv, one "
        "surface per seed at every N, random disk) and their LAMMPS seconds "
        "(timings.csv); no new runs. **The seconds are upper bounds**: they were "
        f"measured {load}, so the atom-steps "
        "(steps times the disk's and the wall's points, summed over the impacts) are "
        "given beside them as the load-free measure of the work.",
        "Error = sqrt(bias^2 + stat^2) with bias = estimate - Q_limit (the limit from "
        "every level, whose own error is stated above each table), stat the estimate's "
        "seed error at the seeds run. Seconds and atom-steps: every impact of the levels "
        "the estimate uses. Time to target: the seconds with every level's seeds scaled "
        "so that stat^2 + bias^2 = target^2 (stat ~ 1 / sqrt(seeds)); never where "
        "|bias| >= target. (b)'s band: the describing forms' intercepts. (c) for e only: "
        "mu is a fit over the angles, with no per-seed value to pair. Q_limit is the "
        "resolution page's limit: for e, the extrapolation of the multilevel levels "
        "(each level as (c) gives it), so (c)'s bias is small by construction; (b) "
        "extrapolates the levels as measured, each on its own seeds (for mu, (b) at the "
        "finest level is Q_limit itself). A bias smaller than Q_limit's own errors is "
        "not told from zero. A quantity the page gives no limit (Walton's mu where the "
        "data bound it from below only: not identified) has no error to measure.",
    ]
    for q, label in resolution.QUANTITIES:
        if q not in found:
            continue
        lim, target = found[q]["limit"], found[q]["target"]
        head = f"## {label}\n\n"
        if lim["status"] != "limit":
            parts.append(head + f"No limit: {lim['status']}.")
            continue
        head += (
            f"Q_limit = {lim['value']:.4f} +- {lim['stat']:.4f} (stat) +- "
            f"{lim['systematic']:.4f} (forms' band), from N = "
            f"{', '.join(str(n) for n in lim['levels'])}. Target error {target:g}.\n\n"
        )
        table = [
            [
                r["method"],
                f"{r['n']:,}",
                f"{r['value']:.4f}",
                f"{r['bias']:+.4f}",
                f"{r['stat']:.4f}",
                f"{r['error']:.4f}",
                f"{r['seconds']:.0f}",
                f"{r['atom_steps']:.3g}",
                "never" if math.isinf(r["to_target"]) else f"{r['to_target']:.3g}",
                "" if r["band"] is None else f"{r['band'][0]:.4f} to {r['band'][1]:.4f}",
            ]
            for r in found[q]["rows"]
        ]
        columns = [
            "estimate",
            "finest N",
            "value",
            "bias",
            "stat",
            "error",
            "LAMMPS s",
            "atom-steps",
            "s to target",
            "(b) band",
        ]
        parts.append(head + markdown_table(columns, table))
    return "\n\n".join(parts)


def draw(found: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(found), figsize=(5 * len(found), 4))
    for ax, (q, entry_) in zip(axes, found.items(), strict=True):
        for method, marker in (("one level", "o"), ("extrapolation", "s"), ("multilevel", "^")):
            mine = [r for r in entry_["rows"] if r["method"] == method]
            if mine:
                ax.loglog(
                    [r["seconds"] for r in mine],
                    [r["error"] for r in mine],
                    marker=marker,
                    label=method,
                )
        ax.axhline(entry_["target"], color="grey", lw=0.8, ls="--")
        ax.set(xlabel="LAMMPS seconds (loaded machine)", ylabel="error against the limit", title=q)
        if entry_["rows"]:  # a quantity with no limit (mu not identified) has none
            ax.legend()
    fig.tight_layout()
    write_figure(fig, path, 100)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        tables = study_docs(args.study)
        rows = read(
            args.rows or tables / "rows.csv",
            args.timings or tables / "timings.csv",
            STUDIES[args.study][0],
        )
    except InputError as error:
        return refuse(__file__, error)
    found = estimates(rows)
    folder = page_folder(args)
    folder.mkdir(parents=True, exist_ok=True)
    write_report(
        "resolution_error",
        "Run time against error, with the resolution in it",
        "python bench/resolution_error.py"
        + ("" if args.study == "resolution_floor" else f" --study {args.study}")
        + (" --docs" if args.docs else ""),
        page(found, args.study) + "\n\n![error against seconds](resolution_error.png)",
        folder=folder,
    )
    draw(found, folder / "resolution_error.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
