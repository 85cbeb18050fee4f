"""The binary page's section on the normal: how many angles keep e and beta
at every normal a target has, and per angle, in normals.csv beside the
page, each normal's numbers (analysis.normal_check's; the prose:
pages/templates/normals.md.j2)."""

from __future__ import annotations

from pathlib import Path

from analysis.normal_check import NAMES
from analysis.table import rounded, write_csv

from .render import macro

TABLE = "normals.csv"
# normals.csv: a row per target, lattice and angle; each normal's numbers
# (blank where the target has no such normal), the headline's spread and
# whether e and beta are robust to the normal, and the friction's tilt.
COLUMNS = (
    "target",
    "lattice",
    "gamma_deg",
    "headline",
    *(f"{q}_{n}{s}" for n in NAMES for q in ("cot_gamma", "e", "beta") for s in ("", "_error")),
    "e_spread",
    "e_robust",
    "beta_spread",
    "beta_robust",
    "tilt_deg",
)


def rows(checks: dict[str, dict]) -> list[dict]:
    """normals.csv's rows: per target, lattice and angle."""
    out = []
    for target, check in checks.items():
        for lattice, entry in check["lattices"].items():
            for j, gamma in enumerate(entry["gamma_deg"]):
                row = {"target": target, "lattice": lattice, "gamma_deg": gamma}
                row["headline"] = check["normals"][0]
                for key in COLUMNS[4:]:
                    if key in entry:
                        row[key] = entry[key][j]
                out.append(rounded(row))
    return out


def section(checks: dict[str, dict | None], folder: Path) -> str:
    """The page's section (Markdown): per target and lattice, how many angles
    are robust to the normal; each angle at each normal into ``folder``'s
    normals.csv."""
    checks = {k: v for k, v in checks.items() if v}
    if checks:
        write_csv(rows(checks), Path(folder) / TABLE, COLUMNS)
    return macro("normals.md.j2", "normals", checks, NAMES, TABLE)
