"""How the paper's facts move with the impact speed and the roughness, around one reading.

    python bench/fact_sensitivity.py [--wall W] [--model M] [--samples 12] [--angles 8]
                                     [--workers 2] [--docs | --out FOLDER]
    python bench/fact_sensitivity.py --from-csv [--docs | --out FOLDER]

Around a reading of bench/model_readings.py (a wall and a reading of the
model; default: the default scene's), the random disk at v_n = 0.05, 0.1 and
0.2 (in the reading's unit) with the roughness at 0.03 R, and at roughness
0.015, 0.03 and 0.06 R with v_n = 0.1: one study each (runner/study.py,
resumable), in runs/fact_sensitivity/. For each, e (mean over cot gamma >=
1), Walton's mu and beta0 fitted the paper's way (e 0.8, K 3), each with its
seed-bootstrap error (analysis.estimates, analysis.claims), and one figure of
how they move. These are the paper's stated values, not readings: the figure
shows how sensitive each fact is to them.

The rows go to fact_sensitivity.csv beside the page after every study; with
--docs a run skips the seeds the committed rows hold.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import bench.model_readings as readings
from analysis.claims import claims
from analysis.estimates import study_estimates
from analysis.table import write_csv
from bench.common import (
    DOCS,
    bench_parser,
    markdown_table,
    page_folder,
    read_rows_csv,
    refuse,
    study_rows,
    write_report,
)
from builder.errors import InputError
from runner.clusters import WORKERS
from runner.driver import run_study
from runner.study import ANGLES, SAMPLES, runs_folder

RUNS = runs_folder() / "fact_sensitivity"
ROWS_CSV = DOCS / "fact_sensitivity.csv"
FIGURE_NAME = "fact_sensitivity.png"
BASE_VN, BASE_ROUGHNESS = 0.1, 0.03
VNS = (0.05, 0.1, 0.2)
ROUGHNESSES = (0.015, 0.03, 0.06)
# (vn, roughness) of every study: the base is shared by both axes
POINTS = tuple(
    dict.fromkeys([(v, BASE_ROUGHNESS) for v in VNS] + [(BASE_VN, r) for r in ROUGHNESSES])
)
FACTS = readings.FACTS[:3]  # e, mu, beta0
KEEP_COLUMNS = (*readings.KEEP_COLUMNS, "roughness", "study_reading")


class SensitivityStudy(readings.ReadingStudy):
    @property
    def folder(self) -> Path:
        return RUNS / self.name


def point_label(point: tuple[float, float]) -> str:
    return f"vn{point[0]:g}_roughness{point[1]:g}"


def study_for(reading, point, samples: int, args, first_seed: int = 1) -> SensitivityStudy:
    base = readings.study_for(reading, "random", samples, args, first_seed)
    fields = {k: getattr(base, k) for k in base.__dataclass_fields__ if k != "name"}
    fields.update(vn=point[0], roughness=point[1])
    return SensitivityStudy(f"{base.name}_{point_label(point)}", **fields)


def facts(rows: list[dict]) -> dict | None:
    """The counts of a point's impacts, and its facts if it has three angles or more."""
    if not rows:
        return None
    done = [r for r in rows if not r.get("error")]
    out = {"impacts": len(rows), "failed": len(rows) - len(done)}
    if len({r["gamma_deg"] for r in done}) < 3:
        return out
    table = claims(study_estimates(done, compliant=False)[0])
    for name, number in readings.fact_numbers(table, FACTS).items():
        out[name] = (number["value"], number["error"]) if number else (float("nan"),) * 2
    return out


def draw(summaries: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(FACTS), 2, figsize=(9, 7.5), sharex="col")
    for column, (axis, values, fixed) in enumerate(
        (
            ("v_n, in units of the reading's speed unit", VNS, lambda v: (v, BASE_ROUGHNESS)),
            ("roughness, R", ROUGHNESSES, lambda r: (BASE_VN, r)),
        )
    ):
        for row, (name, _, _, paper) in enumerate(FACTS):
            ax = axes[row][column]
            shown = [
                (v, summaries[fixed(v)][name])
                for v in values
                if name in (summaries.get(fixed(v)) or {})
            ]
            if shown:
                ax.errorbar(
                    [v for v, _ in shown],
                    [f[0] for _, f in shown],
                    [f[1] for _, f in shown],
                    marker="o",
                    capsize=3,
                )
            ax.axhline(paper, color="grey", lw=0.8)
            ax.set_xscale("log")
            ax.set_xticks(values, [f"{v:g}" for v in values])
            ax.minorticks_off()
            ax.set_ylabel(name)
            if row == len(FACTS) - 1:
                ax.set_xlabel(axis)
    fig.suptitle(
        "Random disk: the paper's facts against its stated speed and roughness\n"
        "(error bars: seed-bootstrap sd, with the fit's systematic error where it fails; "
        "grey: the paper's values)"
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def page(rows: list[dict], reading, args) -> tuple[str, dict]:
    summaries = {
        point: facts([r for r in rows if r["reading"] == point_label(point)]) for point in POINTS
    }
    header = ["v_n", "roughness, R", "impacts", "failed", *(name for name, *_ in FACTS)]
    table = []
    for point in POINTS:
        s = summaries[point]
        cells = [f"{point[0]:g}", f"{point[1]:g}"]
        if s is None:
            table.append(cells + ["-"] * (len(header) - 2))
            continue
        cells += [str(s["impacts"]), str(s["failed"])]
        cells += [f"{s[n][0]:.3f} +- {s[n][1]:.3f}" if n in s else "-" for n, *_ in FACTS]
        table.append(cells)
    body = (
        f"Random disk (800 points) on wall `{reading[0]}`, model `{reading[1]}` "
        f"(bench/model_readings.py), {args.angles} angles from 5.7 to 80.5 degrees, seeds 1 "
        f"to {args.samples}, Verlet at dt = {readings.RUN_OPTIONS.dt:g} R/c. **e**: mean over "
        "cot gamma >= 1 (paper 0.8); "
        "**mu**, **beta0**: Walton's fit the paper's way, e 0.8 and K 3 (paper 0.18, 0.56). "
        "Each value +- its error: the seed-bootstrap sd, combined with the fit's systematic "
        "error where its reduced chi^2 is above the limit (analysis.claims).\n\n"
        + markdown_table(header, table)
        + f"\n\n![the facts against v_n and the roughness]({FIGURE_NAME})\n\n"
        "One row per impact: `fact_sensitivity.csv` (`python bench/fact_sensitivity.py "
        "--from-csv --docs` makes this page and the figure again from it).\n"
    )
    return body, summaries


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__, out="the page, figure and rows")
    parser.add_argument(
        "--wall",
        choices=tuple(readings.WALLS),
        default=None,
        help="the reading's wall (default: the default scene's)",
    )
    parser.add_argument(
        "--model",
        choices=tuple(readings.MODELS),
        default=None,
        help="the reading of the model (default: the default scene's)",
    )
    parser.add_argument(
        "--samples", type=SAMPLES, default=None, help=f"seeds, {SAMPLES.describe()} (default: 12)"
    )
    parser.add_argument(
        "--angles", type=ANGLES, default=None, help=f"angles, {ANGLES.describe()} (default: 8)"
    )
    parser.add_argument(
        "--workers", type=WORKERS, default=None, help=f"workers, {WORKERS.describe()} (default: 2)"
    )
    parser.add_argument(
        "--from-csv", action="store_true", help=f"only the page, from the committed {ROWS_CSV.name}"
    )
    return parser


def check(args: argparse.Namespace) -> None:
    if args.from_csv:
        given = [n for n in ("wall", "model", "samples", "angles", "workers") if getattr(args, n)]
        if given:
            raise InputError(f"--{given[0]} does not apply with --from-csv (its rows give them)")
        if not ROWS_CSV.is_file():
            raise InputError(f"--from-csv: {ROWS_CSV} is missing")
        return
    wall, model = readings.current_default()
    args.wall = args.wall or wall
    args.model = args.model or model
    args.samples = args.samples or 12
    args.angles = args.angles or 8
    args.workers = args.workers or 2
    for point in POINTS:
        study_for((args.wall, args.model), point, args.samples, args).validate()


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        check(args)
    except InputError as error:
        return refuse(__file__, error)
    folder = page_folder(args)
    folder.mkdir(parents=True, exist_ok=True)
    committed = read_rows_csv(ROWS_CSV) if ROWS_CSV.is_file() else []
    if args.from_csv:
        rows = committed
        first = rows[0]["study_reading"].split("/") if rows else ["-", "-"]
        args.wall, args.model = first
        args.angles = len({r["gamma_deg"] for r in rows})
        args.samples = max(int(r["seed"]) for r in rows)
    else:
        reading = (args.wall, args.model)
        rows = committed if args.docs else []
        if rows and rows[0]["study_reading"] != readings.label(reading):
            raise SystemExit(
                f"python bench/fact_sensitivity.py: error: --docs: {ROWS_CSV} holds "
                f"{rows[0]['study_reading']}, not {readings.label(reading)}; remove it first"
            )
        for point in POINTS:
            have = readings.seeds_done(rows, point_label(point), "random", args.angles)
            if have >= args.samples:
                continue
            study = study_for(reading, point, args.samples - have, args, first_seed=have + 1)
            run_study(study, args.workers)
            new = study_rows(study, point_label(point))
            for row in new:
                row["vn"], row["roughness"] = point
                row["study_reading"] = readings.label(reading)
            rows = [
                r for r in rows if r["reading"] != point_label(point) or int(r["seed"]) <= have
            ] + new
            write_csv(rows, folder / ROWS_CSV.name, KEEP_COLUMNS)
    body, summaries = page(rows, (args.wall, args.model), args)
    draw(summaries, folder / FIGURE_NAME)
    print(body)
    command = (
        f"python bench/fact_sensitivity.py --wall {args.wall} --model {args.model} "
        f"--samples {args.samples} --angles {args.angles}"
    )
    if args.docs or args.from_csv:
        command += " --docs"
    path = write_report(
        "fact_sensitivity",
        "How the facts move with speed and roughness",
        command,
        body,
        folder=folder,
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
