"""Where a study's workers come from: a Dask cluster on this machine, Slurm
jobs (dask-jobqueue), or a Dask cluster that is already running.

Every worker is a process with one thread: LAMMPS runs in it, in-process, and
an error of Debian's LAMMPS ends the process, which the worker's nanny starts
again. A study whose impacts run on k MPI ranks each (``ranks``) has a worker
per k cores instead, which runs lmp under mpirun (in a Slurm job, under
``srun --mpi=pmix``, a step of the job's own cores) and waits for it. What
the cluster's scheduler counts as failures does not decide anything here
(runner.cluster.tasks does): clusters made here let a task be retried
ALLOWED_FAILURES times before the scheduler gives it up.
"""

from __future__ import annotations

import contextlib
import logging
import os
import shutil
import subprocess
import sys
import tempfile
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from ground.checks import Range
from ground.errors import InputError

CLUSTERS = ("local", "slurm")
WORKERS = Range(1, 1_024, integer=True)
JOBS = Range(1, 10_000, integer=True)
CORES_PER_JOB = Range(1, 1_024, integer=True)
# A worker that dies takes the tasks it held with it, and the scheduler counts
# a failure against each (runner.cluster.tasks); this only keeps the scheduler from
# giving a task up before runner.cluster.tasks has settled its impacts.
ALLOWED_FAILURES = 1_000
# Housekeeping at a slower pace than Dask's defaults (20 ms, 500 ms, 100 ms):
# an idle LocalCluster then costs the driver's process 1 % of a core rather
# than 3 % (measured on 2 cores), and nothing here needs finer health checks.
HOUSEKEEPING = {
    "distributed.admin.tick.interval": "200ms",
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.worker.memory.monitor-interval": "1s",
}
# Environment a Slurm job's workers need from this process: the project's
# folders (runs, the Poisson cache) and Open MPI's leave to run as root.
# How long Slurm's sbatch may take to answer, checking the job (--test-only)
# and submitting it: a study whose scheduler does not answer ends within a
# minute, with nothing left behind (runner.cluster.driver.run_study).
SBATCH_SECONDS = 25
# How long joining a running cluster may take (--scheduler).
JOIN_SECONDS = 30
PASSED_ON = ("IMPACT_RUNS", "IMPACT_POISSON_CACHE", "OMPI_ALLOW_RUN_AS_ROOT",
             "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM")  # fmt: skip
# How a Slurm job's workers start an impact's ranks (ground.launch.mpi_launcher)
# unless IMPACT_MPIRUN says otherwise: a step of the job's own cores. OpenMPI's
# direct launch needs PMIx; a plain srun fails on Debian 12's Slurm 22.05.
SLURM_MPIRUN = "srun --mpi=pmix"


class ClusterUnavailable(InputError):
    """The cluster asked for cannot be made or joined: nothing has run."""


@dataclass(frozen=True)
class ClusterSpec:
    """Which workers: ``kind`` local or slurm, or ``scheduler`` to join one."""

    kind: str = "local"
    workers: int | None = None  # local: worker processes (None: this machine's cores)
    jobs: int = 1  # slurm: batch jobs
    cores_per_job: int = 1  # slurm: cores per job, a worker process per `ranks` of them
    walltime: str | None = None  # slurm: HH:MM:SS (None: dask-jobqueue's config)
    queue: str | None = None
    account: str | None = None
    memory: str | None = None  # slurm: per job (None: the site's default, --mem left out)
    scheduler: str | None = None  # a running cluster's address or scheduler file
    log_directory: Path | None = None  # slurm: the jobs' output files
    ranks: int = 1  # MPI ranks per impact: cores each worker owns (the study's)

    def size(self) -> int:
        """How many workers the spec asks for (a joined cluster: 0, unknown)."""
        if self.scheduler:
            return 0
        if self.kind == "slurm":
            return self.jobs * (self.cores_per_job // self.ranks)
        return self.workers or max(1, (os.cpu_count() or 1) // self.ranks)

    def check_ranks(self) -> None:
        """Refuse ranks that its workers' cores cannot hold: more than this
        machine's cores (local, with --workers: workers x ranks), or not a
        divisor of --cores-per-job (slurm). A joined cluster's are its own.

        Raises
        ------
        ground.errors.InputError
            One line naming --ranks, the cores and what would fit.
        """
        said = f"ranks {self.ranks} (--ranks, or the study file's [run] ranks)"
        if self.scheduler or self.ranks == 1:
            return
        if self.kind == "slurm":
            if self.cores_per_job % self.ranks:
                raise InputError(
                    f"{said}: --cores-per-job must be a multiple of it (each worker owns "
                    f"ranks cores of its job), got {self.cores_per_job}"
                )
            return
        cores = os.cpu_count() or 1
        if self.ranks > cores:
            raise InputError(f"{said} must be at most this machine's {cores} cores")
        if self.workers and self.workers * self.ranks > cores:
            raise InputError(
                f"--workers {self.workers} x {said} = {self.workers * self.ranks} cores, more "
                f"than this machine's {cores}: give --workers {cores // self.ranks} or leave it out"
            )


def worker_environment(ranks: int = 1) -> list[str]:
    """Shell lines a Slurm job runs before its workers: this interpreter's
    folder first on PATH (the lammps module's and lmp's Python), PASSED_ON,
    and for impacts on several ranks IMPACT_MPIRUN (this process's, or
    SLURM_MPIRUN)."""
    lines = [f'export PATH="{Path(sys.executable).parent}:$PATH"']
    lines += [f'export {name}="{os.environ[name]}"' for name in PASSED_ON if name in os.environ]
    if ranks > 1:
        lines.append(f'export IMPACT_MPIRUN="{os.environ.get("IMPACT_MPIRUN") or SLURM_MPIRUN}"')
    return lines


def make_cluster(spec: ClusterSpec):
    """A new Dask cluster for ``spec`` (not for a joined one)."""
    # Another dashboard on 8787 (a second study): Dask takes a free port, and
    # the driver prints the address it took; its warning would say it again.
    warnings.filterwarnings("ignore", message="Port 8787 is already in use", category=UserWarning)
    if spec.kind == "local":
        from distributed import LocalCluster

        return LocalCluster(
            n_workers=spec.size(),
            threads_per_worker=1,
            processes=True,
            # CRITICAL, not ERROR: on a signal the scheduler in this process
            # closes first, and a worker's heartbeat racing it logged a
            # traceback at ERROR into the study's one-line stderr; an
            # impact's own failure comes back through its future anyway
            silence_logs=logging.CRITICAL,
            dashboard_address=":8787",  # or a free port, if that one is taken
        )
    from dask_jobqueue import SLURMCluster

    if shutil.which("sbatch") is None:
        raise ClusterUnavailable(
            "--cluster slurm: Slurm's sbatch is not on PATH (docs/cluster.md: run on a "
            "machine of the cluster, or join a running Dask cluster with --scheduler)"
        )
    options = {"walltime": spec.walltime, "queue": spec.queue, "account": spec.account}
    if spec.log_directory:
        spec.log_directory.mkdir(parents=True, exist_ok=True)
    workers = spec.cores_per_job // spec.ranks
    cluster = SLURMCluster(
        cores=workers,
        processes=workers,  # one thread per worker
        job_cpu=spec.cores_per_job,  # --cpus-per-task: a worker's ranks are srun steps of these
        # Dask's memory limit needs a figure; Slurm's --mem is left to the
        # site's default unless --memory is given
        memory=spec.memory or f"{spec.cores_per_job}GiB",
        job_directives_skip=[] if spec.memory else ["--mem"],
        python=sys.executable,
        job_script_prologue=worker_environment(spec.ranks),
        log_directory=str(spec.log_directory) if spec.log_directory else None,
        silence_logs=logging.ERROR,
        scheduler_options={"dashboard_address": ":8787"},
        **{key: value for key, value in options.items() if value is not None},
    )
    try:
        test_job(cluster.job_script())
        cluster.scale(jobs=spec.jobs)
        # submit now, not in the background: a failing sbatch is then known at
        # once, not repeated for ever while the study waits for workers
        cluster.sync(cluster._correct_state, callback_timeout=SBATCH_SECONDS)
    except BaseException as error:
        with contextlib.suppress(Exception):
            cluster.close()
        if isinstance(error, ClusterUnavailable):
            raise
        if not isinstance(error, Exception):
            raise  # a signal (runner.stopping)
        raise ClusterUnavailable(
            f"--cluster slurm: sbatch could not submit the jobs: {first_line(error)}"
        ) from None
    return cluster


def first_line(error: BaseException) -> str:
    """An error's most telling line: Slurm's last error (or fatal), else its first line."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    told = [
        line
        for line in lines
        if ("error" in line.lower() or "fatal" in line.lower()) and "exit code" not in line
    ]
    return told[-1] if told else (lines or [type(error).__name__])[0]


def test_job(script: str) -> None:
    """Ask Slurm whether it would take the job (sbatch --test-only, which
    submits nothing), within SBATCH_SECONDS.

    Raises
    ------
    ClusterUnavailable
        With sbatch's error (an unknown partition or account, a walltime over
        the limit, no controller), or if it did not answer in time.
    """
    with tempfile.NamedTemporaryFile("w", suffix=".sh") as handle:
        handle.write(script)
        handle.flush()
        try:
            proc = subprocess.run(
                ["sbatch", "--test-only", handle.name],
                capture_output=True,
                text=True,
                timeout=SBATCH_SECONDS,
            )
        except subprocess.TimeoutExpired:
            raise ClusterUnavailable(
                f"--cluster slurm: sbatch did not answer within {SBATCH_SECONDS} s "
                "(is Slurm's controller up and reachable?)"
            ) from None
        except OSError as error:
            raise ClusterUnavailable(f"--cluster slurm: sbatch cannot run ({error})") from None
    if proc.returncode != 0:
        raise ClusterUnavailable(
            f"--cluster slurm: sbatch refuses the job: {first_line(RuntimeError(proc.stderr))}"
        )


# Slurm's states of a job that has not ended.
LIVE_STATES = "PENDING,RUNNING,CONFIGURING,COMPLETING,SUSPENDED,REQUEUED,RESIZING"


def replace_ended_jobs(client, wanted: int) -> int:
    """Submit a new batch job for each of the client's cluster's jobs that has
    ended (a walltime, scancel) while the study runs, up to ``wanted`` jobs;
    returns how many were submitted.

    dask-jobqueue keeps an ended job of several workers in its plan, or drops
    it without replacing it, depending on when it notices (seen with
    dask-jobqueue 0.9.0 on Slurm 22.05), so neither scale() nor adapt() is
    enough alone.
    """
    cluster = getattr(client, "cluster", None)
    if not hasattr(cluster, "job_cls") or not wanted:
        return 0
    jobs = {name: job for name, job in cluster.workers.items()
            if getattr(job, "job_id", None)}  # fmt: skip
    live: set[str] = set()
    if jobs:
        listed = subprocess.run(
            ["squeue", "--noheader", "--format=%i", f"--states={LIVE_STATES}",
             f"--jobs={','.join(job.job_id for job in jobs.values())}"],
            capture_output=True, text=True,
        )  # fmt: skip
        if listed.returncode not in (0, 1):  # 1: none of them is known any more
            return 0
        live = set(listed.stdout.split())
    for name in [name for name, job in jobs.items() if job.job_id not in live]:
        cluster.worker_spec.pop(name, None)  # forgotten, so that a new job may take the name
        cluster.loop.add_callback(cluster.workers.pop(name).close)
    for name in [name for name in cluster.worker_spec if name not in cluster.workers]:
        cluster.worker_spec.pop(name)  # planned, but its job is gone
    missing = wanted - len(cluster.workers)
    if missing > 0:
        cluster.scale(jobs=wanted)
    return max(missing, 0)


@contextlib.contextmanager
def dask_client(spec: ClusterSpec) -> Iterator:
    """A Client of the cluster ``spec`` names; a cluster made here is closed
    (local workers end, Slurm jobs are cancelled) whatever ends the block."""
    import dask
    from distributed import Client

    settings = {"distributed.scheduler.allowed-failures": ALLOWED_FAILURES, **HOUSEKEEPING}
    with dask.config.set(settings):
        if spec.scheduler:
            target = spec.scheduler
            try:
                client = (
                    Client(scheduler_file=target, timeout=f"{JOIN_SECONDS}s")
                    if Path(target).is_file()
                    else Client(target, timeout=f"{JOIN_SECONDS}s")
                )
            except Exception as error:  # unreachable, or what answers is not Dask's
                said = first_line(error) if str(error) else type(error).__name__
                raise ClusterUnavailable(f"--scheduler {target}: cannot join it ({said})") from None
            with client:
                yield client
            return
        cluster = make_cluster(spec)
        try:
            with Client(cluster) as client:
                yield client
        finally:
            cluster.close()
