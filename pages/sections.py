"""The sections a results page may have (SECTIONS, which a study file's
``sections`` picks from), and those every study's page has alike: its
failures, its inaccurate impacts, the wall's ends (macros of
pages/templates/sections.md.j2, given analysis.impact.failures' numbers)."""

from __future__ import annotations

from analysis.impact.failures import outcome

# The sections a results page may have, in their order: plain data in
# builder.study_names, which a study file is checked against.
from builder.study_names import SECTIONS  # noqa: E402,F401

from .render import macro


def section_text(section: list[str] | str) -> str:
    """A section as the page's text: a list of lines (each section ending
    with an empty one) joined, or its text as it is."""
    if isinstance(section, str):
        return section
    return "\n".join(section) + "\n" if section else ""


def failure_section(failed: list[dict]) -> list[str]:
    """The failed impacts by cause (count, where, one message), then those
    that stayed on the wall, as lines (none if every impact has a result)."""
    return macro("sections.md.j2", "failures", outcome(failed)).splitlines()
