"""What the contact costs per step, and what the pair variant changes.

    python bench/contact_cost.py [--repeats 5] [--steps 2000] [--seeds 2] [--docs]

1. The default scene (random lattice, seed 1, 45 degrees) for 2000 steps from
   the start of the impact, with the segment contact, the pair variant, and no
   contact at all; the three are interleaved and each is timed --repeats times.
   The contact's cost is the extra time over the run without contact, as a
   share of the step; LAMMPS's own Pair and Neigh timers are shown too.
2. e and beta of the same scenes with the segment contact and the pair variant,
   at 0.1 c (the study's speed) and 0.01 c.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.common import (
    BENCH_DECK,
    ROOT,
    SEED_COUNT,
    TIMED_STEPS,
    add_repeats,
    bench_parser,
    markdown_table,
    median,
    timer_seconds,
    write_report,
)
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import PAPER, SceneSpec
from ground.launch import LammpsError, command_line
from runner.impact import run_scene
from runner.options import RunOptions

CONTACTS = ("none", "pair", "segment")
# Four angles across the study's range, grazing to near head-on.
ANGLES = (5.7, 26.6, 55.0, 80.4)


def timed_run(scene: Path, contact: str, steps: int) -> dict[str, float]:
    log = scene / f"bench_{contact}.log"
    variables = {"scene": str(scene), "contact": contact, "steps": str(steps)}
    subprocess.run(["lmp", *command_line(variables, log, BENCH_DECK)], cwd=ROOT, check=True)
    return timer_seconds(log)


def cost_table(scene: Path, repeats: int, steps: int) -> str:
    times = {contact: [] for contact in CONTACTS}
    for _ in range(repeats):
        for contact in CONTACTS:
            times[contact].append(timed_run(scene, contact, steps))
    none = median([t["loop"] for t in times["none"]])
    rows = []
    for contact in CONTACTS:
        loop = median([t["loop"] for t in times[contact]])
        pair = median([t["Pair"] for t in times[contact]])
        neigh = median([t["Neigh"] for t in times[contact]])
        extra = (loop - none) / loop * 100
        rows.append(
            [
                contact,
                f"{steps / loop:,.0f}",
                f"{pair / loop * 100:.1f}",
                f"{neigh / loop * 100:.1f}",
                "-" if contact == "none" else f"{extra:+.1f}",
            ]
        )
        print(" ".join(rows[-1]), flush=True)
    return markdown_table(
        [
            "contact",
            "steps/s",
            "Pair % of step",
            "Neigh % of step",
            "cost over no contact, % of step",
        ],
        rows,
    )


def restitution_table(tmp: Path, seeds: int) -> str:
    rows = []
    for vn in (0.1, 0.01):
        for seed in range(1, seeds + 1):
            for gamma in ANGLES:
                scene = build_scene(SceneSpec(seed=seed, gamma_deg=gamma, vn=vn, **PAPER))
                cells = []
                for contact in ("segment", "pair"):
                    folder = write_scene(scene, tmp / f"{vn}_{seed}_{gamma}_{contact}")
                    try:
                        r = run_scene(folder, RunOptions(contact=contact, tmax=400.0))
                        cells += [f"{r['e']:.3f}", f"{r['beta']:+.3f}"]
                    except LammpsError as error:
                        when = re.search(r"at time ([\d.]+)", str(error))
                        cells += [
                            f"disk entered the wall (t = {float(when.group(1)):.1f})"
                            if when
                            else str(error)[:40],
                            "",
                        ]
                rows.append([f"{vn}", str(seed), f"{gamma:g}", *cells])
                print(" ".join(rows[-1]), flush=True)
    return markdown_table(
        ["vn", "seed", "gamma", "e segment", "beta segment", "e pair", "beta pair"], rows
    )


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 5, "timed runs of each contact")
    parser.add_argument(
        "--steps",
        type=TIMED_STEPS,
        default=2000,
        help=f"steps of each timed run, {TIMED_STEPS.describe()} (default: 2000)",
    )
    parser.add_argument(
        "--seeds",
        type=SEED_COUNT,
        default=2,
        help=f"seeds 1 to N of the e and beta table, {SEED_COUNT.describe()} (default: 2)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        scene = write_scene(build_scene(SceneSpec(gamma_deg=45.0, **PAPER)), tmp / "scene")
        costs = cost_table(scene, args.repeats, args.steps)
        restitution = restitution_table(tmp, args.seeds)
    body = (
        f"## Cost per step\n\nDefault scene, {args.steps} steps from the start of the impact, "
        f"medians of {args.repeats} interleaved runs, serial.\n\n{costs}\n\n"
        f"## e and beta: segment contact against the pair variant\n\n{restitution}\n"
    )
    print(body)
    title = "Contact: cost and pair variant"
    command = "python bench/contact_cost.py" + "".join(
        f" --{name} {value}"
        for name, value, default in (
            ("repeats", args.repeats, 5),
            ("steps", args.steps, 2000),
            ("seeds", args.seeds, 2),
        )
        if value != default
    )
    command += " --docs" if args.docs else ""
    print(f"wrote {write_report('contact_cost', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
