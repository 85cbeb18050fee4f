"""What a finished study gives: its tables, then the page its kind makes
(pages.kinds), from its runs' folders (``report``) or from its tables alone
(``report_from_tables``)."""

from __future__ import annotations

from pathlib import Path

from analysis.impact.failures import failure_causes, genuine
from analysis.study_tables import (
    RUN_RECORD,
    read_failure,
    read_tables,
    record_timings,
    run_record,
    write_records,
    write_study_tables,
)
from analysis.table import collect
from ground.gate import copy_file, gate, make_folder, write_text
from ground.paths import ROOT

from .kinds import StudyTables, table_kind


def report(
    study,
    resamples: int = 200,
    page: Path | None = None,
    preset: str = "paper",
    tables: Path | None = None,
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
) -> dict:
    """Write impacts.csv, means.csv, fits.json, failed.csv, figures/ and results.md for a study.

    Parameters
    ----------
    study : runner.study.Study
        The study, with its folder under runs/.
    resamples : int
        Bootstrap resamples of the fits.
    page : pathlib.Path, optional
        Where results.md goes (default: the study's folder); the figures go
        into ``figures/`` beside it.
    preset : str
        The preset the study was run from, for the command on the page.
    tables : pathlib.Path, optional
        A folder that gets a copy of the tables, study.json and run.json, from which
        ``report_from_tables`` remakes the page (docs/studies/results/ for the paper).
    readings : dict of str to pathlib.Path, optional
        Table folders of the same study under other options, by name, which a
        grazing page tabulates (``grazing.readings_section``).
    sections : tuple of str, optional
        Which of ``SECTIONS`` the results page has, in order (default: all).

    Returns
    -------
    dict
        ``rows`` (finished impacts), ``failed`` (failed impacts), ``fits``
        (``fit_all``, as written to fits.json) and ``page`` (results.md's path).
    """
    jobs = study.jobs()
    rows = collect([(j["lattice"], Path(j["folder"])) for j in jobs])
    failed = [read_failure(j) for j in jobs if (Path(j["folder"]) / "failed.json").exists()]
    for place in (tables, page):  # the one gate of every write (ground.gate)
        if place is not None:
            gate(place)
    info = record_timings(study, rows)
    summary = render(
        info,
        rows,
        failed,
        study.folder,
        page or study.folder / "results.md",
        resamples,
        preset,
        shown_path(tables) if tables is not None else "",
        readings,
        sections,
    )
    write_text(study.folder / RUN_RECORD, run_record(info, rows))
    if tables is not None:
        make_folder(tables)
        # every impact as the committed tables have it: the run's provenance stays theirs
        before = tables / "impacts.csv"
        reproduced = (
            before.is_file() and before.read_bytes() == (study.folder / "impacts.csv").read_bytes()
        )
        for name in ("impacts.csv", "means.csv", "fits.json", "speed.json", "failed.csv"):
            if (study.folder / name).exists():  # a speed study has speed.json instead of fits
                copy_file(study.folder / name, tables / name)
        write_records(info, rows, tables, keep_run=reproduced)
    return summary


def report_from_tables(
    tables: Path,
    page: Path,
    resamples: int = 200,
    preset: str = "paper",
    out: Path | None = None,
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
) -> dict:
    """The page and figures of a study from its tables alone (docs/studies/results/).

    Parameters
    ----------
    tables : pathlib.Path
        A folder with impacts.csv, failed.csv and study.json (``report``'s
        ``tables``); read only, unless it is ``out``.
    page : pathlib.Path
        Where the page goes; the figures go into ``figures/`` beside it.
    resamples, preset, readings, sections
        As for ``report``.
    out : pathlib.Path, optional
        Where the tables (with means.csv and fits.json made again) and
        study.json go; default ``tables`` itself.

    Returns
    -------
    dict
        As ``report``.
    """

    info, rows, failed = read_tables(tables)
    out = Path(out) if out is not None else Path(tables)
    gate(page)
    make_folder(out)
    write_records(info, rows, out)
    return render(
        info,
        rows,
        failed,
        out,
        page,
        resamples,
        preset,
        shown_path(tables),
        readings,
        sections,
    )


def shown_path(path: Path) -> str:
    """A folder as the page names it: from the project's root where it is inside."""
    path = Path(path).resolve()
    return path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else str(path)


def render(
    info: dict,
    rows: list[dict],
    failed: list[dict],
    out: Path,
    page: Path,
    resamples: int,
    preset: str,
    tables: str = "",
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
) -> dict:
    """Tables into ``out``, the figures and the page (see ``report``)."""
    rows = write_study_tables(rows, failed, out)
    study = StudyTables(
        info, rows, failed, out, page, resamples, preset, tables, readings or {}, sections
    )
    numbers = table_kind(study).write(study)
    return summary(rows, failed, numbers, page)


def summary(rows: list[dict], failed: list[dict], numbers: dict, page: Path) -> dict:
    """What ``report`` returns: counts, failure causes, the page's numbers."""
    return {
        "rows": len(rows),
        "failed": len(genuine(failed)),
        "stuck": len(failed) - len(genuine(failed)),
        "causes": failure_causes(failed),
        "drift_exceeded": sum(str(r["drift_exceeded"]) == "True" for r in rows),
        "fits": numbers,
        "page": str(page),
    }
