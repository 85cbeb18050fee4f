"""Errors for bad input, worded for the person who typed it."""

from __future__ import annotations

import errno
import re
from collections.abc import Iterable

# An error line quotes at most QUOTE characters of any one value it echoes
# and is at most LINE long: a 10-million-item list stays one readable line.
QUOTE = 200
LINE = 600


def clipped(message: str) -> str:
    """``message`` with every run of more than QUOTE non-blank characters cut
    to QUOTE, and the whole cut to LINE, each cut saying how long it was."""

    def cut(match: re.Match) -> str:
        return f"{match.group()[:QUOTE]}... ({len(match.group())} characters)"

    short = re.sub(rf"\S{{{QUOTE + 1},}}", cut, message)
    if len(short) > LINE:
        short = f"{short[:LINE]}... ({len(message)} characters in all)"
    return short


class InputError(ValueError):
    """A parameter outside its allowed values; the message names both."""


class BuildError(RuntimeError):
    """A lattice that cannot be built as asked (a geometric failure)."""


def require_choice(name: str, value: str, choices: Iterable[str]) -> None:
    choices = list(choices)
    if value not in choices:
        raise InputError(f"{name} must be one of {', '.join(choices)}; got {value!r}")


# What to do about an operating system's error, by its errno.
_REMEDIES = {
    errno.ENOSPC: "the disk is full: free space or give another folder",
    errno.EDQUOT: "the disk quota is reached: free space or give another folder",
    errno.EFBIG: "the file size limit is reached (ulimit -f): raise it",
    errno.EACCES: "it is not writable: make it writable or give another folder",
    errno.EPERM: "it is not writable: make it writable or give another folder",
    errno.EROFS: "its file system is read-only: give another folder",
    errno.ENOENT: "it does not exist (a dangling link?): remove it or give another path",
    errno.ELOOP: "it is a loop of links: remove them",
    errno.ENOTDIR: "a part of its path is a file, not a folder",
    errno.EISDIR: "it is a folder, not a file",
}


def os_error_line(error: OSError) -> str:
    """An operating system's error as one line: the file, what went wrong,
    what to do."""
    where = error.filename or "a file"
    if error.filename2:
        where = f"{where} -> {error.filename2}"
    remedy = _REMEDIES.get(error.errno, "")
    told = error.strerror or str(error)
    return f"{where}: {told}{'; ' + remedy if remedy else ''}"
