"""The kinds of page, by name: one class each, which takes a study's tables,
has analysis/ compute their numbers, draws the figures and writes the page.

A study of one grid's impacts (impacts.csv, failed.csv, study.json) gets the
first of ``TABLE_KINDS`` whose ``matches`` holds: a speed axis makes a speed
page, two disks a binary page, angles past the paper's last a grazing page,
anything else a results page. A readings study (its study file's ``kind``)
gets the page of that kind (``READINGS_PAGES``: a module of pages/ with
``TITLE`` and ``page(rows, setup, figures)``; its numbers: the module of
analysis/ of the same name, analysis.kinds).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import ModuleType

from analysis import speed, study_numbers
from analysis.grazing import has_grazing_angles, readings_numbers
from analysis.kinds import READINGS_KINDS
from analysis.kinds.readings import Setup, read_record, read_rows
from analysis.study_tables import read_tables
from analysis.table import MEAN_COLUMNS, rounded, write_csv
from ground.gate import gate, make_folder, write_json, write_text

from . import binary, binary_findings, figures, grazing, normals
from . import speed as speed_page
from .render import render
from .results import results_page


@dataclass(frozen=True)
class StudyTables:
    """What a page of one study is made from: its record (study.json), its
    finished and failed impacts, where its tables and page go, and how the
    page names them."""

    info: dict
    rows: list[dict]
    failed: list[dict]
    out: Path  # the tables' folder (means.csv, fits.json, speed.json go here)
    page: Path
    resamples: int = 200
    preset: str = "paper"
    tables: str = ""  # the tables' folder as the page names it ("" for none)
    readings: dict[str, Path] = field(default_factory=dict)  # tables of other readings
    sections: tuple[str, ...] | None = None  # which of pages.sections.SECTIONS

    @property
    def figure_dir(self) -> Path:
        """Where the figures go: figures/ beside the page (in docs/, the
        study's folder docs/studies/<page>/, which holds its tables too)."""
        return self.page.parent / "figures"

    @property
    def shown_figures(self) -> str:
        """The figures' folder as the page links it."""
        return self.figure_dir.relative_to(self.page.parent).as_posix()

    def read_readings(self) -> dict[str, tuple[dict, list[dict], list[dict]]]:
        return {name: read_tables(folder) for name, folder in self.readings.items()}


class ResultsPage:
    """One study's fits, measures and claims (fits.json, means.csv), its
    figures and its results page."""

    name = "results"

    @staticmethod
    def matches(study: StudyTables) -> bool:
        return True

    def sections(self, study: StudyTables, fits: dict) -> dict[str, list[str]]:
        """The sections only this kind has, by name (pages.sections.SECTIONS);
        their numbers go into ``fits``."""
        return {}

    def write(self, study: StudyTables) -> dict:
        """The tables, figures and page; returns fits.json's numbers."""
        gate(study.page)  # the one gate of every write (ground.gate)
        gate(study.figure_dir)
        fits, means = study_numbers.results_numbers(study.rows, study.resamples)
        extra = self.sections(study, fits)
        write_csv(means, study.out / "means.csv", MEAN_COLUMNS)
        write_json(study.out / "fits.json", fits)
        figures.draw(means, fits, study.figure_dir)
        done = study_numbers.samples_done(study.info, study.rows, study.failed)
        write_text(
            study.page,
            results_page(
                study.info,
                study.rows,
                means,
                fits,
                study.shown_figures,
                study.failed,
                study.info["lammps_seconds"],
                done,
                study.preset,
                study.tables,
                extra,
                study.sections,
            ),
        )
        return fits


class GrazingPage(ResultsPage):
    """A results page with e at grazing incidence (angles past the paper's
    80.5 degrees) and the same study under other readings."""

    name = "grazing"

    @staticmethod
    def matches(study: StudyTables) -> bool:
        return has_grazing_angles(study.rows)

    def sections(self, study: StudyTables, fits: dict) -> dict[str, list[str]]:
        fits["grazing"] = study_numbers.grazing_numbers(study.rows, study.resamples)
        grazing.draw(fits["grazing"], study.figure_dir)
        others = readings_numbers(study.read_readings(), study.resamples)
        return {
            "grazing": grazing.grazing_section(fits["grazing"], study.shown_figures),
            "readings": grazing.readings_section(study.info, others),
        }


class BinaryPage(GrazingPage):
    """Two disks colliding (target disk), beside the same disks on the wall
    studies its readings name; with grazing angles, a grazing page's
    sections too."""

    name = "binary"

    @staticmethod
    def matches(study: StudyTables) -> bool:
        return study.info.get("target") == "disk"

    def sections(self, study: StudyTables, fits: dict) -> dict[str, list[str]]:
        extra = super().sections(study, fits) if GrazingPage.matches(study) else {}
        fits.update(
            study_numbers.binary_numbers(study.rows, study.read_readings(), study.resamples)
        )
        for name, numbers in fits["wall_comparison"].items():
            binary.draw(numbers, study.figure_dir, name)
        extra["wall_comparison"] = binary.section(
            fits["wall_comparison"], study.shown_figures, fits["normals"], study.page.parent
        )
        extra["normals"] = normals.section(fits["normals"], study.page.parent)
        extra["findings"] = binary_findings.findings_section(fits, study.info)
        return extra


class SpeedPage:
    """A study with a speed axis: speed.json, its figures and its page."""

    name = "speed"

    @staticmethod
    def matches(study: StudyTables) -> bool:
        return bool(study.info.get("speeds"))

    def write(self, study: StudyTables) -> dict:
        numbers = rounded(speed.estimates(study.rows, study.resamples))
        speed.write_json(numbers, study.out / "speed.json")
        speed_page.draw(numbers, study.figure_dir)
        write_text(study.page, speed_page.text(study, numbers))
        return numbers


# The first that matches a study's tables makes its page.
TABLE_KINDS = (SpeedPage, BinaryPage, GrazingPage, ResultsPage)


def table_kind(study: StudyTables):
    """The page kind of one study's tables."""
    return next(kind for kind in TABLE_KINDS if kind.matches(study))()


# The readings kinds' pages (analysis.kinds.READINGS_KINDS), by kind.
READINGS_PAGES = {kind: f"pages.{kind}" for kind in READINGS_KINDS}


def readings_module(kind: str) -> ModuleType:
    """The page module of a readings kind (imported when asked: matplotlib)."""
    if kind not in READINGS_PAGES:
        raise ValueError(f"not a readings kind: {kind!r}")
    return importlib.import_module(READINGS_PAGES[kind])


def readings_page(kind: str, tables: Path, page: Path, setup: Setup) -> Path:
    """The page of a readings study from its table and record in ``tables``
    (rows.csv, run.json); its figures go into figures/ beside it."""
    module = readings_module(kind)
    figure_dir = page.parent / "figures"
    gate(page)  # the one gate of every write (ground.gate)
    if hasattr(module, "FIGURE"):
        make_folder(figure_dir)
    record = read_record(tables)
    setup = replace(setup, record=record, figures=figure_dir.relative_to(page.parent).as_posix())
    body = module.page(read_rows(tables), setup, figure_dir)
    # the title, the command and machine that made the rows (for rows made
    # before the study file, the commit of the command and the command that
    # runs the same studies since), the body
    write_text(page, render("readings_page.md.j2", title=module.TITLE, record=record, body=body))
    return page
