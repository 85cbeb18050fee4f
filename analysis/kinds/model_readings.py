"""The readings of the model crossed with the best walls, ranked against the
paper's five facts (docs/model.md section 8; studies/model_readings.toml,
docs/studies/model_readings/model_readings.md).

Per reading, the five facts with their seed-bootstrap errors
(analysis.statistics.estimates, analysis.statistics.claims): e (mean over cot gamma >= 1), Walton's
mu and beta0 fitted the paper's way (e 0.8, K 3), the triangular disk's share
of angles with mean beta > 0, and the share of contacts within 1 R of a held
side; each one's miss in units of what counts as near, their sum with its
error, and the ranking by the rule (``rank``, which the study's re-run of the
best follows, with the default of the day: ``current_default``).
"""

from __future__ import annotations

import math

from builder.scene import FIRST_READING, SceneSpec
from ground.digits import rounded

from ..statistics.claims import claims
from ..statistics.estimates import study_estimates
from ..statistics.seeds import QUANTITIES
from .readings import MODEL_CHANGES, WALLS, Setup, distance_from_text

LATTICES = ("random", "triangular")

# The facts (analysis.statistics.claims's order) and the number each is measured by.
# Each: its name here, its place in analysis.statistics.claims.claims()'s list, which of
# its numbers, and the paper's value (checked against the claim's, so that a
# claims list in another order stops the page instead of mixing facts up).
FACTS = (
    ("e", 0, "model_free", 0.8),
    ("mu", 1, "procedure", 0.18),
    ("beta0", 2, "procedure", 0.56),
    ("triangular beta > 0", 3, "model_free", 0.0),
    ("near a side", 4, "model_free", 0.0),
)
# What the page is made from: every quantity the seed bootstrap averages
# (analysis.statistics.seeds.QUANTITIES) and the lattice's constants, besides the impact's key.
COLUMNS = tuple(
    dict.fromkeys(
        (
            "reading",
            "study_lattice",
            "lattice",
            "seed",
            "gamma_deg",
            *QUANTITIES,
            "vn",
            "touches",
            "energy_drift",
            "steps",
            "nu",
            "error",
        )
    )
)


def label(choice: dict) -> str:
    """A combination's reading: ``wall/model``."""
    return f"{choice['wall']}/{choice['model']}"


def current_default() -> dict:
    """The reading the project runs today (builder.scene.SceneSpec's defaults),
    which the re-run of the best takes to the same precision, so that the
    comparison that would change it is made as precisely as the best's."""
    default = SceneSpec()  # the 800-point disk's, whose wall has 1,600 points
    today = {name: getattr(default, name) for name in ("n_wall", "wall_ka", "wall_fixed")}
    wall = next(k for k, v in WALLS.items() if v == today)
    model_today = {name: getattr(default, name) for name in FIRST_READING}
    model = next(k for k, v in MODEL_CHANGES.items() if {**FIRST_READING, **v} == model_today)
    return {"wall": wall, "model": model}


def fact_numbers(table: list[dict], facts=FACTS) -> dict:
    """The claims' number of each fact (None if the study has none), by name."""
    out = {}
    for name, index, kind, paper in facts:
        claim = table[index]
        if claim["paper"] != paper:
            raise RuntimeError(
                f"analysis.statistics.claims' fact {index} is not {name!r}: {claim['fact']}"
            )
        out[name] = claim[kind]
    return out


def facts(rows: list[dict]) -> dict:
    """The reading's five facts with their errors, misses and their sum."""
    done = [r for r in rows if not r.get("error")]
    out = {"impacts": len(rows), "failed": len(rows) - len(done)}
    if {r["study_lattice"] for r in done} != set(LATTICES):
        return out
    fits, _ = study_estimates(done, compliant=False)
    table = claims(fits)
    total, variance = 0.0, 0.0
    numbers = fact_numbers(table)
    for name, index, _, paper in FACTS:
        claim, number = table[index], numbers[name]
        if number is None or not math.isfinite(number["value"]):
            return out
        miss = abs(number["value"] - paper) / claim["near"]
        error = (number["error"] or 0.0) / claim["near"]
        out[name] = {"value": number["value"], "error": number["error"], "miss": miss}
        total += miss
        variance += error**2
    out["chi2"] = fits["lattices"]["random"]["walton"]["paper"]["chi2"]
    out["total"], out["total_se"] = total, math.sqrt(variance)
    out["met"] = sum(out[name]["miss"] <= 1.0 for name, *_ in FACTS)
    return rounded(out)  # as written: equal totals tie exactly, and break by name


def away(reading: str) -> int:
    """A ``wall/model`` reading's choices away from the paper's text."""
    return distance_from_text(*reading.split("/"))


def rank_summaries(summaries: dict) -> list[str]:
    """Readings from best to worst by total miss; the best is the least, unless
    one closer to the paper's text is within one combined standard error."""
    scored = sorted(
        (r for r in summaries if "total" in summaries[r]), key=lambda r: (summaries[r]["total"], r)
    )
    if not scored:
        return []
    least = summaries[scored[0]]
    close = [
        r
        for r in scored
        if summaries[r]["total"] - least["total"]
        <= math.hypot(summaries[r]["total_se"], least["total_se"])
    ]
    best = min(close, key=lambda r: (away(r), summaries[r]["total"]))
    return [best] + [r for r in scored if r != best]


def rank(rows: list[dict], setup: Setup) -> list[str]:
    """The readings from best to worst by the rule, on the first pass's seeds
    alone (so that a run resumed over the re-run's rows picks the same)."""
    first = [r for r in rows if int(r["seed"]) <= setup.study["samples"]]
    labels = [label(c) for c in setup.choices]
    return rank_summaries({x: facts([r for r in first if r["reading"] == x]) for x in labels})


def summaries_of(rows: list[dict], setup: Setup) -> dict:
    """The facts of every reading ``rows`` hold, in the file's order."""
    present = {r["reading"] for r in rows}
    shown = [label(c) for c in setup.choices if label(c) in present]
    return {x: facts([r for r in rows if r["reading"] == x]) for x in shown}
