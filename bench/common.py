"""Helpers for the benchmarks: machine description, LAMMPS loop times, tables."""

from __future__ import annotations

import re
import statistics
import subprocess
import sys
from pathlib import Path

from builder.cli import OneLineParser
from ground import gate
from ground.checks import OutFolder, Range, require_out_folder
from ground.errors import InputError
from ground.gate import runs_folder
from ground.paths import ROOT
from ground.provenance import machine
from pages.text import markdown_table  # noqa: F401 (the benchmarks' tables)

# Where a benchmark's page and tables go: its run folder, unless --docs asks
# for the committed one (make bench and friends do).
DOCS = ROOT / "docs" / "benchmarks"
RUNS = runs_folder() / "bench"
# decks/setup.lmp's dynamics for a fixed number of steps, with or without contact
BENCH_DECK = ROOT / "bench" / "contact_cost.lmp"

# The benchmarks' own counts (the scene's, run's and study's ranges are
# builder.scene's, runner.options' and runner.study's).
REPEATS = Range(1, 1_000, integer=True)  # interleaved runs of each configuration
SEED_COUNT = Range(1, 10_000, integer=True)  # seeds 1 to N
TIMED_STEPS = Range(100, 1_000_000, integer=True)  # steps of one timed run


def loop_seconds(log: Path) -> tuple[float, int]:
    """Total loop time and steps over all runs of a LAMMPS log."""
    seconds, steps = 0.0, 0
    for match in re.finditer(
        r"Loop time of ([\d.eE+-]+) on \d+ procs for (\d+) steps", log.read_text()
    ):
        seconds += float(match.group(1))
        steps += int(match.group(2))
    return seconds, steps


def timer_seconds(log: Path) -> dict[str, float]:
    """Loop time and each section of LAMMPS's timer breakdown (Bond, Pair, Neigh,
    ...: the average over ranks; Other has no min column), in seconds summed
    over every run of a log."""
    text = log.read_text()
    total = {"loop": loop_seconds(log)[0]}
    for match in re.finditer(r"^(\w+)\s*\|\s*[\d.eE+-]*\s*\|\s*([\d.eE+-]+)", text, re.M):
        total[match.group(1)] = total.get(match.group(1), 0.0) + float(match.group(2))
    return total


def file_at(revision: str, path: str) -> str:
    """A file of the project as it was at a git revision (for before/after benchmarks)."""
    return subprocess.run(
        ["git", "show", f"{revision}:{path}"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout


def median(values) -> float:
    return statistics.median(values)


def bench_parser(script: str, doc: str, out: str | None = None) -> OneLineParser:
    """A benchmark's parser: one-line errors, exit 2, and --docs.

    ``script`` is the script's __file__, ``doc`` its docstring. With ``out``
    (what the script writes, for the help), also --out FOLDER, which argparse
    refuses beside --docs; ``page_folder`` gives the folder either names."""
    parser = OneLineParser(
        prog=f"python bench/{Path(script).name}", description=doc.strip().splitlines()[0]
    )
    group = parser.add_mutually_exclusive_group() if out else parser
    group.add_argument(
        "--docs",
        action="store_true",
        help="write the page (and its tables) into docs/benchmarks/, the committed "
        "one; default: runs/bench/",
    )
    if out:
        group.add_argument(
            "--out",
            type=OutFolder(lammps=False),
            default=None,
            help=f"write {out} into this folder instead of runs/bench/",
        )
    return parser


def page_folder(args) -> Path:
    """Where a page goes: --out if given, else docs/benchmarks/ or runs/bench/."""
    return args.out if args.out is not None else output_folder(args.docs)


def refuse(script: str, error: InputError) -> int:
    """A bad combination of options: one line on stderr, exit status 2."""
    print(f"python bench/{Path(script).name}: error: {error}", file=sys.stderr)
    return 2


def distinct(option: str, values: list) -> list:
    """``values`` if none repeats (a repeated one would be run and tabled twice)."""
    repeated = sorted({v for v in values if values.count(v) > 1})
    if repeated:
        raise InputError(f"{option} repeats {', '.join(f'{v:g}' for v in repeated)}")
    return values


def add_repeats(parser, default: int, what: str) -> None:
    """--repeats: how many times each configuration runs (``what`` says it)."""
    parser.add_argument(
        "--repeats",
        type=REPEATS,
        default=default,
        help=f"{what}, {REPEATS.describe()} (default: {default})",
    )


def add_scene_pick(parser) -> None:
    """--gamma and --seed: which default-scene impact a timing benchmark runs."""
    from builder.scene import ANGLE, SEED

    parser.add_argument(
        "--gamma",
        type=ANGLE,
        default=30.0,
        help=f"incidence angle, {ANGLE.describe()} (default: 30)",
    )
    parser.add_argument(
        "--seed", type=SEED, default=1, help=f"sample seed, {SEED.describe()} (default: 1)"
    )


def output_folder(docs: bool) -> Path:
    """docs/benchmarks/ if asked (--docs grants it: the benchmarks' own pages),
    else runs/bench/; made through the write gate (ground.gate)."""
    if docs:
        gate.grant(DOCS)
    folder = DOCS if docs else require_out_folder("the benchmarks' folder", RUNS)
    return gate.make_folder(folder, "--docs" if docs else "the benchmarks' folder")


def write_report(
    name: str, title: str, command: str, body: str, docs: bool = False, folder: Path | None = None
) -> Path:
    """The page ``name``.md, into ``folder`` if given, else output_folder(docs)."""
    path = (folder or output_folder(docs)) / f"{name}.md"
    return gate.write_text(
        path, f"# {title}\n\nGenerated by `{command}` on {machine()}.\n\n{body}\n"
    )


def paired_steps(runs: list[dict], quantities: tuple[str, ...]) -> list[dict]:
    """Per label and resolution N: the per-seed differences Q(N) - Q(N/2) of
    each quantity over the seeds run at both, their mean, its standard error
    (sd / sqrt(n)) and the half-width of its t-based 95 % interval
    (n - 1 degrees of freedom). ``runs`` are rows of label, n_disk, seed and
    the quantities (numbers as text, as csv gives them)."""
    from scipy.stats import t as student

    values = {(r["label"], int(r["n_disk"]), int(r["seed"])): r for r in runs}
    rows = []
    for label, n in sorted({(k[0], k[1]) for k in values}):
        seeds = sorted(
            k[2] for k in values if k[:2] == (label, n) and (label, n // 2, k[2]) in values
        )
        if len(seeds) < 2:
            continue
        row = {"label": label, "n_disk": n, "from": n // 2, "seeds": len(seeds)}
        for name in quantities:
            step = [
                float(values[(label, n, s)][name]) - float(values[(label, n // 2, s)][name])
                for s in seeds
            ]
            se = statistics.stdev(step) / len(step) ** 0.5
            row[f"{name}_step"] = f"{statistics.fmean(step):.4g}"
            row[f"{name}_step_se"] = f"{se:.2g}"
            row[f"{name}_step_t95"] = f"{student.ppf(0.975, len(step) - 1) * se:.2g}"
        rows.append(row)
    return rows
