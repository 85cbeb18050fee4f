"""The study's engine: Dask against the process pool it replaced, and what its
serial parts project at many workers.

    python bench/study_engine.py [--preset demo] [--samples 16] [--angles 16] [--repeats 3]
                                 [--before 1a8c74d] [--tasks 10000] [--docs]

1. The same study (a preset's lattices, samples x angles impacts) run by
   this tree on a local Dask cluster and by the tree at --before (the last
   commit with runner/pool.py), interleaved and repeated, on a Poisson cache
   warmed once before: wall time of the whole command and of the runs.
2. The driver process's CPU time (driver and scheduler) over the impacts,
   from the runs' study.json.
3. On the study's own local cluster: the driver process's CPU share while
   idle (housekeeping h), and Dask's cost per task from --tasks no-op tasks;
   over a task's impacts, the serial time per impact s.
4. The efficiency these project at 16 to 256 workers: a worker needs an
   impact every t seconds, the driver gives one every s with 1 - h of its
   core, so at N workers the efficiency is min(1, (1 - h) t / (N s)).
   Beside it, the partitions path that Dask replaced, bound by its one
   builder process.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.common import ROOT, add_repeats, bench_parser, markdown_table, median, write_report
from ground.checks import Range
from ground.gate import runs_folder
from runner.cluster.driver import job_groups
from runner.cluster.workers import ClusterSpec, dask_client
from runner.study import ANGLES, SAMPLES
from runner.study.studies import load_study

TASKS = Range(100, 1_000_000, integer=True)
# The partitions path's builder (issue 28, measured on this machine): 40 ms
# per impact on a warm Poisson cache, 72 ms cold, against 130 to 180 ms of
# LAMMPS per impact: it fed 130 / 72 = 1.8 to 180 / 40 = 4.5 ranks.
PARTITIONS_FED = (130 / 72, 180 / 40)
WORKERS = (16, 64, 256)


def study_command(preset: str, name: str, samples: int, angles: int) -> list[str]:
    return [sys.executable, "-m", "runner", "study", preset, "--name", name,
            "--samples", str(samples), "--angles", str(angles)]  # fmt: skip


def run(tree: Path, preset: str, name: str, samples: int, angles: int, env: dict) -> dict:
    """One study, from scratch, by the project at ``tree``."""
    shutil.rmtree(runs_folder() / name, ignore_errors=True)
    start = time.monotonic()
    proc = subprocess.run(
        study_command(preset, name, samples, angles),
        cwd=tree,
        env={**env, "PYTHONPATH": str(tree)},  # that tree's packages, not the installed ones
        capture_output=True,
        text=True,
    )
    seconds = time.monotonic() - start
    if proc.returncode not in (0, 1):  # 1: some impacts failed, which the count shows
        raise subprocess.CalledProcessError(proc.returncode, proc.args, proc.stdout, proc.stderr)
    record = json.loads((runs_folder() / name / "study.json").read_text())
    clock = record["wall_clock"]
    impacts = len(list((runs_folder() / name).rglob("result.json")))
    return {"command": seconds, "runs": clock["seconds"], "impacts": impacts, "clock": clock}


def tree_at(revision: str, folder: Path) -> Path:
    """The project at ``revision`` in ``folder``, with this tree's build/ (the
    styles, unchanged since)."""
    subprocess.run(["git", "worktree", "add", "--detach", str(folder), revision], cwd=ROOT,
                   check=True, capture_output=True)  # fmt: skip
    (folder / "build").symlink_to(ROOT / "build")
    return folder


def scheduler_cost(tasks: int, idle: float = 10.0) -> dict:
    """On the study's own local cluster (runner.cluster.workers): the driver
    process's CPU share while idle (Dask's housekeeping, paid per second), and
    per no-op task the wall time and the client and scheduler's CPU time (both
    run in this process)."""
    from distributed import wait

    start = time.perf_counter()
    with dask_client(ClusterSpec()) as client:
        client.submit(int, 0).result()  # workers up
        started = time.perf_counter() - start
        cpu = time.process_time()
        time.sleep(idle)
        housekeeping = (time.process_time() - cpu) / idle
        cpu, start = time.process_time(), time.perf_counter()
        futures = [client.submit(int, i, pure=False) for i in range(tasks)]
        wait(futures)
        wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    return {"wall": wall / tasks, "cpu": cpu / tasks, "housekeeping": housekeeping,
            "start": started}  # fmt: skip


def parser():
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--preset", choices=("demo", "paper"), default="demo",
        help="the study's preset: its lattices and settings (default: demo)",
    )  # fmt: skip
    parser.add_argument(
        "--samples", type=SAMPLES, default=16, help=f"samples, {SAMPLES.describe()} (default: 16)"
    )
    parser.add_argument(
        "--angles", type=ANGLES, default=16, help=f"angles, {ANGLES.describe()} (default: 16)"
    )
    parser.add_argument(
        "--before",
        type=revision,
        default="1a8c74d",
        help="the commit whose process pool is compared (default: 1a8c74d, the last with it)",
    )
    parser.add_argument(
        "--tasks", type=TASKS, default=10_000, help=f"no-op tasks, {TASKS.describe()}"
    )
    add_repeats(parser, 3, "interleaved runs of each engine")
    return parser


def revision(text: str) -> str:
    found = subprocess.run(["git", "rev-parse", "--verify", "--quiet", f"{text}^{{commit}}"],
                           cwd=ROOT, capture_output=True, text=True)  # fmt: skip
    if found.returncode:
        raise ValueError(text)
    return found.stdout.strip()[:12]


revision.__name__ = "commit"
revision.bad_values = ("no-such-commit",)


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="bench-engine-") as tmp:
        before = tree_at(args.before, Path(tmp) / "before")
        # one Poisson cache for every run, warmed by one run first
        env = {**os.environ, "IMPACT_POISSON_CACHE": str(Path(tmp) / "poisson"),
               "IMPACT_RUNS": str(runs_folder())}  # fmt: skip
        trees = {"Dask, local cluster (this tree)": ROOT, f"process pool ({args.before})": before}
        run(ROOT, args.preset, "bench_engine_warm", args.samples, args.angles, env)
        times: dict[str, list[dict]] = {way: [] for way in trees}
        for _ in range(args.repeats):
            for k, (way, tree) in enumerate(trees.items()):
                name = f"bench_engine_{k}"
                times[way].append(run(tree, args.preset, name, args.samples, args.angles, env))
                print(f"{way}: {times[way][-1]['command']:.1f} s", flush=True)
        subprocess.run(["git", "worktree", "remove", "--force", str(before)], cwd=ROOT)
    cost = scheduler_cost(args.tasks)
    impacts = times[next(iter(trees))][0]["impacts"]
    rows = [
        [way, str(runs[0]["impacts"]), f"{median([r['command'] for r in runs]):.1f}",
         f"{median([r['runs'] for r in runs]):.1f}",
         f"{runs[0]['impacts'] / median([r['runs'] for r in runs]) * 60:.0f}"]
        for way, runs in times.items()
    ]  # fmt: skip
    ours = times[next(iter(trees))]
    ratio = median([r["command"] for r in times[f"process pool ({args.before})"]]) / median(
        [r["command"] for r in ours]
    )
    driver = median([r["clock"]["driver_cpu_seconds"] / r["impacts"] for r in ours])
    per_impact = median([sum(r["clock"]["worker_seconds"].values()) / r["impacts"] for r in ours])
    lattices = load_study(args.preset).lattices
    synthetic = [{"seed": s, "lattice": la, "folder": f"{la}/{s}/{g}"} for s in range(args.samples)
                 for la in lattices for g in range(args.angles)]  # fmt: skip
    groups = len(synthetic) // len(job_groups(synthetic, os.cpu_count() or 1))
    # what grows with the impacts: the client's and scheduler's CPU per task,
    # over a task's impacts (the driver's whole CPU time also holds the
    # housekeeping, paid per second)
    serial = cost["cpu"] / groups
    projection = []
    for n in WORKERS:
        efficiency = min(1.0, (1 - cost["housekeeping"]) * per_impact / (n * serial))
        partitions = [min(1.0, fed / n) for fed in PARTITIONS_FED]
        projection.append([str(n), f"{efficiency:.2f}",
                           f"{partitions[0]:.2f} to {partitions[1]:.2f}"])  # fmt: skip
    body = (
        f"The {args.preset} preset's lattices ({', '.join(load_study(args.preset).lattices)}), "
        f"{args.samples} samples x {args.angles} angles ({impacts} "
        f"impacts), default settings, 2 local workers each way (the machine's cores), on a "
        f"Poisson cache warmed by one run before; medians of {args.repeats} interleaved runs. "
        "Command: the whole `python -m runner study` command; runs: the study's own "
        "wall clock (study.json), from the first submission to the last result.\n\n"
        + markdown_table(["engine", "impacts", "command s", "runs s", "impacts per minute"], rows)
        + f"\n\nThe process pool took {ratio:.2f} times Dask's time for the whole command. "
        f"Dask's runs include starting the local cluster, {cost['start']:.1f} s here (its "
        "scheduler, a nanny and a worker process per core, up to the first task's result), "
        "which the pool's processes did not need.\n\n"
        "## Serial time per impact\n\n"
        + markdown_table(
            ["", "per impact", "share of an impact's worker time"],
            [
                [
                    "an impact on a worker (build, LAMMPS, analysis)",
                    f"{per_impact * 1e3:.0f} ms",
                    "1",
                ],
                [
                    "the driver process (driver and scheduler), CPU, all of it",
                    f"{driver * 1e3:.2f} ms",
                    f"{driver / per_impact:.2%}",
                ],
                [
                    f"Dask, a no-op task ({args.tasks:,} tasks), wall",
                    f"{cost['wall'] * 1e3:.2f} ms",
                    f"{cost['wall'] / per_impact:.2%}",
                ],
                [
                    f"Dask, a no-op task ({args.tasks:,} tasks), client and scheduler CPU",
                    f"{cost['cpu'] * 1e3:.2f} ms",
                    f"{cost['cpu'] / per_impact:.2%}",
                ],
                [
                    f"... over a task's {groups} impacts: the serial part, s",
                    f"{serial * 1e3:.3f} ms",
                    f"{serial / per_impact:.3%}",
                ],
            ],
        )  # fmt: skip
        + f"\n\nA task is {groups} impacts (runner.cluster.driver.job_groups), so Dask's cost per "
        f"impact is a {groups}th of a task's. Idle, the driver process (a local cluster's "
        f"scheduler with the study's settings, runner.cluster.workers.HOUSEKEEPING) uses "
        f"{cost['housekeeping']:.1%} of a core: its heartbeats and health checks, paid per "
        "second whatever the impacts, so its share per impact falls as workers are added. "
        "The serial part s is what grows with the impacts: Dask's CPU time per task "
        "(client and scheduler) over a task's impacts.\n\n"
        "## Projected efficiency\n\n"
        f"Efficiency min(1, (1 - h) t / (N s)) with h = {cost['housekeeping']:.3f} of a core, "
        f"t = {per_impact * 1e3:.0f} ms per impact on a worker "
        f"and s = {serial * 1e3:.3f} ms of the driver process per impact; the partitions path "
        "was bound by its one builder process, which fed 1.8 to 4.5 ranks (40 to 72 ms per "
        "impact against 130 to 180 ms of LAMMPS). On paper, from the figures above: a real "
        "cluster adds its network and file system.\n\n"
        + markdown_table(["workers", "Dask (this tree)", "partitions (before)"], projection)
    )
    command = (
        f"python bench/study_engine.py --preset {args.preset} --samples {args.samples} "
        f"--angles {args.angles} "
        f"--before {args.before} --tasks {args.tasks} --repeats {args.repeats}"
        + (" --docs" if args.docs else "")
    )
    print(body)
    print(f"wrote {write_report('study_engine', 'The study engine', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
