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

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
# Each study's generated record: its page, tables, figures and run.json in
# docs/studies/<page>/ (the page docs/studies/<page>/<page>.md); the top of
# docs/ holds only hand-written pages.
STUDY_DOCS = DOCS / "studies"
DECKS = ROOT / "decks"
STUDIES = ROOT / "studies"
# What make setup builds: the styles' libraries, LAMMPS's headers, the
# contact's tables, the sampler's cache.
BUILD = ROOT / "build"


def study_docs(page: str) -> Path:
    """A study's folder in docs/: its page, tables, figures and run.json."""
    return STUDY_DOCS / page


def study_page(page: str) -> Path:
    """A study's generated page, docs/studies/<page>/<page>.md."""
    return study_docs(page) / f"{page}.md"


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
