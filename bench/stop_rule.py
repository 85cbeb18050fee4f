"""The predictive stop rule against runs that go on long after it would stop.

    python bench/stop_rule.py [--seeds 3] [--slack R] [--vibration 1] [--name stop_rule]
                              [--docs]

Every lattice of the study at angles from 5.7 to 80.5 degrees, several seeds.
Each impact runs twice: stopped by the predictive rule, and continued to
t = 100 R/c. A contact in the long run after the predictive stop is a missed
re-contact; the table counts them and how much they change e and beta, and
the steps each way. Writes runs/bench/<--name>.md, with --docs
docs/benchmarks/<--name>.md; the committed tables are `--vibration 1 --name
stop_rule_vibration --docs` and `--vibration 0 --slack 0.0337 --name
stop_rule_fixed_margin --docs`.
"""

from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path

from analysis.impact.series import read_series
from bench.common import SEED_COUNT, bench_parser, markdown_table, median, write_report
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.materials import square_ratio_for_poisson
from builder.scene import PAPER, SceneSpec
from ground.checks import Range
from runner.impact import run_scene
from runner.options import DEFAULT_DT, RunOptions

LATTICES = {
    "random": {},
    "triangular": {},
    "square nu=0.1": {"k2_over_k1": square_ratio_for_poisson(0.1)},
    "square nu=0.3": {"k2_over_k1": square_ratio_for_poisson(0.3)},
}
ANGLES = (5.7, 26.6, 45.0, 63.4, 80.5)
LONG = 100.0
# decks/impact.lmp's stop_slack (a margin in R; its default is 0.1 cutoff,
# 0.0067 R on the default wall) and stop_vibration (the weight of the
# vibration amplitudes in the margin: 0 leaves them out, 1 counts them)
SLACK = Range(0.0, 1.0, unit="R")
VIBRATION = Range(0.0, 10.0)


def page_name(text: str) -> str:
    """--name: a page of this benchmark, stop_rule or stop_rule_<word>, so that
    it cannot overwrite another benchmark's page."""
    if not re.fullmatch(r"stop_rule(_[A-Za-z0-9_-]+)?", text):
        raise argparse.ArgumentTypeError(
            f"must be stop_rule or stop_rule_<letters, digits, _ or ->, got {text!r}"
        )
    return text


page_name.__name__ = "name"
page_name.bad_values = ("", "other", "stop_rule_", "stop_rule/x", "../stop_rule")


def long_run(folder: Path) -> dict:
    """The impact continued to t = LONG whatever happens (the deck's early_stop no)."""
    return run_scene(folder, RunOptions(tmax=LONG), {"early_stop": "no"})


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--seeds",
        type=SEED_COUNT,
        default=3,
        help=f"seeds 1 to N, {SEED_COUNT.describe()} (default: 3)",
    )
    parser.add_argument(
        "--slack",
        type=SLACK,
        default=None,
        help=f"stop_slack, {SLACK.describe()} (default: the deck's, 0.1 cutoff)",
    )
    parser.add_argument(
        "--vibration",
        type=VIBRATION,
        default=1.0,
        help=f"stop_vibration, {VIBRATION.describe()}: 0 leaves the vibration amplitudes "
        "out of the margin, 1 counts them (default: 1)",
    )
    parser.add_argument(
        "--name",
        type=page_name,
        default="stop_rule",
        help="the page's name, stop_rule or stop_rule_<word> (default: stop_rule)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    extra_vars = {"stop_vibration": repr(args.vibration)}
    if args.slack is not None:
        extra_vars["stop_slack"] = repr(args.slack)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra in LATTICES.items():
            lattice = name.split()[0]
            steps, misses, worst = [], 0, 0.0
            for seed in range(1, args.seeds + 1):
                for gamma in ANGLES:
                    scene = build_scene(
                        SceneSpec(lattice=lattice, seed=seed, gamma_deg=gamma, **extra, **PAPER)
                    )
                    tag = f"{lattice}{extra.get('k2_over_k1', '')}_{seed}_{gamma}"
                    stopped = run_scene(
                        write_scene(scene, Path(tmp) / f"{tag}_p"), RunOptions(), extra_vars
                    )
                    folder = write_scene(scene, Path(tmp) / f"{tag}_long")
                    full = long_run(folder)
                    series = read_series(folder / "series.dat")
                    later = (series["time"] > stopped["time_end"]) & (series["pe_contact"] > 0)
                    if later.any():
                        misses += 1
                        gap = max(abs(stopped[k] - full[k]) for k in ("e", "beta"))
                        worst = max(worst, gap)
                        print(
                            f"  missed re-contact: {name} seed {seed} gamma {gamma}: stopped at "
                            f"{stopped['time_end']:.1f}, contact again at "
                            f"{series['time'][later][0]:.1f}, "
                            f"e and beta change by {gap:.1e}",
                            flush=True,
                        )
                    steps.append(stopped["steps"])
            rows.append(
                [
                    name,
                    str(len(steps)),
                    f"{median(steps):.0f}",
                    f"{LONG / DEFAULT_DT:.0f}",
                    str(misses),
                    f"{worst:.1e}" if misses else "-",
                ]
            )
            print(" | ".join(rows[-1]), flush=True)
    body = (
        f"Angles {', '.join(f'{a:g}' for a in ANGLES)} degrees, seeds 1 to {args.seeds}, "
        f"default settings, stop_vibration {args.vibration:g}, stop_slack "
        f"{'0.1 cutoff' if args.slack is None else args.slack}; the long runs go on to "
        f"t = {LONG:g} R/c.\n\n"
        + markdown_table(
            [
                "lattice",
                "impacts",
                "median steps, predictive stop",
                f"steps to t = {LONG:g}",
                "contacts after the stop",
                "largest change of e or beta they make",
            ],
            rows,
        )
    )
    print(body)
    command = (
        f"python bench/stop_rule.py --vibration {args.vibration:g}"
        + (f" --slack {args.slack:g}" if args.slack is not None else "")
        + (f" --seeds {args.seeds}" if args.seeds != 3 else "")
        + f" --name {args.name}"
        + (" --docs" if args.docs else "")
    )
    print(f"wrote {write_report(args.name, 'Stop rule', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
