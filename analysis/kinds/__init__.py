"""The kinds of study a study file may ask for (its ``kind``), and the module
of analysis/ that measures each readings kind.

``results`` (the default) is one grid's impacts, whose page is chosen by its
tables (pages.kinds.TABLE_KINDS). The others are the readings studies, each
a module of analysis with:

- ``COLUMNS``: its table's columns (one row per impact);
- ``label(choice)``: the reading a combination of the study's axes is;
- optionally ``rank(rows, setup)``: the readings best first, which the
  study's ``[rerun]`` follows, ``row_fields(choice, setup)``: what every
  row of a combination records besides its impact's columns, and
  ``plan(choice, study)``: the combination's study as run.

Each has its page in pages/ under the same name (pages.kinds.readings_page).
"""

from __future__ import annotations

import importlib
from types import ModuleType

from builder.study_names import KINDS, READINGS_KINDS  # noqa: F401 (plain data there)


def kind_module(kind: str) -> ModuleType:
    """The module of a readings kind (imported when asked: they need scipy)."""
    if kind not in READINGS_KINDS:
        raise ValueError(f"not a readings kind: {kind!r}")
    return importlib.import_module(f"analysis.kinds.{kind}")
