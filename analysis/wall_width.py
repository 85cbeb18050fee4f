"""Does the wall's width change grazing impacts? (studies/wall_width.toml,
docs/wall_width.md)

At grazing angles the disk slides several R during contact, and on MODEL.md's
8 R wall its centre can pass an end of the wall, where the wall is held,
before the contact is over. The study runs each seed and angle on every
width; the page gives, per angle and width, the mean and standard error of e
and beta over the seeds, the median contact time, and how many impacts had
the disk's centre within 1 R of a held side during contact (side_clearance
< 1, the disk's radius), or past it (< 0).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .readings import Setup, markdown_table

TITLE = "Wall width at grazing angles"
COLUMNS = (
    "reading",
    "study_lattice",
    "seed",
    "gamma_deg",
    "wall_width",
    "n_wall_points",
    "e",
    "beta",
    "contact_time",
    "side_clearance",
    "error",
)


def label(choice: dict) -> str:
    """A width's reading: ``width16``."""
    return f"width{choice['wall_width']:g}"


def row_fields(choice: dict, setup: Setup) -> dict:
    return {"wall_width": choice["wall_width"]}


def mean_se(values: list[float]) -> str:
    a = np.asarray(values, float)
    return f"{a.mean():.3f} +- {a.std(ddof=1) / np.sqrt(len(a)):.3f}" if len(a) > 1 else "-"


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body (no figure)."""
    study = setup.study
    widths = [c["wall_width"] for c in setup.choices]
    table = []
    for gamma in sorted({float(r["gamma_deg"]) for r in rows}):
        for width in widths:
            runs = [
                r
                for r in rows
                if float(r["gamma_deg"]) == gamma and r["reading"] == label({"wall_width": width})
            ]
            good = [r for r in runs if not r.get("error")]
            clearance = np.array([float(r["side_clearance"]) for r in good])
            table.append(
                [
                    f"{gamma:g}",
                    f"{width:g}",
                    str(len(good)),
                    str(len(runs) - len(good)),
                    mean_se([float(r["e"]) for r in good]),
                    mean_se([float(r["beta"]) for r in good]),
                    f"{np.median([float(r['contact_time']) for r in good]):.1f}" if good else "-",
                    str(int((clearance < 1.0).sum())),
                    str(int((clearance < 0.0).sum())),
                ]
            )
    errors = sorted({r["error"][:100] for r in rows if r.get("error")})
    points: dict[str, list[int]] = {}
    for r in rows:
        if not r.get("error"):
            points.setdefault(r["reading"], []).append(int(float(r["n_wall_points"])))
    wall_points = ", ".join(
        f"{np.median(points[label({'wall_width': w})]):.0f} at {w:g} R"
        for w in widths
        if label({"wall_width": w}) in points
    )
    ka = study["wall_ka"]
    ka = f"springs {ka}" if isinstance(ka, str) else f"springs {ka:g} times the disk's ka"
    return (
        f"Random lattice, seeds {study['first_seed']} to "
        f"{study['first_seed'] + study['samples'] - 1}, v_n = {study['vn']:g} c, dt = "
        f"{study['options']['dt']:g} R/c; the wall's points `{study['n_wall']}` (median "
        f"{wall_points}), {ka}, its {study['wall_fixed']} held. A wall at the disk's number "
        "density (`density`) keeps its material as it widens; today's default, 1,600 points, "
        "would spread thinner.\n\n"
        + markdown_table(
            [
                "gamma",
                "wall width, R",
                "impacts",
                "failed",
                "e",
                "beta",
                "median contact time, R/c",
                "centre within 1 R of a side",
                "centre past a side",
            ],
            table,
        )
        + ("\n\nFailures: " + "; ".join(errors) if errors else "")
        + f"\n\nOne row per impact: `{study['name']}/rows.csv` (`python -m runner page "
        f"{study['name']}` rebuilds this page from it).\n"
    )
