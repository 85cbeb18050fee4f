"""The study's driver: it submits groups of impacts to a Dask cluster, records
what comes back and reports progress. The workers do everything else
(runner.cluster.tasks), so the driver's time per impact stays small however many
workers there are.
"""

from __future__ import annotations

import time
from dataclasses import replace

from ground.gate import remove

from ..study import Study
from ..study.folders import state
from ..study.lock import made_by_lock, study_lock
from ..study.sample_bodies import BODIES_FOLDER
from .tasks import MAX_ATTEMPTS, WORKER_PHASES, group_task
from .workers import ClusterSpec, ClusterUnavailable, dask_client, replace_ended_jobs

PROGRESS_EVERY = 10.0  # seconds between progress lines


class WorkerTime:
    """The seconds of WORKER_PHASES summed over the impacts a study ran."""

    def __init__(self) -> None:
        self.seconds = dict.fromkeys(WORKER_PHASES, 0.0)
        self.steps = 0

    def add(self, value: dict) -> None:
        for phase in WORKER_PHASES:
            self.seconds[phase] += value[phase]
        self.steps += value["steps"]

    def line(self) -> str:
        total = sum(self.seconds.values()) or 1.0
        parts = ", ".join(
            f"{phase} {s:.0f} s ({100 * s / total:.0f} %)" for phase, s in self.seconds.items()
        )
        rate = self.steps / self.seconds["lammps"] if self.seconds["lammps"] else 0.0
        return f"workers' time: {parts}; LAMMPS {rate:,.0f} steps per second per worker"


class Progress:
    """done / total, failed, rate and time left, on one line."""

    def __init__(self, total: int, already: int):
        self.total, self.already, self.start = total, already, time.monotonic()
        self.done = self.failed = self.stuck = 0

    def line(self) -> str:
        elapsed = time.monotonic() - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        left = (self.total - self.already - self.done) / rate if rate > 0 else float("nan")
        stuck = f", {self.stuck} on the wall at tmax" if self.stuck else ""
        return (
            f"  {self.already + self.done}/{self.total} impacts ({self.failed} failed{stuck}), "
            f"{rate * 60:.0f} per minute, {left / 60:.1f} min left"
        )


def job_groups(jobs: list[dict], workers: int) -> list[list[int]]:
    """Indices of ``jobs`` in the groups a worker takes whole.

    A whole sample (every lattice and angle of a seed) if there are enough
    samples to keep every worker busy to near the end: its bodies are built
    once, and its wall, which the lattices share, once for all. Otherwise a
    lattice of a sample, or single impacts. Largest first, for the same reason.
    """
    keys = (lambda j: j["seed"], lambda j: (j["seed"], j["lattice"]), lambda j: j["folder"])
    for key in keys:
        groups: dict = {}
        for index, job in enumerate(jobs):
            groups.setdefault(key(job), []).append(index)
        if len(groups) >= 8 * workers:  # so the last groups leave little idle time
            break
    return sorted(groups.values(), key=len, reverse=True)


def run_study(
    study: Study,
    workers: int | None = None,
    retry_failed: bool = False,
    *,
    client=None,
    cluster: ClusterSpec | None = None,
) -> dict:
    """Run every impact of the study that is not settled; returns counts.

    Parameters
    ----------
    study : Study
        The study; its folder is runs/<name>.
    workers : int, optional
        Worker processes of a local Dask cluster (default: this machine's cores).
    retry_failed : bool
        Run again the impacts that failed before.
    client : distributed.Client, optional
        Run on this client's cluster (a notebook's, a dask-mpi allocation's).
    cluster : ClusterSpec, optional
        The cluster to make or join (runner.cluster.workers); ``workers`` is its
        shorthand for a local one. Its workers own the study's MPI ranks
        per impact (``study.options.nprocs``) each; ranks they cannot hold
        are refused before anything is written.

    Returns
    -------
    dict
        Counts of the study's impacts: done, failed, pending (``Study.summary``),
        ran (how many were to run), and where the workers' and the driver's
        time went.
    """
    spec = replace(cluster or ClusterSpec(workers=workers), ranks=study.options.nprocs)
    if client is None:
        spec.check_ranks()
    created = not study.folder.exists() or made_by_lock(study.folder)
    with study_lock(study.folder):  # one run per study folder (its command's, if it holds it)
        return run_locked(study, spec, retry_failed, client, created)


def run_locked(study: Study, spec: ClusterSpec, retry_failed: bool, client, created: bool) -> dict:
    """``run_study`` with the study folder's lock held."""
    jobs = study.prepare(retry_failed)
    todo = [j for j in jobs if state(j) == "pending"]
    told = (
        f"study {study.name}: {len(jobs)} impacts, {len(jobs) - len(todo)} already done or "
        f"failed, {len(todo)} to run"
    )
    counts = {"ran": len(todo), "worker_seconds": dict.fromkeys(WORKER_PHASES, 0.0)}
    try:
        if not todo or client is not None:
            print(told, flush=True)
        if todo:
            if client is not None:
                counts.update(drive(study, jobs, todo, client))
            else:
                with dask_client(spec) as own:  # said once the cluster is there
                    print(told, flush=True)
                    counts.update(drive(study, jobs, todo, own, spec.size()))
    except ClusterUnavailable:
        if created:  # nothing ran: the study's name stays free
            remove(study.folder)
        raise
    finally:
        # the workers' scratch (runner.study.SampleBodies), also what workers
        # that crashed left: no task of this study runs any more
        remove(study.folder / BODIES_FOLDER)
    return {**study.summary(jobs), **counts}


def drive(study: Study, jobs: list[dict], todo: list[dict], client, workers: int = 0) -> dict:
    """Submit ``todo`` in groups to ``client``'s cluster and wait for them.
    ``workers``: how many the cluster will have (0: as many as it has now)."""
    from distributed import wait
    from distributed.scheduler import KilledWorker

    cpu_start = time.process_time()  # this process: the driver, and a scheduler made here
    if not workers:
        client.wait_for_workers(1)
        workers = sum(client.nthreads().values())
    groups = [[todo[i] for i in group] for group in job_groups(todo, workers)]
    ranks = f", {study.options.nprocs} MPI ranks each" if study.options.nprocs > 1 else ""
    print(f"  on {workers} Dask workers{ranks}; dashboard: {client.dashboard_link}", flush=True)
    progress = Progress(len(jobs), len(jobs) - len(todo))
    spent = WorkerTime()
    # A scheduler gives a task up when workers died running it (a joined
    # cluster's allowed-failures); the driver submits it again and the
    # impacts' folders decide. A worker dies with every task it holds, so a
    # task can be given up behind other impacts' crashes however often: the
    # bound is on the deaths, and each impact can end at most MAX_ATTEMPTS
    # workers at each of its steps (runner.cluster.tasks). More deaths than
    # that are a cluster whose workers die before they start any impact.
    deaths: set[str] = set()
    most_deaths = len(todo) * MAX_ATTEMPTS * (1 + study.options.barrier_halvings)
    again = 0
    prefix = f"impacts-{study.name}"  # the dashboard groups tasks by it
    batch_jobs = len(getattr(getattr(client, "cluster", None), "worker_spec", None) or {})
    pending = {
        client.submit(group_task, study, group, pure=False, key=f"{prefix}-{index}"): index
        for index, group in enumerate(groups)
    }
    last = time.monotonic()
    while pending:
        try:
            finished, _ = wait(list(pending), timeout=PROGRESS_EVERY, return_when="FIRST_COMPLETED")
        except TimeoutError:
            finished = set()
        for future in finished:
            index = pending.pop(future)
            try:
                # never without a timeout: a result held by a worker that has
                # since ended (a cancelled batch job) is computed again, which
                # needs a worker, which the next tick's replacement provides
                outcomes = future.result(timeout=PROGRESS_EVERY)
            except TimeoutError:
                pending[future] = index  # still wanted: not released
                continue
            except KilledWorker as error:  # a joined cluster gave the task up: its impacts decide
                future.release()
                deaths.add(error.last_worker.address)
                if len(deaths) > most_deaths:
                    raise
                again += 1
                key = f"{prefix}-{index}-again{again}"
                resubmitted = client.submit(group_task, study, groups[index], pure=False, key=key)
                pending[resubmitted] = index
                continue
            except BaseException:
                future.release()
                raise
            future.release()  # a result no worker holds is not computed again
            for outcome in outcomes:
                if outcome["state"] == "settled":
                    continue
                if outcome["state"] == "disk":  # a full disk, a read-only folder: stop here
                    raise OSError(*outcome["error"])
                progress.done += 1
                if outcome["state"] in ("failed", "stuck"):
                    progress.failed += outcome["state"] == "failed"
                    progress.stuck += outcome["state"] == "stuck"
                    report_failure(outcome)
                else:
                    spent.add(outcome)
        if time.monotonic() - last >= PROGRESS_EVERY or not pending:
            print(progress.line(), flush=True)
            last = time.monotonic()
            if pending and (replaced := replace_ended_jobs(client, batch_jobs)):
                print(f"  {replaced} batch job(s) ended; as many submitted again", flush=True)
    print(spent.line(), flush=True)
    return {
        "worker_seconds": spent.seconds,
        "workers": workers,
        "driver_cpu_seconds": time.process_time() - cpu_start,
    }


def report_failure(outcome: dict) -> None:
    said = "failed" if outcome["state"] == "failed" else "on the wall at tmax"
    print(
        f"  {said}: {outcome['lattice']} seed {outcome['seed']} gamma {outcome['gamma']}: "
        f"{outcome['error']}",
        flush=True,
    )
