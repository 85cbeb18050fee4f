"""Does packing several scenes side by side into one LAMMPS run pay?

    python bench/packing.py [--repeats 3] [--steps 3000] [--docs]

The issue's lead for the study's throughput: K copies of one scene in one run
(LAMMPS's replicate) against K separate runs. Each configuration runs the
default scene (random lattice, seed 1, 45 degrees) for a fixed number of steps
with bench/contact_cost.lmp; the table gives the medians, over interleaved
repeats, of scene-steps per second inside LAMMPS's loop (copies x steps / loop
time). "2 runs at once" is two single-scene runs started together, one per
core, which is what the study's two workers do.

The copies run without contact: the segment contact knows one wall polyline,
and its cost is about 2 % of a step (docs/benchmarks/loop_overhead.md), so
it cannot change the comparison.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.common import (
    BENCH_DECK,
    ROOT,
    TIMED_STEPS,
    add_repeats,
    bench_parser,
    markdown_table,
    median,
    timer_seconds,
    write_report,
)
from builder.lammps_data import write_scene
from builder.scene import SceneSpec, build_scene
from runner.lammps_run import command_line, mpi_environment, mpi_launcher

SECTIONS = ("Bond", "Neigh", "Modify")


def start(scene: Path, copies: int, ranks: int, steps: int, log: Path) -> subprocess.Popen:
    variables = {
        "scene": str(scene),
        "contact": "none",
        "steps": str(steps),
        "copies": str(copies),
    }
    command = mpi_launcher(ranks) + ["lmp", *command_line(variables, log, BENCH_DECK)]
    return subprocess.Popen(
        command,
        cwd=ROOT,
        env=mpi_environment(),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )


def measure(scene: Path, way: tuple[str, int, int, int], steps: int, tmp: Path) -> dict:
    """Scene-steps per second of one way: (label, copies per run, ranks, runs at once)."""
    _, copies, ranks, runs = way
    logs = [tmp / f"packing_{copies}_{ranks}_{i}.log" for i in range(runs)]
    procs = [start(scene, copies, ranks, steps, log) for log in logs]
    for proc in procs:
        _, errors = proc.communicate()
        if proc.returncode != 0:
            raise RuntimeError(f"lmp failed: {errors.strip()[-300:]}")
    times = [timer_seconds(log) for log in logs]
    rate = sum(copies * steps / t["loop"] for t in times)
    shares = {name: times[0][name] / times[0]["loop"] for name in SECTIONS}
    return {"rate": rate, **shares}


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 3, "interleaved repeats of every way")
    parser.add_argument(
        "--steps",
        type=TIMED_STEPS,
        default=3000,
        help=f"steps of each run, {TIMED_STEPS.describe()} (default: 3000)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)

    ways = [
        ("1 scene, 1 rank", 1, 1, 1),
        ("2 runs at once, 1 rank each", 1, 1, 2),
        ("2 scenes packed, 1 rank", 2, 1, 1),
        ("8 scenes packed, 1 rank", 8, 1, 1),
        ("2 scenes packed, 2 ranks", 2, 2, 1),
        ("8 scenes packed, 2 ranks", 8, 2, 1),
    ]
    scene = build_scene(SceneSpec(gamma_deg=45.0))
    samples: dict[str, list[dict]] = {way[0]: [] for way in ways}
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_scene(scene, Path(tmp) / "scene")
        for _ in range(args.repeats):
            for way in ways:
                samples[way[0]].append(measure(folder, way, args.steps, Path(tmp)))
                print(way[0], f"{samples[way[0]][-1]['rate']:,.0f}", flush=True)

    base = median([s["rate"] for s in samples[ways[0][0]]])
    rows = []
    for way in ways:
        runs = samples[way[0]]
        rate = median([s["rate"] for s in runs])
        rows.append(
            [way[0], str(way[1] * way[3]), f"{rate:,.0f}", f"{rate / base:.2f}"]
            + [f"{median([s[name] for s in runs]) * 100:.0f}" for name in SECTIONS]
        )
    body = (
        f"Default scene ({scene.info['n_atoms']} atoms, {scene.info['n_springs']} springs), "
        f"{args.steps} steps without contact, medians of {args.repeats} interleaved repeats.\n\n"
        + markdown_table(
            [
                "way",
                "scenes",
                "scene-steps/s",
                "vs 1 scene",
                "Bond % of loop",
                "Neigh %",
                "Modify (nve) %",
            ],
            rows,
        )
    )
    print(body)
    command = f"python bench/packing.py --repeats {args.repeats} --steps {args.steps}" + (
        " --docs" if args.docs else ""
    )
    title = "Packing scenes into one run"
    print(f"wrote {write_report('packing', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
