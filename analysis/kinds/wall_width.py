"""Does the wall's width change grazing impacts? (studies/wall_width.toml,
docs/studies/wall_width/wall_width.md)

At grazing angles the disk slides several R during contact, and on docs/model.md's
8 R wall its centre can pass an end of the wall, where the wall is held,
before the contact is over. The study runs each seed and angle on every
width; the page gives, per angle and width, the mean and standard error of e
and beta over the seeds, the median contact time, and how many impacts had
the disk's centre within 1 R of a held side during contact (side_clearance
< 1, the disk's radius), or past it (< 0).
"""

from __future__ import annotations

import numpy as np

from .readings import Setup

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


def mean_se(values: list[float]) -> tuple[float, float] | None:
    """The mean and its standard error over the seeds (None for fewer than two)."""
    a = np.asarray(values, float)
    return (float(a.mean()), float(a.std(ddof=1) / np.sqrt(len(a)))) if len(a) > 1 else None


def summary(rows: list[dict], widths: list[float]) -> dict:
    """Per angle and width (``table``): the impacts, the failed ones, e and
    beta (mean, standard error), the median contact time, and how many
    contacts came within 1 R of a held side (``near``) or past it
    (``past``); the median number of wall points per width (``points``);
    the failures' messages (``errors``)."""
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
            contact = [float(r["contact_time"]) for r in good]
            table.append(
                {
                    "gamma": gamma,
                    "width": width,
                    "impacts": len(good),
                    "failed": len(runs) - len(good),
                    "e": mean_se([float(r["e"]) for r in good]),
                    "beta": mean_se([float(r["beta"]) for r in good]),
                    "contact_time": float(np.median(contact)) if good else None,
                    "near": int((clearance < 1.0).sum()),
                    "past": int((clearance < 0.0).sum()),
                }
            )
    points: dict[str, list[int]] = {}
    for r in rows:
        if not r.get("error"):
            points.setdefault(r["reading"], []).append(int(float(r["n_wall_points"])))
    return {
        "table": table,
        "points": [
            (float(np.median(points[label({"wall_width": w})])), w)
            for w in widths
            if label({"wall_width": w}) in points
        ],
        "errors": sorted({r["error"][:100] for r in rows if r.get("error")}),
    }
