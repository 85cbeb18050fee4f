"""Where the project's commands may write: one rule for every entry point.

- A folder a command writes into is checked where it really is: not inside
  the committed record or the code (ground.paths.protected_problem).
- A study file names its page by a plain name (``page_problem``), never a
  path; it writes docs/<page>.md, docs/<page>/ and docs/figures/<page>/ only.
- A page in docs/ belongs to one study: a study file in studies/ owns its page
  and the readings its page tabulates; a study file of one's own may make a
  new page only where no committed page has that name (``page_owner``).

ground.checks.OutFolder and require_out_folder apply the first rule to every
``--out``; runner applies the others.
"""

from __future__ import annotations

import re
import subprocess
from collections.abc import Mapping
from pathlib import Path

from ground.errors import InputError
from ground.paths import DOCS, ROOT

# A page's name: one plain word, which stays a file name in docs/ whatever
# joins it (no separator, no '..', nothing LAMMPS reads). The tables of a
# reading (docs/<reading>/, a study's --name) may have dots between words
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


def page_owner(page: str, pages: Mapping[str, str], readings: Mapping[str, tuple]) -> str | None:
    """The study in studies/ whose page (or one of whose readings) is ``page``, or None.

    Parameters
    ----------
    page : str
        A page's name (docs/<page>.md, docs/<page>/).
    pages : mapping of str to str
        Each study file's page by study (runner.study.DOC_PAGES).
    readings : mapping of str to tuple of str
        The readings each study's page tabulates (runner.study.READINGS).
    """
    for study, own in pages.items():
        if page == own:
            return study
    for study, names in readings.items():
        if page in names:
            return study
    return None


def require_new_page(
    where: str, study: str, page: str, pages: Mapping[str, str], readings: Mapping[str, tuple]
) -> None:
    """Refuse a page for a study file of one's own where another study has it.

    A study file outside studies/ may make a new page only: not one that a
    study of studies/ owns, nor one committed in docs/ (a page, its tables or
    its figures). Its own page, made by an earlier run and not committed, it
    may make again.

    Raises
    ------
    ground.errors.InputError
        One line naming the file, the page and whose it is.
    """
    if problem := page_problem(page, tables=True):
        raise InputError(f"{where}: page {problem}, got {page!r}")
    owner = page_owner(page, pages, readings)
    if owner is not None and owner != study:
        raise InputError(
            f"{where}: page {page!r} is the {owner} study's (studies/{owner}.toml); "
            "give the file a page of its own"
        )
    if owner is None and committed(DOCS / f"{page}.md", DOCS / page, DOCS / "figures" / page):
        raise InputError(
            f"{where}: page {page!r} is committed in docs/ and not this study's; "
            "give the file a page of its own"
        )
