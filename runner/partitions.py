"""The study on LAMMPS partitions: mpirun -np P lmp -partition Px1 -in decks/sweep.lmp.

Scenes are built a batch at a time into their impact folders, linked as
1..N into a batch folder, and run by the partitions, which share them out as
they go. After the batch the outputs are analysed like any run's. An error in
one impact ends the whole MPI job (Debian's LAMMPS cannot catch it): the impact
that has started but not finished is marked failed, the ones not started stay
pending, and the next batch goes on.

The MPI job runs in a process group of its own, so that stopping the study
(SIGINT, SIGTERM: runner.stopping) ends mpirun and every rank with it.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import shutil
import signal
import subprocess
from pathlib import Path

from analysis.result import analyse_run, write_json_atomically

from .impact import git_revision
from .lammps_run import (
    ROOT,
    LammpsError,
    lammps_error,
    lammps_version,
    mpi_environment,
    mpi_launcher,
)
from .stopping import as_worker
from .study import Progress, Study, mark_failed, prune, state

SWEEP = ROOT / "decks" / "sweep.lmp"


def finished(folder: Path) -> bool:
    """The deck writes the last row of energy.dat when an impact ends well."""
    energy = folder / "energy.dat"
    return energy.exists() and len(energy.read_text().splitlines()) == 3


def build_scenes(study: Study, jobs: list[dict]) -> None:
    for job in jobs:
        study.build(job)


def run_group(command: list[str], **kwargs) -> subprocess.CompletedProcess:
    """subprocess.run in a new process group, which is ended whole if this
    process is interrupted (subprocess.run would SIGKILL only mpirun, whose
    ranks would run on)."""
    with subprocess.Popen(
        command,
        start_new_session=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **kwargs,
    ) as process:
        try:
            stdout, stderr = process.communicate()
        except BaseException:
            os.killpg(process.pid, signal.SIGTERM)  # mpirun passes it on to the ranks
            try:
                process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
            try:
                os.killpg(process.pid, signal.SIGKILL)  # whatever is left of the group
            except ProcessLookupError:
                pass
            process.wait()
            raise
    return subprocess.CompletedProcess(command, process.returncode, stdout, stderr)


def run_batch(study: Study, jobs: list[dict], partitions: int, batch: Path) -> int:
    """Run ``jobs``, whose scenes are built, on the partitions; return how many
    finished or failed."""
    shutil.rmtree(batch, ignore_errors=True)
    batch.mkdir(parents=True)
    for k, job in enumerate(jobs, start=1):
        (batch / str(k)).symlink_to(Path(job["folder"]).resolve())
    partitions = min(partitions, len(jobs))  # a universe loop needs a job per partition
    variables = study.options.deck_variables()
    command = mpi_launcher(partitions) + [
        "lmp",
        "-partition",
        f"{partitions}x1",
        "-in",
        str(SWEEP),
        "-plog",
        str(batch / "log"),
        "-log",
        "none",
        "-pscreen",
        "none",
        "-nocite",
        "-var",
        "batch",
        str(batch),
        "-var",
        "count",
        str(len(jobs)),
    ]
    for name, value in variables.items():
        command += ["-var", name, value]
    launched = run_group(command, cwd=ROOT, env=mpi_environment())
    (ROOT / "tmp.lammps.variable").unlink(missing_ok=True)  # the universe loop's counter
    logs = sorted(batch.glob("log.*"))
    version = lammps_version(logs[0]) if logs else "unknown"
    errors = [e for e in (lammps_error(log, "") for log in logs) if e]
    settled = 0
    for job in jobs:
        folder = Path(job["folder"])
        settled += finished(folder) or (folder / "series.dat").exists()
        if finished(folder):
            clock = [float(t) for t in (folder / "clock.txt").read_text().split()]
            run = {
                "options": study.options.as_dict(),
                "wall_seconds": clock[1] - clock[0],
                "lammps_version": version,
                "git_revision": git_revision(),
                "partitions": partitions,
            }
            write_json_atomically(run, folder / "run.json")
            write_json_atomically(analyse_run(folder), folder / "result.json")
            prune(folder)
        elif (folder / "series.dat").exists():  # it was running when the job ended
            mark_failed(job, errors[0] if errors else "the MPI job ended during this impact")
        else:  # never started: next batch
            shutil.rmtree(folder, ignore_errors=True)
    if not settled:
        raise LammpsError(
            "the MPI job ended before any impact started: "
            + (errors[0] if errors else launched.stderr.strip()[-2000:])
        )
    shutil.rmtree(batch, ignore_errors=True)
    return settled


def run_study_partitions(
    study: Study, partitions: int, retry_failed: bool = False, batch_size: int = 16
) -> dict:
    """Run every unfinished impact of the study on ``partitions`` LAMMPS partitions."""
    jobs = study.prepare(retry_failed)
    progress = Progress(len(jobs), sum(state(j) != "pending" for j in jobs))
    size = batch_size * partitions
    # The next batch's scenes are built while LAMMPS runs this one; leaving
    # the block, however, terminates the builder.
    with mp.get_context("fork").Pool(1, initializer=as_worker) as builder:
        while todo := [j for j in jobs if state(j) == "pending"]:
            batches = [todo[i : i + size] for i in range(0, len(todo), size)]
            building = builder.apply_async(build_scenes, (study, batches[0]))
            for k, batch in enumerate(batches):
                building.get()
                if k + 1 < len(batches):
                    building = builder.apply_async(build_scenes, (study, batches[k + 1]))
                run_batch(study, batch, partitions, study.folder / ".batch")
                progress.failed = sum(state(j) == "failed" for j in jobs)
                progress(sum(state(j) != "pending" for j in jobs) - progress.already)
    return {**study.summary(jobs), "ran": len(jobs) - progress.already}
