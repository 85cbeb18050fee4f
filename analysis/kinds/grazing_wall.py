"""Does the wall change grazing impacts with its width, and does holding its
bottom as well as its sides change that? (studies/grazing_wall.toml,
docs/studies/grazing_wall/grazing_wall.md)

Each seed and angle runs on every wall: held at its sides (the default, a
clamped beam of span W and thickness 2 R) or at its sides and bottom (an
elastic layer of thickness 2 R on a rigid base), W R wide, its points at the
default wall's spacing (``WALL_POINTS_PER_R`` per R of width: ``plan``).
The page gives, per angle and wall, e and beta (mean and standard error
over the seeds), the failures and their causes, the median contact time,
the impacts whose disk centre came within 1 R of a held side or past it,
LAMMPS seconds per impact; the paired-by-seed differences between
consecutive widths of one holding; and per holding the least width from
which e and beta stay within two standard errors of the next wider wall
(``verdict``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..impact.failures import impact_state
from .readings import Setup

COLUMNS = (
    "reading",
    "study_lattice",
    "seed",
    "gamma_deg",
    "wall_fixed",
    "wall_width",
    "n_wall",
    "n_wall_points",
    "e",
    "beta",
    "contact_time",
    "side_clearance",
    "energy_drift",
    "dt",
    "error",
)
# The default wall's points per R of its width (1,600 over 8 R, 2 R high):
# every width keeps its spacing, so that a wider wall is more of the same
# material, not the same points spread thinner (the "density" wall is
# another one: the disk's number density).
WALL_POINTS_PER_R = 200
# The wall the costs are compared with: today's default, 8 R held at its sides.
BASE = {"wall_fixed": "sides", "wall_width": 8.0}
# What a held wall is in the continuum (the page's words; ``height``: the wall's, in R).
CONTINUUM = {
    "sides": "a clamped beam of span W and thickness {height:g} R",
    "sides+bottom": "an elastic layer of thickness {height:g} R on a rigid base",
}
# How many standard errors of a paired difference count as "the same".
SAME_WITHIN = 2.0
QUANTITIES = ("e", "beta")


def wall_points(width: float) -> int:
    """The points of a ``width`` R wide wall at the default wall's spacing."""
    return int(round(WALL_POINTS_PER_R * width))


def label(choice: dict) -> str:
    """A wall's reading: ``sides+bottom_width32``."""
    return f"{choice['wall_fixed']}_width{choice['wall_width']:g}"


def plan(choice: dict, study):
    """The combination's study as run: its wall's points tied to its width."""
    return replace(study, n_wall=wall_points(choice["wall_width"]))


def row_fields(choice: dict, setup: Setup) -> dict:
    """What every row of a wall records (failed impacts too, which have no columns)."""
    return {
        "wall_fixed": choice["wall_fixed"],
        "wall_width": choice["wall_width"],
        "n_wall": wall_points(choice["wall_width"]),
    }


def walls(choices) -> list[tuple[str, float]]:
    """The walls of a study's combinations, (held, width), in its order."""
    return [(c["wall_fixed"], float(c["wall_width"])) for c in choices]


def holdings(choices) -> dict[str, list[float]]:
    """Each holding's widths, narrowest first, in the order the study gives the holdings."""
    out: dict[str, list[float]] = {}
    for fixed, width in walls(choices):
        out.setdefault(fixed, []).append(width)
    return {fixed: sorted(widths) for fixed, widths in out.items()}


def reading(fixed: str, width: float) -> str:
    return label({"wall_fixed": fixed, "wall_width": width})


def median(values) -> float | None:
    return float(np.median(values)) if len(values) else None


def mean_se(values) -> tuple[float, float] | None:
    """The mean and its standard error over the seeds (NaN for one value,
    None for none)."""
    a = np.asarray(values, float)
    if len(a) < 2:
        return (float(a[0]), float("nan")) if len(a) else None
    return float(a.mean()), float(a.std(ddof=1) / np.sqrt(len(a)))


def by_seed(rows: list[dict], name: str, gamma: float) -> dict[int, dict]:
    """A wall's rows at one angle, by seed."""
    return {
        int(r["seed"]): r for r in rows if r["reading"] == name and float(r["gamma_deg"]) == gamma
    }


def angles(rows: list[dict]) -> list[float]:
    return sorted({float(r["gamma_deg"]) for r in rows})


def wall_row(runs: list[dict]) -> dict:
    """One wall at one angle: impacts, failures, e, beta, contact, sides, cost."""
    good = [r for r in runs if not r.get("error")]
    clearance = np.array([float(r["side_clearance"]) for r in good])
    seconds = [float(r["wall_seconds"]) for r in good if r.get("wall_seconds") not in (None, "")]
    points = [int(float(r["n_wall_points"])) for r in good]
    return {
        "impacts": len(good),
        "failed": sum(bool(r.get("error")) and impact_state(r["error"]) == "failed" for r in runs),
        "stuck": sum(bool(r.get("error")) and impact_state(r["error"]) == "stuck" for r in runs),
        "points": median(points),
        "e": mean_se([float(r["e"]) for r in good]),
        "beta": mean_se([float(r["beta"]) for r in good]),
        "contact_time": median([float(r["contact_time"]) for r in good]),
        "near": int((clearance < 1.0).sum()),
        "past": int((clearance < 0.0).sum()),
        "seconds": float(np.mean(seconds)) if seconds else None,
        "seconds_total": float(np.sum(seconds)),
    }


def paired_step(rows: list[dict], fixed: str, narrow: float, wide: float, gamma: float) -> dict:
    """The wider wall minus the narrower, seed by seed, at one angle: the
    seeds that finished on both (``pairs``), the mean and standard error of
    the per-seed differences of e and beta, the seeds that failed on one wall
    only (``one_sided``), and whether the two walls are ``same``: at least
    two pairs, no seed failing on one only, and both differences within
    SAME_WITHIN standard errors of zero."""
    a, b = by_seed(rows, reading(fixed, narrow), gamma), by_seed(rows, reading(fixed, wide), gamma)
    seeds = sorted(set(a) & set(b))
    both = [s for s in seeds if not a[s].get("error") and not b[s].get("error")]
    one_sided = [s for s in seeds if bool(a[s].get("error")) != bool(b[s].get("error"))]
    out = {"gamma": gamma, "narrow": narrow, "wide": wide, "pairs": len(both)}
    out["one_sided"] = one_sided
    same = len(both) >= 2 and not one_sided
    for q in QUANTITIES:
        d = mean_se([float(b[s][q]) - float(a[s][q]) for s in both])
        out[q] = d
        same = same and d is not None and abs(d[0]) <= SAME_WITHIN * d[1]
    out["same"] = bool(same)
    return out


def steps(rows: list[dict], choices) -> dict[str, list[list[dict]]]:
    """Per holding, its consecutive widths' paired steps, each a list over the angles."""
    gammas = angles(rows)
    return {
        fixed: [
            [paired_step(rows, fixed, narrow, wide, g) for g in gammas]
            for narrow, wide in zip(widths, widths[1:])
        ]
        for fixed, widths in holdings(choices).items()
    }


def why_not(step: list[dict]) -> str:
    """What makes a step of widths not the same, in words: at each angle that
    is not, the seeds failing on one wall only, too few pairs, and each
    quantity beyond SAME_WITHIN standard errors."""
    said = []
    for s in step:
        if s["same"]:
            continue
        why = []
        if s["one_sided"]:
            n = len(s["one_sided"])
            why.append(f"{n} seed{'s' if n != 1 else ''} failing on one of the two walls only")
        if s["pairs"] < 2:
            why.append(f"{s['pairs']} seed{'s' if s['pairs'] != 1 else ''} finished on both")
        else:
            for q in QUANTITIES:
                m, se = s[q]
                if not abs(m) <= SAME_WITHIN * se:
                    why.append(f"{q} moving by {m:+.3f} +- {se:.3f}")
        said.append(f"{', '.join(why)} at {s['gamma']:g} degrees")
    return "; ".join(said)


def verdict(fixed: str, widths: list[float], holding_steps: list[list[dict]]) -> dict:
    """The least width from which e and beta at every angle stay within
    SAME_WITHIN standard errors of the next wider wall (every step from it on
    ``same``), and the sentence that says it."""
    same = [all(s["same"] for s in step) for step in holding_steps]
    start = None
    for i in range(len(same) - 1, -1, -1):
        if not same[i]:
            break
        start = widths[i]
    if len(widths) < 2:
        text = f"one width only ({widths[0]:g} R): nothing to compare"
    elif start is not None:
        text = f"width-independent from {start:g} R"
    elif not any(same):
        text = "changes with its width at every width measured"
    else:
        last = max(i for i, s in enumerate(same) if not s)
        text = (
            f"changes with its width up to the widest measured: from {widths[last]:g} to "
            f"{widths[last + 1]:g} R, {why_not(holding_steps[last])}"
        )
    changed = [
        {"narrow": widths[i], "wide": widths[i + 1], "why": why_not(step)}
        for i, step in enumerate(holding_steps)
        if not same[i]
    ]
    return {"fixed": fixed, "from": start, "text": text, "changed": changed}


def causes(rows: list[dict], choices) -> list[dict]:
    """The impacts without a result, by wall, angle and cause (the table's
    causes: analysis.impact.failures.failure_cause), with their seeds."""
    out: dict[tuple, list[int]] = {}
    order = {w: i for i, w in enumerate(walls(choices))}
    for r in rows:
        if r.get("error"):
            key = (r["wall_fixed"], float(r["wall_width"]), float(r["gamma_deg"]), r["error"])
            out.setdefault(key, []).append(int(r["seed"]))
    keys = sorted(out, key=lambda k: (order[k[:2]], *k[2:]))
    return [
        {"fixed": f, "width": w, "gamma": g, "cause": c, "state": impact_state(c),
         "seeds": sorted(out[(f, w, g, c)])}
        for f, w, g, c in keys
    ]  # fmt: skip


def summary(rows: list[dict], choices) -> dict:
    """Everything the page says: per angle and wall (``table``, with each
    wall's LAMMPS seconds per finished impact over the BASE wall's at that
    angle, ``ratio``); the failures (``causes``); per holding the paired
    steps between consecutive widths (``steps``) and its ``verdicts``; the
    totals (impacts, without a result, LAMMPS seconds of the finished)."""
    table = []
    for gamma in angles(rows):
        at = [r for r in rows if float(r["gamma_deg"]) == gamma]
        base = wall_row([r for r in at if r["reading"] == label(BASE)])
        for fixed, width in walls(choices):
            row = wall_row([r for r in at if r["reading"] == reading(fixed, width)])
            ratio = None
            if row["seconds"] is not None and base["seconds"]:
                ratio = row["seconds"] / base["seconds"]
            table.append({"gamma": gamma, "fixed": fixed, "width": width, **row, "ratio": ratio})
    paired = steps(rows, choices)
    verdicts = [verdict(f, w, paired[f]) for f, w in holdings(choices).items()]
    return {
        "table": table,
        "causes": causes(rows, choices),
        "steps": paired,
        "holdings": holdings(choices),
        "verdicts": verdicts,
        "impacts": len(rows),
        "without_result": sum(bool(r.get("error")) for r in rows),
        "seconds": float(sum(t["seconds_total"] for t in table)),
        "points": {w: wall_points(w) for w in sorted({w for _, w in walls(choices)})},
        "dt": sorted({float(r["dt"]) for r in rows if r.get("dt") not in (None, "")}),
    }
