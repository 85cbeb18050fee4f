"""The binary page's section on the normal: each angle's e and beta at every
normal a target has, withheld where the normals disagree
(analysis.normal_check's numbers; the prose: pages/templates/normals.md.j2)."""

from __future__ import annotations

from analysis.normal_check import NAMES

from .render import macro


def section(checks: dict[str, dict | None]) -> str:
    """The page's section (Markdown): per target and lattice, each angle at each normal."""
    checks = {k: v for k, v in checks.items() if v}
    return macro("normals.md.j2", "normals", checks, NAMES)
