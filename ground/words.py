"""Whether a name or path can pass through LAMMPS and the file system: one
word (LAMMPS splits its commands at whitespace) of plain portable characters.

Nothing here imports another module of the project."""

from __future__ import annotations

import re

# LAMMPS splits a command at whitespace, takes "#" for a comment, "$" for a
# variable and quotes and "&" for its own syntax: a path with any of them
# cannot be passed to it as one word.
LAMMPS_UNSAFE = frozenset("#$&'\"`")


def word_problem(path: str) -> str | None:
    """Why LAMMPS cannot take ``path`` as one word, or None."""
    if any(c.isspace() for c in path):
        return "must not contain whitespace (LAMMPS splits its commands at it)"
    if bad := sorted(set(path) & LAMMPS_UNSAFE):
        return f"must not contain {' '.join(bad)} (LAMMPS's own syntax)"
    return None


# What a name or path of runs may hold: LAMMPS (and other tools the runs
# meet) fail on others ("Cannot open restart file" for non-ASCII, * or %).
PORTABLE = re.compile(r"[A-Za-z0-9._+=,@:/~-]*")


def portable_problem(text: str) -> str | None:
    """Why ``text`` (a study's name, a file's stem, a runs' folder) is not
    plain portable characters, or None."""
    if PORTABLE.fullmatch(text):
        return None
    bad = "".join(sorted({c for c in text if not PORTABLE.fullmatch(c)}))
    return (
        f"must be plain portable characters (letters, digits and . _ - + = , @), not {bad!r}: "
        "LAMMPS cannot open such files"
    )
