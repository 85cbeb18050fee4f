"""The readings of the model crossed with the best walls, ranked against the
paper's five facts (MODEL.md section 8; studies/model_readings.toml,
docs/model_readings.md).

Per reading, the five facts with their seed-bootstrap errors
(analysis.estimates, analysis.claims): e (mean over cot gamma >= 1), Walton's
mu and beta0 fitted the paper's way (e 0.8, K 3), the triangular disk's share
of angles with mean beta > 0, and the share of contacts within 1 R of a held
side; each one's miss in units of what counts as near, their sum with its
error, and the ranking by the rule (``rank``, which the study's re-run of the
best follows, with the default of the day: ``current_default``).
"""

from __future__ import annotations

import math
from pathlib import Path

from builder.scene import FIRST_READING, SceneSpec

from .claims import claims
from .estimates import study_estimates
from .readings import MODEL_CHANGES, WALLS, Setup, distance_from_text, markdown_table
from .seeds import QUANTITIES

TITLE = "The readings of the model"
LATTICES = ("random", "triangular")

# The facts (analysis.claims's order) and the number each is measured by.
# Each: its name here, its place in analysis.claims.claims()'s list, which of
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
# (analysis.seeds.QUANTITIES) and the lattice's constants, besides the impact's key.
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
            raise RuntimeError(f"analysis.claims' fact {index} is not {name!r}: {claim['fact']}")
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
    return out


def away(reading: str) -> int:
    """A ``wall/model`` reading's choices away from the paper's text."""
    return distance_from_text(*reading.split("/"))


def rank_summaries(summaries: dict) -> list[str]:
    """Readings from best to worst by total miss; the best is the least, unless
    one closer to the paper's text is within one combined standard error."""
    scored = sorted(
        (r for r in summaries if "total" in summaries[r]), key=lambda r: summaries[r]["total"]
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


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body (no figure): every reading on all its seeds, ranked."""
    study, rerun = setup.study, setup.rerun
    summaries = summaries_of(rows, setup)
    shown = list(summaries)
    ranking = rank_summaries(summaries)
    header = ["wall", "model", "impacts", "failed"]
    header += [f"{name}" for name, *_ in FACTS]
    header += [
        "Walton chi2/dof",
        "misses (e, mu, beta0, share, side)",
        "total miss",
        "away from text",
    ]
    table = []
    for reading in ranking + [r for r in shown if r not in ranking]:
        s = summaries[reading]
        cells = [*reading.split("/"), str(s["impacts"]), str(s["failed"])]
        if "total" not in s:
            table.append(cells + ["-"] * (len(header) - len(cells) - 1) + [str(away(reading))])
            continue
        cells += [f"{s[name]['value']:.3f} +- {s[name]['error']:.3f}" for name, *_ in FACTS]
        cells += [
            f"{s['chi2']:.1f}",
            ", ".join(f"{s[name]['miss']:.2f}" for name, *_ in FACTS),
            f"{s['total']:.2f} +- {s['total_se']:.2f}",
            str(away(reading)),
        ]
        table.append(cells)
    best = ranking[0].split("/") if ranking else None
    return (
        f"Random and triangular disks (800 points), {study['angles']} angles from 5.7 to 80.5 "
        f"degrees, seeds 1 to {study['samples']} per reading (the {rerun.get('best', 0)} best, "
        f"and the default when the run was made, `{setup.record['default']}`, to "
        f"{rerun.get('samples')}), "
        "v_n = 0.1 (in the reading's unit), the default run of the day (velocity "
        f"Verlet, dt = {study['options']['dt']:g} R/c). A reading is a wall (the five best of "
        "[scene_readings.md](scene_readings.md), `points_ka_held`) and a reading of the model "
        "(`first-read`: one point's mass, the speed in c, roughness along the normal, an even "
        "row, the regular disks' band; otherwise the options it changes, docs/model.md "
        "section 8).\n\n"
        "The facts of MODEL.md section 8, each the value with its seed-bootstrap error (whole "
        "seeds resampled, every angle of both disks together): **e** the mean over cot gamma "
        ">= 1 (paper: 0.8); **mu** and **beta0** Walton's fit to the random disk the paper's "
        "way, e fixed at 0.8 and K = 3 (paper: 0.18 and 0.56; its reduced chi^2 beside); "
        "**triangular beta > 0** the triangular disk's share of angles whose mean beta is "
        "positive (paper: 0); **near a side** the random disk's share of contacts within 1 R "
        "of a held side (paper: 0, its contacts stayed on the wall). A miss is |value - paper| "
        "in units of what counts as near (0.1, 0.05, 0.2, 0.1, 0.1); a fact is met at a miss "
        "up to 1. **Total miss**: their sum, with the error of the sum from the facts' errors. "
        "The rule: the default is the reading of least total miss; where others come within "
        "one combined standard error of it, the one with the fewest choices away from the "
        "paper's text (800 points, one ka, the sides held, the speed in c, roughness along the "
        "normal, the triangular disk's surface the random kind).\n\n"
        + markdown_table(header, table)
        + (
            f"\n\nThe rule's pick: wall `{best[0]}`, model `{best[1]}`, total miss "
            f"{summaries[ranking[0]]['total']:.2f} +- {summaries[ranking[0]]['total_se']:.2f}, "
            f"{summaries[ranking[0]]['met']} of 5 facts met.\n"
            if best
            else "\n"
        )
        + f"\nOne row per impact: `{study['name']}/rows.csv` (`python -m runner page "
        f"{study['name']}` rebuilds this page from it).\n"
    )
