"""Worker processes that survive crashing jobs.

Debian's LAMMPS has no C++ exceptions: a LAMMPS error ends the process that
runs it. Each worker here is a long-lived process that takes a group of jobs
(the impacts of one sample, which share their bodies) and runs them in-process
one after another (no program to start per impact), sending each result back
before it starts the next. When a worker dies, the first job of its group
without a result is the one that killed it: the parent records it as failed,
puts the rest of the group back in the queue, and starts a new worker.

Each worker talks to the parent through its own pipe, whose sends are
synchronous: a worker that dies cannot lose a result it has sent, nor leave a
lock held that the others need (as a shared multiprocessing.Queue can).

Whatever ends run_jobs (an exception, SIGINT or SIGTERM turned into one by
runner.stopping), its workers are stopped before it returns; a worker whose
parent is gone without a word (SIGKILL) exits after its current job.
"""

from __future__ import annotations

import collections
import multiprocessing as mp
import os
import time
from collections.abc import Callable, Sequence
from multiprocessing.connection import wait

from .stopping import as_worker


def _work(function, jobs, connection, parent: int):
    as_worker()
    try:
        while True:
            # No EOF comes if the parent dies: the workers forked after this
            # one hold copies of the pipe's other end. Hence the parent check.
            while not connection.poll(1.0):
                if os.getppid() != parent:
                    return
            indices = connection.recv()
            if indices is None:
                return
            for index in indices:
                try:
                    message = ("done", index, function(jobs[index]))
                except Exception as error:  # a Python error in the job: report, go on
                    message = ("error", index, f"{type(error).__name__}: {error}")
                connection.send(message)
    except (BrokenPipeError, EOFError):  # the parent is gone
        return


class _Worker:
    def __init__(self, context, function, jobs):
        self.connection, child = context.Pipe()
        self.process = context.Process(
            target=_work, args=(function, jobs, child, os.getpid()), daemon=True
        )
        self.process.start()
        child.close()
        self.todo: list[int] = []  # the group's jobs not yet reported

    def give(self, indices: list[int]) -> None:
        self.todo = list(indices)
        self.connection.send(self.todo)


def run_jobs(
    function: Callable,
    jobs: Sequence,
    groups: Sequence[Sequence[int]],
    workers: int,
    on_done: Callable[[int, object], None],
    on_failed: Callable[[int, str], None],
    on_progress: Callable[[int], None] | None = None,
    progress_every: float = 10.0,
) -> None:
    """Run ``function(jobs[i])`` for every job, a group at a time per worker;
    call on_done(i, value) or on_failed(i, message) for each, in this process."""
    context = mp.get_context("fork")
    queued = collections.deque(list(g) for g in groups if g)
    remaining = sum(len(g) for g in queued)
    running: list[_Worker] = []

    def report(worker: _Worker, kind: str, index: int, value) -> None:
        nonlocal remaining
        worker.todo.remove(index)
        remaining -= 1
        (on_done if kind == "done" else on_failed)(index, value)

    def feed(worker: _Worker) -> None:
        if queued:
            worker.give(queued.popleft())

    try:
        for _ in range(max(1, min(workers, len(queued)))):
            running.append(_Worker(context, function, jobs))
            feed(running[-1])
        last = time.monotonic()
        while remaining:
            ready = wait(
                [w.connection for w in running] + [w.process.sentinel for w in running],
                timeout=progress_every,
            )
            for worker in list(running):
                if worker.connection in ready or worker.process.sentinel in ready:
                    try:
                        while worker.connection.poll():
                            report(worker, *worker.connection.recv())
                    except (EOFError, OSError):
                        pass
                    if not worker.process.is_alive():
                        worker.process.join()
                        running.remove(worker)
                        if worker.todo:  # the job it died in; the rest go back
                            crashed, *rest = worker.todo
                            report(
                                worker,
                                "error",
                                crashed,
                                "the run ended its process "
                                f"(exit status {worker.process.exitcode})",
                            )
                            if rest:
                                queued.appendleft(rest)
                        if queued:
                            running.append(_Worker(context, function, jobs))
                            feed(running[-1])
                    elif not worker.todo:
                        feed(worker)
            if on_progress and time.monotonic() - last > progress_every:
                on_progress(sum(len(g) for g in groups) - remaining)
                last = time.monotonic()
        for worker in running:
            worker.connection.send(None)
            worker.process.join(timeout=5)
    finally:
        _stop(running)  # whatever ended the loop: no worker outlives it
    if on_progress:
        on_progress(sum(len(g) for g in groups))


def _stop(running: list[_Worker]) -> None:
    """End every worker still running: SIGTERM, then SIGKILL if it lingers."""
    for worker in running:
        if worker.process.is_alive():
            worker.process.terminate()
    for worker in running:
        worker.process.join(timeout=5)
        if worker.process.is_alive():
            worker.process.kill()
            worker.process.join()
