"""Where the project's commands may write: one rule for every entry point.

- A folder a command writes into is checked where it really is: not inside
  the committed record or the code (ground.gate.protected_problem).
- A study file names its page by a plain name (``page_problem``), never a
  path; it writes docs/studies/<page>/ only (its page, tables and figures).
- A page in docs/ belongs to exactly one committed study file of studies/:
  it owns its page and the readings its page tabulates; any other study file
  (of one's own, or placed in studies/) may make a new page only where no
  committed page has that name (``require_own_page``).

ground.checks.OutFolder and require_out_folder apply the first rule to every
``--out``; runner applies the others.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from ground.errors import InputError
from ground.paths import DOCS, ROOT, study_docs

# A page's name: one plain word, which stays a file name in docs/ whatever
# joins it (no separator, no '..', nothing LAMMPS reads). The tables of a
# reading (docs/studies/<reading>/, a study's --name) may have dots between words
# (grazing_literal_v0.1), never two together or at an end.
PLAIN_NAME = re.compile(r"[A-Za-z0-9_-]+")
TABLE_NAME = re.compile(r"[A-Za-z0-9_-]+(\.[A-Za-z0-9_-]+)*")
# The longest file name Linux file systems take (NAME_MAX), in bytes.
NAME_MAX = 255


def page_problem(name: object, tables: bool = False) -> str | None:
    """Why ``name`` cannot be a page's name (``tables``: a reading's tables'
    folder in docs/), or None."""
    if tables and not (isinstance(name, str) and TABLE_NAME.fullmatch(name)):
        return "must be a plain name (letters, digits, _ and -, dots between them), not a path"
    if not tables and not (isinstance(name, str) and PLAIN_NAME.fullmatch(name)):
        return "must be a plain name (letters, digits, _ and -), not a path"
    if len(name.encode()) > NAME_MAX - len(".md"):
        return f"must be at most {NAME_MAX - len('.md')} characters"
    return None


def committed(*paths: Path) -> list[str]:
    """Those of ``paths`` (files or folders) that git tracks; where git cannot
    tell (no clone), those that exist."""
    try:
        listed = subprocess.run(
            ["git", "ls-files", "--", *map(str, paths)],
            cwd=ROOT,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        return [str(p.relative_to(ROOT)) for p in paths if p.exists()]
    return listed


def require_own_page(
    where: str,
    study: str,
    page: str,
    owners: list[str],
    naming: list[str],
    committed_file: bool,
    made_by: str | None = None,
) -> None:
    """Refuse a page in docs/ that is not the study's own.

    A page belongs to exactly one committed study file of studies/ (its page,
    or a reading its page tabulates). A committed file may write its own
    page; any other file (of one's own, or placed in studies/) only a new
    page: not one a committed file owns, nor one committed in docs/, nor one
    another study file names or another study's run made.

    Parameters
    ----------
    where, study, page : str
        The file (for the message), its study's name, and the page.
    owners : list of str
        The committed study files (by name) whose page or readings is ``page``.
    naming : list of str
        Every other study file of studies/ (committed or not) naming ``page``.
    committed_file : bool
        Whether the file is a committed file of studies/.
    made_by : str, optional
        The study whose tables docs/studies/<page>/ holds from an earlier run, if any.

    Raises
    ------
    ground.errors.InputError
        One line naming the file, the page and whose it is.
    """
    if problem := page_problem(page, tables=True):
        raise InputError(f"{where}: page {problem}, got {page!r}")
    if len(owners) > 1:
        raise InputError(
            f"{where}: page {page!r} is named by {len(owners)} study files "
            f"({', '.join(f'studies/{o}.toml' for o in owners)}); a page has one owner"
        )
    if committed_file and owners == [study]:
        return
    if owners:
        raise InputError(
            f"{where}: page {page!r} is the {owners[0]} study's (studies/{owners[0]}.toml); "
            "give the file a page of its own"
        )
    if naming:
        raise InputError(
            f"{where}: page {page!r} is named by studies/{naming[0]}.toml too; "
            "give the file a page of its own"
        )
    if committed(study_docs(page), DOCS / f"{page}.md", DOCS / page):
        raise InputError(
            f"{where}: page {page!r} is committed in docs/ and not this study's; "
            "give the file a page of its own"
        )
    if made_by is not None and made_by != study:
        raise InputError(
            f"{where}: page {page!r} was made by the {made_by} study "
            f"(docs/studies/{page}/study.json); give the file a page of its own"
        )
