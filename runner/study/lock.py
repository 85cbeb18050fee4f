"""One run per study folder: a lock held for the whole run.

Two processes sharing a study's folder would build, run and set aside each
other's impacts (issue 44: seven wrong results kept as done). A run holds an
exclusive ``fcntl.flock`` on runs/<study>/.lock from before it prepares the
folder until its page is written; a second run of the same folder is refused
in one line naming the first's process, or waits for it (``--wait``).

fcntl (the standard library) rather than the filelock package: no new
dependency, and filelock takes the same flock on Linux. The kernel releases
the lock when its process ends however it ends (SIGKILL too), so a killed
run leaves no stale lock; the file, with the last holder's pid, stays.
"""

from __future__ import annotations

import fcntl
import os
import socket
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ground.errors import InputError
from ground.gate import make_folder, real

LOCK = ".lock"
# folders this process holds (reentrant: the study command and its driver
# both take it), and those it made by taking the lock
_held: dict[Path, int] = {}
_made: set[Path] = set()


def holder(folder: Path) -> str:
    """Who holds (or last held) the folder's lock: 'pid N on HOST'."""
    try:
        pid, host = (folder / LOCK).read_text().split()[:2]
        return f"pid {pid} on {host}"
    except (OSError, ValueError):
        return "another process"


def made_by_lock(folder: Path) -> bool:
    """Whether taking the lock made ``folder`` (nothing else is in it yet)."""
    return real(folder) in _made


@contextmanager
def study_lock(folder: Path, wait: bool = False) -> Iterator[None]:
    """Hold the study folder's lock for the block.

    Raises
    ------
    ground.errors.InputError
        If another process holds it and ``wait`` is not set: one line naming
        that process and what to do.
    """
    key = real(folder)
    if key in _held:
        _held[key] += 1
        try:
            yield
        finally:
            _held[key] -= 1
        return
    existed = folder.exists()
    make_folder(folder, "--name")
    if not existed:
        _made.add(key)
    fd = os.open(folder / LOCK, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            if not wait:
                raise InputError(
                    f"{folder}: another run of this study is under way ({holder(folder)}); "
                    "let it end, or give --wait to start when it has"
                ) from None
            print(f"waiting for {holder(folder)}, which runs {folder}", file=sys.stderr, flush=True)
            fcntl.flock(fd, fcntl.LOCK_EX)
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()} {socket.gethostname()}\n".encode())
        _held[key] = 1
        try:
            yield
        finally:
            del _held[key]
    finally:
        # a run refused before any work leaves no folder: the study's name stays free
        # (the driver may have removed it already, for the same reason)
        if key in _made and folder.is_dir() and [p.name for p in folder.iterdir()] == [LOCK]:
            (folder / LOCK).unlink()
            folder.rmdir()
        _made.discard(key)
        os.close(fd)  # releases the lock
