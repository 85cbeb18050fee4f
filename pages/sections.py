"""The sections a results page may have (SECTIONS, which a study file's
``sections`` picks from), and those every study's page has alike: its
failures, its inaccurate impacts, the wall's ends (macros of
pages/templates/sections.md.j2, given analysis.failures' numbers)."""

from __future__ import annotations

from analysis.failures import outcome

from .render import macro

# The sections a results page may have, in the order it has them
# (pages.results.results_page; a study file's `sections` picks some).
SECTIONS = (
    "findings",  # a binary study's (pages.binary_findings)
    "earlier_runs",
    "statistics",
    "claims",
    "fits",
    "measures",
    "nu",
    "wall_ends",
    "grazing",
    "readings",
    "wall_comparison",  # a binary study's (pages.binary)
    "normals",  # a binary study's: e and beta at every normal (pages.normals)
)


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
