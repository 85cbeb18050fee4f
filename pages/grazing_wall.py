"""The grazing wall page (analysis.kinds.grazing_wall's numbers): per angle
and wall, e and beta with their standard errors, failures, contact, sides
and cost; the paired steps between widths and each holding's verdict. The
prose: pages/templates/grazing_wall.md.j2."""

from __future__ import annotations

from pathlib import Path

from analysis.kinds.grazing_wall import (
    CONTINUUM,
    SAME_WITHIN,
    WALL_POINTS_PER_R,
    summary,
)
from analysis.kinds.readings import Setup
from builder.scene import SCENE

from .render import render

TITLE = "The wall at grazing angles: its width and how it is held"


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body (no figure)."""
    height = SCENE["wall_height"].default  # not an option of a study: every wall's
    return render(
        "grazing_wall.md.j2",
        study=setup.study,
        s=summary(rows, setup.choices),
        height=height,
        continuum={fixed: words.format(height=height) for fixed, words in CONTINUUM.items()},
        within=SAME_WITHIN,
        per_r=WALL_POINTS_PER_R,
    )
