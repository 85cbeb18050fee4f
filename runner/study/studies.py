"""The study files of studies/, read when asked: no registry is filled at
import, and nothing here changes what a file says.

    load_study("paper")        # the Study of studies/paper.toml
    study_file("my.toml")      # what a file says (runner.study.file.StudyFile)
    all_studies()              # every file of studies/, by name
"""

from __future__ import annotations

import json
from pathlib import Path

from builder.outputs import committed, require_own_page
from ground.errors import InputError
from ground.gate import grant
from ground.paths import study_docs

from . import Study
from .file import STUDIES, StudyFile, read_study_file, study_path


def study_file(name_or_path: str | Path) -> StudyFile:
    """What studies/<name>.toml, or the file at a path, says.

    Raises
    ------
    ground.errors.InputError
        For no such file, a file that is not a study's, or a file of one's
        own whose name is that of a file of studies/ (its folders and page
        would be that study's).
    """
    path = study_path(str(name_or_path))
    own = STUDIES / f"{path.stem}.toml"
    if own.is_file() and path.resolve() != own.resolve():
        raise InputError(f"{path}: {own} has the name {path.stem!r} already; rename the file")
    return read_study_file(path)


def load_study(name: str) -> Study:
    """The study of studies/<name>.toml (or of a file at a path)."""
    return study_file(name).study


def study_names() -> list[str]:
    """The names of the study files of studies/, sorted."""
    return sorted(p.stem for p in STUDIES.glob("*.toml"))


def all_studies() -> dict[str, StudyFile]:
    """Every study file of studies/, by name, sorted."""
    return {name: read_study_file(STUDIES / f"{name}.toml") for name in study_names()}


def built_in_pages() -> tuple[dict[str, str], dict[str, tuple[str, ...]]]:
    """The pages in docs/ of the study files of studies/ (study -> page) and
    the readings those pages tabulate (study -> names), for the studies that
    have them."""
    files = all_studies()
    pages = {name: f.page for name, f in files.items() if f.page}
    readings = {name: f.readings for name, f in files.items() if f.readings}
    return pages, readings


def committed_studies() -> list[str]:
    """The names of the study files of studies/ that git tracks."""
    return sorted(Path(p).stem for p in committed(STUDIES) if p.endswith(".toml"))


def require_page(described: StudyFile, page: str, *also: str) -> list[str]:
    """Let ``described`` write docs/studies/<page>/ (its page, tables and
    figures; and the same of the pages ``also``, which its page
    tabulates) if the page is its own (builder.outputs.require_own_page), by
    opening the one gate of every write (ground.gate) to them. A page of
    ``also`` that is another committed study's own page (the paper's
    results, which the binary page tabulates) is read, never written: it is
    neither granted nor refused. Returns the pages granted.

    Raises
    ------
    ground.errors.InputError
        For a page that is another study's, committed and not the file's own,
        or named by two study files.
    """
    files = all_studies()
    tracked = set(committed_studies())
    name = described.study.name
    path = described.path
    own = STUDIES / f"{name}.toml"
    committed_file = path is not None and path.resolve() == own.resolve() and name in tracked
    granted_pages = []
    for each in (page, *also):
        # a page's owner is the file whose page it is; a reading's (tables a
        # page tabulates, with no page of their own) the file that names it
        owners = [n for n in sorted(tracked) if n in files and files[n].page == each]
        if each != page and owners and name not in owners:
            continue  # another study's own page: only read
        owners = owners or [n for n in sorted(tracked) if n in files and each in files[n].readings]
        naming = [
            n
            for n, f in files.items()
            if n not in tracked and n != name and each in (f.page, *f.readings)
        ]
        made_by = None
        record = study_docs(each) / "study.json"
        if record.is_file():
            try:
                made_by = json.loads(record.read_text(encoding="utf-8")).get("name")
            except (OSError, ValueError, AttributeError):
                made_by = None
        where = str(path) if path else name
        require_own_page(where, name, each, owners, naming, committed_file, made_by)
        grant(study_docs(each))
        granted_pages.append(each)
    return granted_pages
