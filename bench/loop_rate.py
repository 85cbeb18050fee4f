"""LAMMPS's rate per atom-step against the resolution, with and without this
project's loop savings.

    python bench/loop_rate.py [--sizes 800 3200 12800 51200] [--ranks 1 2]
                              [--two-rank-sizes ...] [--repeats 3] [--gamma 30]
                              [--seed 1] [--docs]

For each number of disk points N (random disk, seed --seed, --gamma degrees,
0.1 c, the continuum reading's correlation length 0.048 R, the scene's
defaults otherwise: bench/resolution_cost.py), the scene is built once and its
impact run by the runner (the study's stop rule, dt auto) with LAMMPS's timer
breakdown (the deck's post yes), in two settings, interleaved with the rank
counts and repeated:

  now    the deck's defaults: the packed bond list of harmonic/quartic, fix
         nve/2d, ghosts per type (comm_modify mode multi), balance on more
         than one rank;
  plain  the same physics in LAMMPS's plain settings: harmonic/quartic
         reading each bond's type (packed no), LAMMPS's own fix nve, one
         communication cutoff for every atom, LAMMPS's even split of the box.

Each gives the loop's atom-steps per second (atoms times steps over LAMMPS's
"Loop time"), the shares of Bond and Modify in it, the ghost atoms per rank,
and e; medians over the repeats. Both settings sum the same forces in the same
order on one rank, so e must agree to every digit there (the script fails if
not); on two ranks the split differs, and a rough contact's chaos may move e's
last digits. The machine's 1-minute load average is given beside each size:
on a shared machine wall-clock rates are only as good as that load allows.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import sys
from pathlib import Path

from bench.common import (
    RUNS,
    add_repeats,
    add_scene_pick,
    bench_parser,
    distinct,
    markdown_table,
    median,
    refuse,
    timer_seconds,
    write_report,
)
from bench.resolution_cost import SIZE, scaled_settings, spec_at
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.errors import InputError
from ground.launch import LammpsError
from runner.impact import run_scene
from runner.options import NPROCS, RunOptions

SIZES = [800, 3200, 12800, 51200]
SETTINGS = {
    "now": {},
    "plain": {
        "springs_args": "packed no",
        "nve_style": "nve",
        "comm_style": "single",
        "balance": "no",
    },
}


def run_once(folder: Path, dt: float, ranks: int, setting: str) -> dict | None:
    """One impact; its rate, shares, ghosts and e (None if LAMMPS failed)."""
    overrides = {"post": "yes", **SETTINGS[setting]}
    try:
        result = run_scene(folder, RunOptions(dt=dt, nprocs=ranks), overrides)
    except LammpsError as error:
        print(f"  {folder.name}, {ranks} ranks, {setting}: {error}", flush=True)
        return None
    log = folder / "log.lammps"
    text = log.read_text()
    runs = re.findall(
        r"Loop time of ([\d.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", text
    )
    seconds, steps, atoms = max((float(s), int(n), int(a)) for s, n, a in runs)
    timers = timer_seconds(log)  # summed over the deck's runs; the run 0s add nothing
    ghosts = re.findall(r"^Nghost:\s+([\d.eE+-]+) ave", text, re.M)
    return {
        "rate": atoms * steps / seconds,
        "steps": steps,
        "atoms": atoms,
        "bond": timers.get("Bond", 0.0) / timers["loop"],
        "modify": timers.get("Modify", 0.0) / timers["loop"],
        "comm": timers.get("Comm", 0.0) / timers["loop"],
        "ghosts": float(ghosts[0]) if ghosts else float("nan"),  # the impact run's (post yes)
        "e": result["e"],
    }


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--sizes", type=SIZE, nargs="+", default=SIZES,
        help=f"numbers of disk points, each {SIZE.describe()} (default: "
        f"{' '.join(map(str, SIZES))})",
    )  # fmt: skip
    parser.add_argument(
        "--ranks", type=NPROCS, nargs="+", default=[1, 2],
        help=f"MPI ranks of each impact, each {NPROCS.describe()} (default: 1 2)",
    )  # fmt: skip
    parser.add_argument(
        "--two-rank-sizes", type=SIZE, nargs="+", default=None,
        help="the sizes run on more than one rank, among --sizes (default: all of them)",
    )  # fmt: skip
    parser.add_argument(
        "--body", action="store_true",
        help="the default body (the scene's defaults: one continuous surface, L 0.2 R, the "
        "area barrier) instead of the continuum reading at 0.048 R; the page loop_rate_body",
    )  # fmt: skip
    add_repeats(parser, 3, "runs of each setting and rank count, interleaved")
    add_scene_pick(parser)
    return parser


def scene_at(n: int, gamma: float, seed: int, body: bool) -> tuple[SceneSpec, float]:
    """The scene of N disk points and its step (dt auto): the continuum
    reading of bench/resolution_cost.py, or (``body``) the default body."""
    if body:
        spec = SceneSpec(n_disk=n, gamma_deg=gamma, seed=seed)
        return spec, RunOptions().for_scene(spec).dt
    return spec_at(n, gamma, seed), scaled_settings(n)[0]


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--sizes", args.sizes)
        distinct("--ranks", args.ranks)
        for n in args.sizes:
            scene_at(n, args.gamma, args.seed, args.body)[0].validate()
        many = args.sizes if args.two_rank_sizes is None else args.two_rank_sizes
        if not set(many) <= set(args.sizes):
            raise InputError("--two-rank-sizes must be among --sizes")
    except InputError as error:
        return refuse(__file__, error)
    sizes = sorted(args.sizes)
    rows, summary = [], {}
    for n in sizes:
        folder = RUNS / "loop_rate" / f"n{n}"
        shutil.rmtree(folder, ignore_errors=True)
        spec, dt = scene_at(n, args.gamma, args.seed, args.body)
        write_scene(build_scene(spec), folder)
        ranks = [r for r in args.ranks if r == 1 or n in many]
        load = os.getloadavg()[0]
        done: dict[tuple[int, str], list[dict]] = {(r, s): [] for r in ranks for s in SETTINGS}
        for _ in range(args.repeats):
            for r in ranks:
                for setting in SETTINGS:
                    done[r, setting].append(run_once(folder, dt, r, setting))
        loads = f"{load:.1f} to {os.getloadavg()[0]:.1f}"
        for (r, setting), runs in done.items():
            if None in runs:
                rows.append([f"{n:,}", str(r), setting] + ["failed"] * 7 + [loads])
                continue
            rate = median(x["rate"] for x in runs)
            summary[n, r, setting] = rate
            rows.append([
                f"{n:,}", str(r), setting, f"{runs[0]['atoms']:,}", f"{runs[0]['steps']:,}",
                f"{rate / 1e6:.1f}", f"{median(x['bond'] for x in runs):.0%}",
                f"{median(x['modify'] for x in runs):.0%}",
                f"{median(x['comm'] for x in runs):.0%}",
                f"{median(x['ghosts'] for x in runs):,.0f}" if r > 1 else "-",
                f"{runs[0]['e']:.6f}", loads,
            ])  # fmt: skip
        one = done.get((1, "now")), done.get((1, "plain"))
        if all(one) and None not in one[0] + one[1]:
            if {x["e"] for x in one[0] + one[1]} != {one[0][0]["e"]}:
                print(f"{n} points: the two settings' e differ on one rank", file=sys.stderr)
                return 1
        print(rows[-1], flush=True)
    body = (
        f"Random disk, seed {args.seed}, {args.gamma:g} degrees, 0.1 c, "
        + (
            "the default body (the scene's defaults: one continuous surface, L 0.2 R, the area "
            "barrier)"
            if args.body
            else "correlation length 0.048 R, the scene's defaults"
        )
        + "; the runner's impact (dt auto, the study's stop "
        f"rule) with LAMMPS's timer breakdown; medians of {args.repeats} runs, settings and "
        "rank counts interleaved. rate: atoms times steps over LAMMPS's loop time, in "
        "millions of atom-steps per second; Bond, Modify, Comm: shares of the loop "
        "(average over ranks); ghosts: per rank at the end. load: the 1-minute load "
        f"average before and after the size ({os.cpu_count()} cores).\n\n"
        + markdown_table(
            [
                "disk points N",
                "ranks",
                "setting",
                "atoms",
                "steps",
                "M atom-steps/s",
                "Bond",
                "Modify",
                "Comm",
                "ghosts per rank",
                "e",
                "load",
            ],
            rows,
        )  # fmt: skip
    )
    ratios = []
    largest = sizes[-1]
    for setting in SETTINGS:
        rate = {(n, r): v for (n, r, s), v in summary.items() if s == setting}
        if (largest, 1) in rate and (12800, 1) in rate:
            value = rate[largest, 1] / rate[12800, 1]
            ratios.append(
                [f"rate at {largest:,} / rate at 12,800, one rank", setting, f"{value:.2f}"]
            )
        for n in sizes:
            if (n, 2) in rate and (n, 1) in rate:
                value = rate[n, 2] / rate[n, 1]
                ratios.append([f"two ranks / one rank at {n:,}", setting, f"{value:.2f}"])
    if ratios:
        body += "\n\nRatios of the median rates:\n\n" + markdown_table(
            ["ratio", "setting", "value"], ratios
        )
    command = (
        "python bench/loop_rate.py --sizes " + " ".join(map(str, sizes))
        + " --ranks " + " ".join(map(str, args.ranks))
        + ("" if args.two_rank_sizes is None
           else " --two-rank-sizes " + " ".join(map(str, args.two_rank_sizes)))
        + f" --repeats {args.repeats} --gamma {args.gamma:g} --seed {args.seed}"
        + (" --body" if args.body else "") + (" --docs" if args.docs else "")
    )  # fmt: skip
    print(body)
    title = "LAMMPS's rate per atom-step against the resolution"
    name = "loop_rate_body" if args.body else "loop_rate"
    if args.body:
        title += ": the default body"
    print(f"wrote {write_report(name, title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
