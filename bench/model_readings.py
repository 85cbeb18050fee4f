"""The readings of the model crossed with the best readings of the wall (MODEL.md section 8).

    python bench/model_readings.py [--samples 12] [--angles 8] [--top 5 [--top-samples 30]]
                                   [--workers 2] [--docs | --out FOLDER]
    python bench/model_readings.py --from-csv [--docs | --out FOLDER]
                                   # the page from the committed rows only

A reading is a wall (the five best of docs/benchmarks/scene_readings.md) and
a reading of the model: as first read (`first-read`: one point's mass, c,
along the normal, an even row, the band), or one choice changed (the
contact's mass, the speed unit, the roughness's direction, the disk's surface
row, a regular disk's own surface), or the disk's mass with the regular
disk's own surface. Each runs the random and the triangular disk at the
default run settings as a study (runner/study.py: resumable, failures
recorded) in runs/model_readings/<reading>_<lattice>/; the random disk of a
reading that only changes the regular disks is the same study as without it.

Per reading, the five facts of MODEL.md section 8 with their seed-bootstrap
errors (analysis.estimates, analysis.claims): e (mean over cot gamma >= 1),
Walton's mu and beta0 fitted the paper's way (e 0.8, K 3), the triangular
disk's share of angles with mean beta > 0, and the share of contacts within
1 R of a held side; each one's miss in units of what counts as near, their
sum with its error, and the ranking by the rule. --top N runs the N best,
and the default of the day (the comparison that would change it needs it as
precise; model_readings.json records it), to --top-samples and ranks again.

The rows (one per impact, failures too) go to model_readings.csv beside the
page, rewritten after every study, so the run can be stopped and committed
at any point; a run skips the studies whose rows --docs committed (the
committed rows are kept), so it goes on across machines and sessions.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

from analysis.claims import claims
from analysis.estimates import study_estimates
from analysis.seeds import QUANTITIES
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
from builder.checks import Range
from builder.errors import InputError
from builder.scene import FIRST_READING, SceneSpec
from runner.clusters import WORKERS
from runner.driver import run_study
from runner.options import RunOptions
from runner.study import ANGLES, SAMPLES, Study, runs_folder

RUNS = runs_folder() / "model_readings"
ROWS_CSV = DOCS / "model_readings.csv"

# The five best walls of docs/benchmarks/scene_readings.md (its ranking, random
# disk), as (points, ka over the random disk's, held), and their labels there.
WALLS = {
    "density_1ka_sides-bottom": ("density", 1.0, "sides+bottom"),
    "density_same-c_sides-bottom": ("density", "same-c", "sides+bottom"),
    "1600_10ka_sides": (1600, 10.0, "sides"),
    "1600_1ka_sides-bottom": (1600, 1.0, "sides+bottom"),
    "density_10ka_sides": ("density", 10.0, "sides"),
}
# The readings of the model: one choice changed at a time, and the pair that
# the trials point at (the disk's mass moved mu most; a regular disk
# with its own surface is the construction that could make it slip).
MODELS = {
    "first-read": {},
    "disk-mass": {"contact_mass": "disk"},
    "spring-speed": {"speed_unit": "spring"},
    "both-directions": {"roughness_direction": "both"},
    "random-row": {"surface_row": "random"},
    "lattice-surface": {"regular_surface": "lattice"},
    "disk-mass+lattice-surface": {"contact_mass": "disk", "regular_surface": "lattice"},
}
LATTICES = ("random", "triangular")


def current_default() -> tuple[str, str]:
    """The reading the project runs today (builder.scene.SceneSpec's defaults):
    --top runs it to --top-samples too, so that the comparison that would
    change it is made at the same precision as the best."""
    wall = (SceneSpec.n_wall, SceneSpec.wall_ka, SceneSpec.wall_fixed)
    today = {name: getattr(SceneSpec, name) for name in FIRST_READING}
    model = next(k for k, v in MODELS.items() if {**FIRST_READING, **v} == today)
    return next(k for k, v in WALLS.items() if v == wall), model


# Choices that depart from the paper's text, for the rule's tie-break: its
# sentence (800 points, one ka, the sides held), its c, its "displaced along
# the normal" and its triangular disk whose "surface is the random one's".
# "The mass of the particle" reads either way, as does the even row.
TEXT = {"n_wall": 800, "wall_ka": 1.0, "wall_fixed": "sides"}
DEPARTS = {"speed_unit": "spring", "roughness_direction": "both", "regular_surface": "lattice"}

# The facts (analysis.claims's order) and the number each is measured by.
# Each: its name here, its place in analysis.claims.claims()'s list, which of
# its numbers, and the paper's value (checked against the claim's, so that a
# claims list in another order stops the page instead of mixing facts up).
FACTS = (
    ("e", 0, "model_free", 0.8),
    ("mu", 1, "procedure", 0.18),
    ("beta0", 2, "procedure", 0.56),
    ("triangular beta > 0", 3, "model_free", 0.0),
    ("near a side", 4, "model_free", 0.0),
)


def fact_numbers(table: list[dict], facts=FACTS) -> dict:
    """The claims' number of each fact (None if the study has none), by name."""
    out = {}
    for name, index, kind, paper in facts:
        claim = table[index]
        if claim["paper"] != paper:
            raise RuntimeError(f"analysis.claims' fact {index} is not {name!r}: {claim['fact']}")
        out[name] = claim[kind]
    return out


# What the page is made from: every quantity the seed bootstrap averages
# (analysis.seeds.QUANTITIES) and the lattice's constants, besides the impact's key.
KEEP_COLUMNS = tuple(
    dict.fromkeys(
        (
            "reading",
            "study_lattice",
            "lattice",
            "seed",
            "gamma_deg",
            *QUANTITIES,
            "vn",
            "touches",
            "energy_drift",
            "steps",
            "wall_seconds",
            "nu",
            "error",
        )
    )
)
TOP = Range(0, len(WALLS) * len(MODELS), integer=True)
# The run settings the committed rows were made with: the default of the day.
RUN_OPTIONS = RunOptions(dt=0.002, route="python")


@dataclass
class ReadingStudy(Study):
    """A study whose folder is runs/model_readings/<name>."""

    @property
    def folder(self) -> Path:
        return RUNS / self.name


def readings(walls=tuple(WALLS), models=tuple(MODELS)) -> list[tuple[str, str]]:
    return [(wall, model) for wall in walls for model in models]


def label(reading: tuple[str, str]) -> str:
    return f"{reading[0]}/{reading[1]}"


def study_for(
    reading: tuple[str, str], lattice: str, samples: int, args, first_seed: int = 1
) -> ReadingStudy:
    """The study of one lattice on one reading, seeds ``first_seed`` on. The
    random disk ignores the regular disks' surface: its study is the reading's
    without it, and so shared."""
    wall, model = reading
    choices = dict(MODELS[model])
    if lattice == "random":
        choices.pop("regular_surface", None)
    # "default": the folder's name from before the default moved
    own = "+".join(f"{k}={v}" for k, v in sorted(choices.items())) or "default"
    n_wall, wall_ka, wall_fixed = WALLS[wall]
    choices = {**FIRST_READING, **choices}  # relative to the first reading, not today's default
    return ReadingStudy(
        f"{wall}_{own}_{lattice}",
        options=RUN_OPTIONS,
        lattices=(lattice,),
        angles=args.angles,
        samples=samples,
        first_seed=first_seed,
        n_wall=n_wall,
        wall_ka=wall_ka,
        wall_fixed=wall_fixed,
        **choices,
    )


def distance_from_text(reading: tuple[str, str]) -> int:
    wall = dict(zip(("n_wall", "wall_ka", "wall_fixed"), WALLS[reading[0]], strict=True))
    model = MODELS[reading[1]]
    return sum(wall[k] != v for k, v in TEXT.items()) + sum(
        model.get(k) == v for k, v in DEPARTS.items()
    )


def seeds_done(rows: list[dict], name: str, lattice: str, angles: int) -> int:
    """How many seeds, from 1 on, ``rows`` of reading ``name`` hold at every angle
    (finished or failed)."""
    angles_of: dict[int, set] = {}
    for r in rows:
        if r["reading"] == name and r["study_lattice"] == lattice:
            angles_of.setdefault(int(r["seed"]), set()).add(round(float(r["gamma_deg"]), 4))
    seed = 0
    while len(angles_of.get(seed + 1, ())) >= angles:
        seed += 1
    return seed


def facts(rows: list[dict]) -> dict:
    """The reading's five facts with their errors, misses and their sum."""
    done = [r for r in rows if not r.get("error")]
    out = {"impacts": len(rows), "failed": len(rows) - len(done)}
    if {r["study_lattice"] for r in done} != set(LATTICES):
        return out
    fits, _ = study_estimates(done, compliant=False)
    table = claims(fits)
    total, variance = 0.0, 0.0
    numbers = fact_numbers(table)
    for name, index, _, paper in FACTS:
        claim, number = table[index], numbers[name]
        if number is None or not math.isfinite(number["value"]):
            return out
        miss = abs(number["value"] - paper) / claim["near"]
        error = (number["error"] or 0.0) / claim["near"]
        out[name] = {"value": number["value"], "error": number["error"], "miss": miss}
        total += miss
        variance += error**2
    out["chi2"] = fits["lattices"]["random"]["walton"]["paper"]["chi2"]
    out["total"], out["total_se"] = total, math.sqrt(variance)
    out["met"] = sum(out[name]["miss"] <= 1.0 for name, *_ in FACTS)
    return out


def rank(summaries: dict) -> list[tuple]:
    """Readings from best to worst by total miss; the best is the least, unless
    one closer to the paper's text is within one combined standard error."""
    scored = sorted(
        (r for r in summaries if "total" in summaries[r]), key=lambda r: summaries[r]["total"]
    )
    if not scored:
        return []
    least = summaries[scored[0]]
    close = [
        r
        for r in scored
        if summaries[r]["total"] - least["total"]
        <= math.hypot(summaries[r]["total_se"], least["total_se"])
    ]
    best = min(close, key=lambda r: (distance_from_text(r), summaries[r]["total"]))
    return [best] + [r for r in scored if r != best]


def page(rows: list[dict], args) -> str:
    present = {r["reading"] for r in rows}
    shown = [reading for reading in readings() if label(reading) in present]
    summaries = {
        reading: facts([r for r in rows if r["reading"] == label(reading)]) for reading in shown
    }
    ranking = rank(summaries)
    header = ["wall", "model", "impacts", "failed"]
    header += [f"{name}" for name, *_ in FACTS]
    header += [
        "Walton chi2/dof",
        "misses (e, mu, beta0, share, side)",
        "total miss",
        "away from text",
    ]
    table = []
    for reading in ranking + [r for r in shown if r not in ranking]:
        s = summaries[reading]
        cells = [reading[0], reading[1], str(s["impacts"]), str(s["failed"])]
        if "total" not in s:
            table.append(
                cells + ["-"] * (len(header) - len(cells) - 1) + [str(distance_from_text(reading))]
            )
            continue
        cells += [f"{s[name]['value']:.3f} +- {s[name]['error']:.3f}" for name, *_ in FACTS]
        cells += [
            f"{s['chi2']:.1f}",
            ", ".join(f"{s[name]['miss']:.2f}" for name, *_ in FACTS),
            f"{s['total']:.2f} +- {s['total_se']:.2f}",
            str(distance_from_text(reading)),
        ]
        table.append(cells)
    best = ranking[0] if ranking else None
    return (
        f"Random and triangular disks (800 points), {args.angles} angles from 5.7 to 80.5 "
        f"degrees, seeds 1 to {args.samples} per reading (the {args.top} best, and the "
        f"default when the run was made, `{label(args.compared_default)}`, to "
        f"{args.top_samples}), "
        "v_n = 0.1 (in the reading's unit), the default run of the day (velocity "
        f"Verlet, dt = {RUN_OPTIONS.dt:g} R/c). A reading is a wall (the five best of "
        "[scene_readings.md](scene_readings.md), `points_ka_held`) and a reading of the model "
        "(`first-read`: one point's mass, the speed in c, roughness along the normal, an even "
        "row, the regular disks' band; otherwise the options it changes, docs/model.md "
        "section 8).\n\n"
        "The facts of MODEL.md section 8, each the value with its seed-bootstrap error (whole "
        "seeds resampled, every angle of both disks together): **e** the mean over cot gamma "
        ">= 1 (paper: 0.8); **mu** and **beta0** Walton's fit to the random disk the paper's "
        "way, e fixed at 0.8 and K = 3 (paper: 0.18 and 0.56; its reduced chi^2 beside); "
        "**triangular beta > 0** the triangular disk's share of angles whose mean beta is "
        "positive (paper: 0); **near a side** the random disk's share of contacts within 1 R "
        "of a held side (paper: 0, its contacts stayed on the wall). A miss is |value - paper| "
        "in units of what counts as near (0.1, 0.05, 0.2, 0.1, 0.1); a fact is met at a miss "
        "up to 1. **Total miss**: their sum, with the error of the sum from the facts' errors. "
        "The rule: the default is the reading of least total miss; where others come within "
        "one combined standard error of it, the one with the fewest choices away from the "
        "paper's text (800 points, one ka, the sides held, the speed in c, roughness along the "
        "normal, the triangular disk's surface the random kind).\n\n"
        + markdown_table(header, table)
        + (
            f"\n\nThe rule's pick: wall `{best[0]}`, model `{best[1]}`, total miss "
            f"{summaries[best]['total']:.2f} +- {summaries[best]['total_se']:.2f}, "
            f"{summaries[best]['met']} of 5 facts met.\n"
            if best
            else "\n"
        )
        + "\nOne row per impact: `model_readings.csv` (`python bench/model_readings.py "
        "--from-csv --docs` rebuilds this page from it).\n"
    )


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__, out="the page and rows")
    # None: not given (--from-csv takes them from its rows, and refuses them)
    parser.add_argument(
        "--samples",
        type=SAMPLES,
        default=None,
        help=f"samples per angle, {SAMPLES.describe()} (default: 12)",
    )
    parser.add_argument(
        "--angles", type=ANGLES, default=None, help=f"angles, {ANGLES.describe()} (default: 8)"
    )
    parser.add_argument(
        "--workers",
        type=WORKERS,
        default=None,
        help=f"worker processes, {WORKERS.describe()} (default: 2)",
    )
    parser.add_argument(
        "--top",
        type=TOP,
        default=None,
        help=f"then run the best TOP readings to --top-samples, {TOP.describe()} (default: 5)",
    )
    parser.add_argument(
        "--top-samples",
        type=SAMPLES,
        default=None,
        help=f"samples of the best readings, {SAMPLES.describe()}, more than --samples "
        "(default: 30)",
    )
    parser.add_argument(
        "--walls",
        nargs="+",
        choices=tuple(WALLS),
        default=None,
        help="only these walls (default: all five)",
    )
    parser.add_argument(
        "--models",
        nargs="+",
        choices=tuple(MODELS),
        default=None,
        help="only these readings of the model (default: all)",
    )
    parser.add_argument(
        "--from-csv",
        action="store_true",
        help=f"only rebuild the page from the committed {ROWS_CSV.name}",
    )
    return parser


def check(args: argparse.Namespace) -> None:
    """Refuse options that do not apply together; fill in the defaults."""
    run_size = ("samples", "angles", "workers", "top", "top_samples", "walls", "models")
    if args.from_csv:
        given = [name for name in run_size if getattr(args, name) is not None]
        if given:
            option = "--" + given[0].replace("_", "-")
            raise InputError(f"{option} does not apply with --from-csv (its rows give the size)")
        for path in (ROWS_CSV, ROWS_CSV.with_suffix(".json")):
            if not path.is_file():
                raise InputError(f"--from-csv: {path} is missing")
        return
    if args.top_samples is not None and args.top == 0:
        raise InputError("--top-samples applies with --top 1 or more only")
    args.samples = 12 if args.samples is None else args.samples
    args.angles = 8 if args.angles is None else args.angles
    args.workers = 2 if args.workers is None else args.workers
    args.top = 5 if args.top is None else args.top
    args.top_samples = 30 if args.top_samples is None else args.top_samples
    for name in ("walls", "models"):
        values = getattr(args, name)
        if values is not None and len(set(values)) != len(values):
            raise InputError(f"--{name} names a value twice: {' '.join(values)}")
    args.readings = readings(args.walls or tuple(WALLS), args.models or tuple(MODELS))
    if args.top and args.top_samples <= args.samples:
        raise InputError(
            f"--top-samples must be more than --samples ({args.samples}), got {args.top_samples}"
        )
    for reading in args.readings:  # every study of the run, before the first one starts
        for lattice in LATTICES:
            study_for(reading, lattice, args.samples, args).validate()


def run(rows: list[dict], reading, samples: int, args, save) -> list[dict]:
    """The reading's impacts up to seed ``samples``: those ``rows`` lack run
    as a study of the seeds after the last one they hold whole."""
    for lattice in LATTICES:
        have = seeds_done(rows, label(reading), lattice, args.angles)
        if have >= samples:
            continue
        study = study_for(reading, lattice, samples - have, args, first_seed=have + 1)
        run_study(study, args.workers)
        kept = [
            r
            for r in rows
            if not (r["reading"] == label(reading) and r["study_lattice"] == lattice)
            or int(r["seed"]) <= have
        ]
        rows = kept + study_rows(study, label(reading))
        save(rows)
    return rows


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
        # the run's size: its record beside the rows (the rows alone cannot tell
        # whether the current default was among the best or added to them)
        size = json.loads(ROWS_CSV.with_suffix(".json").read_text())
        for name in ("samples", "angles", "top", "top_samples"):
            setattr(args, name, size[name])
        args.compared_default = tuple(size["default"].split("/"))
    else:
        rows = committed if args.docs else []
        # the default the committed rows were compared with stays the one compared
        args.compared_default = current_default()
        if args.docs and ROWS_CSV.with_suffix(".json").is_file():
            size = json.loads(ROWS_CSV.with_suffix(".json").read_text())
            args.compared_default = tuple(size.get("default", label(current_default())).split("/"))

        def save(rows: list[dict]) -> None:
            write_csv(rows, folder / ROWS_CSV.name, KEEP_COLUMNS)
            size = {k: getattr(args, k) for k in ("samples", "angles", "top", "top_samples")}
            size["default"] = label(args.compared_default)
            (folder / ROWS_CSV.name).with_suffix(".json").write_text(json.dumps(size) + "\n")

        for reading in args.readings:
            rows = run(rows, reading, args.samples, args, save)
        # the best by the first pass alone (seeds up to --samples), so that a run
        # resumed over rows of the second pass picks the same readings
        first = [x for x in rows if int(x["seed"]) <= args.samples]
        summaries = {
            r: facts([x for x in first if x["reading"] == label(r)]) for r in args.readings
        }
        best = rank(summaries)[: args.top]
        compared = args.compared_default
        if args.top and compared in args.readings and compared not in best:
            best.append(compared)
        for reading in best:
            rows = run(rows, reading, args.top_samples, args, save)
        # the others at --samples, whatever earlier runs left in the rows
        chosen = {label(r) for r in best}
        rows = [x for x in rows if x["reading"] in chosen or int(x["seed"]) <= args.samples]
        save(rows)
    body = page(rows, args)
    print(body)
    command = f"python bench/model_readings.py --samples {args.samples} --angles {args.angles}"
    command += f" --top {args.top} --top-samples {args.top_samples}"
    for name in ("walls", "models"):
        if getattr(args, name, None):
            command += f" --{name} {' '.join(getattr(args, name))}"
    if args.docs or args.from_csv:
        command += " --docs"
    path = write_report("model_readings", "The readings of the model", command, body, folder=folder)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
