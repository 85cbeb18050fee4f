"""The study files of studies/, read when asked: no registry is filled at
import, and nothing here changes what a file says.

    load_study("paper")        # the Study of studies/paper.toml
    study_file("my.toml")      # what a file says (runner.study_file.StudyFile)
    all_studies()              # every file of studies/, by name
"""

from __future__ import annotations

from pathlib import Path

from ground.errors import InputError

from .study import Study
from .study_file import STUDIES, StudyFile, read_study_file, study_path


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
