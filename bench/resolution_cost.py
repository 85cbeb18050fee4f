"""What a resolution costs: building and running an impact against the disk's points.

    python bench/resolution_cost.py [--sizes 200 400 ... 51200] [--ranks 1 2]
                                    [--repeats 3] [--gamma 30] [--seed 1] [--docs]

For each number of disk points N (random disk, seed --seed, --gamma degrees,
0.1 c) at the scene's defaults, which follow the resolution: the wall of 2 N
points, dt auto = 8e-3 sqrt(800 / N) R/c, the contact scaled with the spacing
(a R = 300 sqrt(N / 800); docs/model.md, "The model as the resolution
grows"), with the continuum reading's roughness, correlation length 0.048 R
(the resolution study's; the paper's per-point roughness steepens with N).

Each scene is built by ``python -m builder scene`` in a process of its own,
twice: with an empty Poisson-disk cache (IMPACT_POISSON_CACHE, a fresh
folder: every sample drawn, as a new seed is) and then with the samples it
drew (the rest of the builder alone). The build's peak memory is the
process's maximum resident set size (os.wait4). The impact is then run by
the runner (the study's stop rule) on each number of --ranks, --repeats
times, the rank counts interleaved; LAMMPS seconds are the median loop time,
and the median CPU time of lmp and mpirun over the run. Power-law exponents
are fitted in log-log (numpy.polyfit) over all sizes and over the largest four.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.common import (
    ROOT,
    RUNS,
    add_repeats,
    add_scene_pick,
    bench_parser,
    distinct,
    loop_seconds,
    markdown_table,
    median,
    refuse,
    write_report,
)
from builder.scene import N_DISK, N_WALL, PAPER, SceneSpec
from ground.checks import Range
from ground.errors import InputError
from ground.launch import LammpsError
from runner.impact import run_scene
from runner.options import NPROCS, RunOptions

# The disk's points: a wall of twice as many must be one the builder takes.
SIZE = Range(N_DISK.low, min(N_DISK.high, N_WALL.high // 2), integer=True)
SIZES = [200, 400, 800, 1600, 3200, 6400, 12800, 25600, 51200]
# The study's resolution, where the step and the contact are the validated ones.
ROUGHNESS_LENGTH = 0.048  # R: the resolution study's continuum reading
FIT_TAIL = 4  # the local exponent: a fit over the largest this many sizes


def scaled_settings(n_disk: int) -> tuple[float, float, int]:
    """The scene's own time step, contact a R and wall points at n_disk
    (dt auto, contact_scaling spacing, n_wall twice n_disk)."""
    spec = spec_at(n_disk, 30.0, 1)
    return RunOptions().for_scene(spec).dt, spec.contact_decay * spec.radius, spec.wall_points


def spec_at(n_disk: int, gamma: float, seed: int) -> SceneSpec:
    return SceneSpec(
        seed=seed, gamma_deg=gamma, n_disk=n_disk, **{**PAPER, "roughness_length": ROUGHNESS_LENGTH}
    )


def build(spec: SceneSpec, folder: Path, cache: Path) -> tuple[float, float, float]:
    """Build the scene with ``python -m builder scene`` in its own process;
    its wall seconds, CPU seconds and peak resident memory in MB."""
    command = [
        sys.executable,
        "-m",
        "builder",
        "scene",
        "--n-disk",
        str(spec.n_disk),
        "--roughness-length",
        repr(spec.roughness_length),
        # the four options that carry the body to finer disks, all given: their
        # defaults are the refined body's, not this page's scene
        "--roughness-profile",
        spec.roughness_profile,
        "--contact-scaling",
        spec.contact_scaling,
        "--area-floor",
        repr(spec.area_floor),
        "--gamma",
        repr(spec.gamma_deg),
        "--seed",
        str(spec.seed),
        "--out",
        str(folder),
    ]
    environment = {**os.environ, "IMPACT_POISSON_CACHE": str(cache)}
    with tempfile.TemporaryFile() as errors:
        start = time.perf_counter()
        process = subprocess.Popen(
            command, cwd=ROOT, env=environment, stdout=subprocess.DEVNULL, stderr=errors
        )
        # os.wait4 gives this child's own resource use (the children's total
        # from getrusage would be the largest of every build so far)
        _, status, usage = os.wait4(process.pid, 0)
        seconds = time.perf_counter() - start
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            errors.seek(0)
            tail = errors.read().decode(errors="replace").strip().splitlines()[-1:]
            raise RuntimeError(f"the build of {spec.n_disk} points failed: {tail}")
    return seconds, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0  # kB on Linux


def run_once(folder: Path, dt: float, ranks: int) -> dict | None:
    """One impact of the built scene on ``ranks`` ranks; None if LAMMPS failed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        result = run_scene(folder, RunOptions(dt=dt, nprocs=ranks))
    except LammpsError as error:
        print(f"  {folder.name}, {ranks} ranks: {error}", flush=True)
        return None
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds, steps = loop_seconds(folder / "log.lammps")
    return {
        "seconds": seconds,
        # lmp's (and mpirun's) CPU time, all ranks: the whole run, start-up included
        "cpu": after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime,
        "steps": steps,
        "e": result["e"],
        "drift": result["energy_drift"],
    }


def measure(spec: SceneSpec, ranks: list[int], repeats: int) -> dict:
    """Build the scene cold and with its samples cached, then run it on each
    number of ranks, ``repeats`` times interleaved: the median seconds."""
    dt, _, _ = scaled_settings(spec.n_disk)
    folder = RUNS / "resolution_cost" / f"n{spec.n_disk}"
    shutil.rmtree(folder, ignore_errors=True)
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory(prefix="poisson_") as cache:
        cold_wall, cold, cold_mb = build(spec, folder, Path(cache))
        _, warm, warm_mb = build(spec, folder, Path(cache))
    out = {"cold_wall": cold_wall, "cold": cold, "warm": warm, "load": load, "runs": {}}
    out["peak_mb"] = max(cold_mb, warm_mb)
    runs = {count: [] for count in ranks}
    for _ in range(repeats):
        for count in ranks:
            runs[count].append(run_once(folder, dt, count))
    for count, done in runs.items():
        if None in done:
            out["runs"][count] = None
            continue
        out["runs"][count] = {
            **done[0],
            "seconds": median(r["seconds"] for r in done),
            "cpu": median(r["cpu"] for r in done),
        }
    out["atoms"] = json.loads((folder / "scene.json").read_text())["n_atoms"]
    return out


def exponent(sizes: list[int], values: list[float | None]) -> str:
    """The slope of log(value) against log(N), over the sizes that have a value."""
    pairs = [(n, v) for n, v in zip(sizes, values) if v is not None and v > 0]
    if len(pairs) < 2:
        return "-"
    n, v = np.array(pairs, dtype=float).T
    return f"{np.polyfit(np.log(n), np.log(v), 1)[0]:.2f}"


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--sizes",
        type=SIZE,
        nargs="+",
        default=SIZES,
        help=f"numbers of disk points, each {SIZE.describe()} (default: "
        f"{' '.join(map(str, SIZES))})",
    )
    parser.add_argument(
        "--ranks",
        type=NPROCS,
        nargs="+",
        default=[1, 2],
        help=f"MPI ranks of each impact, each {NPROCS.describe()} (default: 1 2)",
    )
    add_repeats(parser, 3, "runs of each impact, interleaved; the table gives the median")
    add_scene_pick(parser)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--sizes", args.sizes)
        distinct("--ranks", args.ranks)
        for n in args.sizes:
            spec_at(n, args.gamma, args.seed).validate()
            RunOptions(dt=scaled_settings(n)[0]).validate()
    except InputError as error:
        return refuse(__file__, error)
    sizes = sorted(args.sizes)

    measured = {}
    for n in sizes:
        out = measure(spec_at(n, args.gamma, args.seed), args.ranks, args.repeats)
        measured[n] = out
        runs = " ".join(
            f"{r} ranks: {run['steps']} steps {run['seconds']:.1f} s" if run else f"{r}: failed"
            for r, run in out["runs"].items()
        )
        print(
            f"{n} points: build CPU {out['cold']:.1f} s cold, {out['warm']:.1f} s cached, "
            f"{out['peak_mb']:.0f} MB; {runs}",
            flush=True,
        )

    rank_header = [
        h
        for r in args.ranks
        for h in (f"steps ({r} rank{'s' * (r > 1)})", f"LAMMPS s ({r})", f"LAMMPS CPU s ({r})")
    ]
    rows = []
    for n in sizes:
        out = measured[n]
        dt, contact_a, _ = scaled_settings(n)
        cells = []
        for r in args.ranks:
            run = out["runs"][r]
            cells += (
                [f"{run['steps']:,}", f"{run['seconds']:.2f}", f"{run['cpu']:.1f}"]
                if run
                else ["failed", "-", "-"]
            )
        first = next((run for run in out["runs"].values() if run), None)
        rows.append(
            [
                f"{n:,}",
                f"{out['atoms']:,}",
                f"{dt:.2e}",
                f"{contact_a:.0f}",
                f"{out['cold']:.1f}",
                f"{out['warm']:.1f}",
                f"{out['cold_wall']:.1f}",
                f"{out['peak_mb']:.0f}",
                *cells,
                f"{first['e']:.4f}" if first else "-",
                f"{first['drift']:+.1e}" if first else "-",
                f"{out['load']:.1f}",
            ]
        )

    columns = {
        "atoms": [measured[n]["atoms"] for n in sizes],
        "build CPU s, empty sample cache": [measured[n]["cold"] for n in sizes],
        "build CPU s, samples cached": [measured[n]["warm"] for n in sizes],
        "build peak memory": [measured[n]["peak_mb"] for n in sizes],
    }
    for r in args.ranks:
        runs = [measured[n]["runs"][r] for n in sizes]
        columns[f"steps ({r} rank{'s' * (r > 1)})"] = [run and run["steps"] for run in runs]
        columns[f"LAMMPS s ({r})"] = [run and run["seconds"] for run in runs]
        columns[f"LAMMPS CPU s ({r})"] = [run and run["cpu"] for run in runs]
    tail = sizes[-FIT_TAIL:]
    fits = [
        [
            name,
            exponent(sizes, values),
            exponent(tail, values[-FIT_TAIL:]) if len(sizes) > FIT_TAIL else "-",
        ]
        for name, values in columns.items()
    ]
    body = (
        f"Random disk, seed {args.seed}, {args.gamma:g} degrees, 0.1 c, roughness 0.03 R, "
        f"correlation length {ROUGHNESS_LENGTH:g} R, at the scene's defaults: a wall of 2 N "
        "points, dt auto = 8e-3 sqrt(800 / N) R/c, a R = 300 sqrt(N / 800) (contact_scaling "
        "spacing). "
        "Build: the whole `python -m builder scene` command in its own process, first with "
        "an empty Poisson-disk sample cache, then with the samples it drew; its CPU seconds "
        "(user + system; the machine is shared, so these and not its wall seconds, given "
        "for the empty cache, are the cost), and its peak memory, the larger of the two "
        "processes' maximum resident set size (about 115 MB of it is the imports). "
        f"LAMMPS s: the loop time of the runner's impact (the study's stop rule); LAMMPS "
        "CPU s: the CPU time of lmp (and mpirun) over the whole run, every rank, start-up "
        f"included; each the median of {args.repeats} runs, the rank counts interleaved. "
        "e and the "
        "energy drift are the first rank count's. load: the machine's 1-minute load "
        f"average when the size started ({os.cpu_count()} cores).\n\n"
        + markdown_table(
            [
                "disk points N",
                "atoms",
                "dt, R/c",
                "a R",
                "build CPU s, empty cache",
                "build CPU s, cached",
                "build wall s, empty cache",
                "build peak MB",
                *rank_header,
                "e",
                "energy drift",
                "load",
            ],
            rows,
        )
        + "\n\nPower-law exponents, the slope of log(quantity) against log(N) "
        "(numpy.polyfit):\n\n"
        + markdown_table(
            ["quantity", "all sizes", f"largest {FIT_TAIL} sizes ({tail[0]:,} to {tail[-1]:,})"]
            if len(sizes) > FIT_TAIL
            else ["quantity", "all sizes", f"largest {FIT_TAIL} sizes"],
            fits,
        )
    )
    command = (
        "python bench/resolution_cost.py --sizes "
        + " ".join(map(str, sizes))
        + " --ranks "
        + " ".join(map(str, args.ranks))
        + f" --repeats {args.repeats} --gamma {args.gamma:g} --seed {args.seed}"
        + (" --docs" if args.docs else "")
    )
    print(body)
    title = "What a resolution costs: building and running an impact against N"
    print(f"wrote {write_report('resolution_cost', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
