"""Stopping a study on SIGINT (Ctrl-C) and SIGTERM (kill, a batch system's time limit).

The study's process turns either signal into a ``Stopped`` exception, so that
the ``finally`` blocks of the drivers stop their workers and MPI jobs before
it exits; ``python -m runner`` then prints one line. The workers themselves
ignore SIGINT (a terminal sends it to the whole process group, and LAMMPS,
busy in C, would only see it at the end of the impact) and die at once on
SIGTERM, which is how the study's process stops them.
"""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Stopped(Exception):
    """The study's process received SIGINT or SIGTERM."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _stop(signum: int, frame) -> None:
    # A second signal during the clean-up would interrupt it half-way.
    for number in SIGNALS:
        signal.signal(number, signal.SIG_IGN)
    raise Stopped(signum)


@contextlib.contextmanager
def stop_on_signals() -> Iterator[None]:
    """Raise ``Stopped`` in this process on SIGINT or SIGTERM, within the block."""
    previous = {number: signal.signal(number, _stop) for number in SIGNALS}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def as_worker() -> None:
    """For a worker process: ignore SIGINT, die on SIGTERM."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
