"""The wall width page (analysis.kinds.wall_width's numbers): per angle and width,
e and beta with their standard errors, the contact time, the sides. The
prose: pages/templates/wall_width.md.j2."""

from __future__ import annotations

from pathlib import Path

from analysis.kinds.readings import Setup
from analysis.kinds.wall_width import summary

from .render import render

TITLE = "Wall width at grazing angles"


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body (no figure)."""
    widths = [c["wall_width"] for c in setup.choices]
    return render("wall_width.md.j2", study=setup.study, s=summary(rows, widths))
