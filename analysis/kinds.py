"""The kinds of page a study file may ask for (its ``kind``), and the page of
a readings study made from its table.

``results`` (the default) is analysis.report's page of one study's tables
(a speed study's is analysis.speed_page's). The others are the readings
studies' pages, each a module of analysis with:

- ``TITLE``, and ``COLUMNS``: its table's columns (one row per impact);
- ``label(choice)``: the reading a combination of the study's axes is;
- ``page(rows, setup, figures)``: the page's body, its figures into ``figures``;
- optionally ``rank(rows, setup)``: the readings best first, which the
  study's ``[rerun]`` follows, and ``row_fields(choice, setup)``: what every
  row of a combination records besides its impact's columns.
"""

from __future__ import annotations

import importlib
from dataclasses import replace
from pathlib import Path
from types import ModuleType

from .readings import Setup, page_text, read_record, read_rows

READINGS_KINDS = (
    "scene_readings",
    "model_readings",
    "fact_sensitivity",
    "wall_width",
    "resolution",
    "references",
)
KINDS = ("results", *READINGS_KINDS)


def kind_module(kind: str) -> ModuleType:
    """The module of a readings kind (imported when asked: they need scipy)."""
    if kind not in READINGS_KINDS:
        raise ValueError(f"not a readings kind: {kind!r}")
    return importlib.import_module(f"analysis.{kind}")


def figure_link(page: Path, figures: Path) -> str:
    return figures.relative_to(page.parent).as_posix()


def readings_page(kind: str, tables: Path, page: Path, setup: Setup) -> Path:
    """The page of a readings study from its table and record in ``tables``
    (rows.csv, run.json); its figures go into figures/<page's name>/ beside it."""
    module = kind_module(kind)
    figures = page.parent / "figures" / page.stem
    if hasattr(module, "FIGURE"):
        figures.mkdir(parents=True, exist_ok=True)
    record = read_record(tables)
    setup = replace(setup, record=record, figures=figure_link(page, figures))
    body = module.page(read_rows(tables), setup, figures)
    page.write_text(page_text(module.TITLE, record, body))
    return page
