"""Where the project's files are, and where its commands may write runs.

The project runs from its clone (an editable install, pyproject.toml): the
code finds decks/, potentials/, build/, docs/ and studies/ beside itself.
One definition of the root here, for every package.

A folder a command writes into (``--out``, a study's ``--name`` under the
runs' folder, ``$IMPACT_RUNS``) is checked where it really is, with every
symbolic link resolved: it must not be inside the committed record (docs/,
studies/) or the code, which only ``--docs`` and the project's own make
targets write (``protected_problem``).
"""

from __future__ import annotations

import os
from pathlib import Path

from .errors import InputError

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
DECKS = ROOT / "decks"
STUDIES = ROOT / "studies"
# What make setup builds: the styles' libraries, LAMMPS's headers, the
# contact's tables, the sampler's cache.
BUILD = ROOT / "build"
# The project's folders that no --out, --name or $IMPACT_RUNS may point into:
# the committed record, the code, and what make setup builds.
PROTECTED = (
    "docs",
    "studies",
    "ground",
    "builder",
    "analysis",
    "runner",
    "reference",
    "calibration",
    "bench",
    "decks",
    "potentials",
    "notebooks",
    "tests",
    "build",
    ".git",
    ".venv",
    ".venv-pypi",
)


def protected_problem(path: Path | str) -> str | None:
    """Why a command may not write into ``path``, or None.

    The path is resolved first (every symbolic link on it followed, also of
    the parts that do not exist yet), so that a link cannot lead a write
    into the project's record or code.
    """
    where = Path(path).expanduser().resolve()
    if where == ROOT:
        return "is the project's root; give a folder of its own (runs/<name>)"
    for name in PROTECTED:
        folder = (ROOT / name).resolve()
        if where == folder or where.is_relative_to(folder):
            shown = "" if where == Path(path).expanduser().absolute() else f" (it leads to {where})"
            what = "the committed record" if name in ("docs", "studies") else "the project's own"
            hint = "; only --docs writes docs/" if name == "docs" else ""
            return f"is inside {name}/, {what}{shown}{hint}"
    return None


def runs_folder() -> Path:
    """Where studies and runs go: runs/ in the clone, or $IMPACT_RUNS (a
    cluster's scratch space; the tests' temporary folder).

    Raises
    ------
    ground.errors.InputError
        If $IMPACT_RUNS points into the project's record or code.
    """
    folder = Path(os.environ.get("IMPACT_RUNS") or ROOT / "runs")
    if problem := protected_problem(folder):
        raise InputError(f"IMPACT_RUNS: {folder} {problem}")
    return folder
