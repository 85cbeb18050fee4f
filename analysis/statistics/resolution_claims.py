"""The paper's claims judged at each resolution and in the limit
(docs/studies/resolution/resolution.md; the rules are analysis.statistics.claims's).

Per reading, each claim of docs/studies/results/results.md's table that the resolution study
measures, and the letter's e > 1 peak at grazing incidence, gets a verdict at
every level and in the limit N -> infinity:

- at a level, the number's statistical error (widened to the t interval's
  width where fewer than 16 seeds enter: the jackknife's n - 1 degrees of
  freedom) combined in quadrature, for a Walton fit that fails (chi2/dof above
  analysis.statistics.estimates.CHI2_LIMIT), with the fitting choice's systematic error;
- in the limit, the extrapolation's statistical error and the band between
  its forms (analysis.statistics.extrapolation) in quadrature, and for a Walton fit
  that fails at the finest level in the fits, that level's fitting-choice
  systematic error; a quantity not converged,
  with too few levels or no form that describes it is "undecided", never
  judged;
- a level left out of the fits (analysis.kinds.resolution.excluded) is not judged;
- Walton's mu the measured way or with the seeds' covariance
  (analysis.statistics.walton_gls), where a level's profile bounds
  it from below only (``mu_bounds``), misses if that lower bound lies
  beyond the claim's range and is undecided otherwise, and mu on the
  sliding branch found in the rows (analysis.statistics.sliding) is
  undecided at a level whose rows hold no branch; in the limit both are
  undecided ("not identified"). The paper's way is the paper's own
  procedure and is judged by its number and seed error, as the paper gave
  it; a fitted mu below the rows' own lower bound (mu_eff at the most
  grazing angle, ``contradicted``) is said not to describe the rows;
- mu_eff at the most grazing angle is mu or a lower bound of it: it misses
  the claim only if it lies above the claim's range, and is undecided
  otherwise;
- "x > 1" (the grazing peak) meets if the interval x +- 2 errors lies above
  1, misses if below, and is undecided otherwise.
"""

from __future__ import annotations

import math

from scipy import stats

from ground.digits import rounded

from .claims import NEAR, SAME, verdict
from .estimates import CHI2_LIMIT
from .seeds import error_method, interval_factor

# (claim, lattice, quantity, paper's value, near (None: "above"), Walton fit way or None)
CLAIMS = (
    ("e near 0.8 (mean e at cot gamma >= 1)", "random", "e_normal", 0.8, NEAR["e"], None),
    ("Walton's mu near 0.18 (the paper's way)", "random", "mu_paper", 0.18, NEAR["mu"], "paper"),
    (
        "mu near 0.18 (mu on the sliding branch found in the rows)",
        "random",
        "mu_branch",
        0.18,
        NEAR["mu"],
        None,
    ),
    (
        "mu near 0.18 (mu_eff at the most grazing angle: mu where the disk slides there, "
        "a lower bound of mu where it does not)",
        "random",
        "mu_eff_grazing",
        0.18,
        NEAR["mu"],
        None,
    ),
    (
        "Walton's mu near 0.18 (fitted with the seeds' covariance)",
        "random",
        "mu_gls",
        0.18,
        NEAR["mu"],
        "gls",
    ),
    (
        "Walton's beta0 near 0.56 (fitted with the seeds' covariance)",
        "random",
        "beta0_gls",
        0.56,
        NEAR["beta0"],
        "gls",
    ),
    (
        "Walton's beta0 near 0.56 (the paper's way)",
        "random",
        "beta0_paper",
        0.56,
        NEAR["beta0"],
        "paper",
    ),
    (
        "beta0 near 0.56 (mean beta at cot gamma >= 4)",
        "random",
        "beta_normal",
        0.56,
        NEAR["beta0"],
        None,
    ),
    (
        "triangular: beta < 0 at every angle (share of angles with mean beta > 0: 0)",
        "triangular",
        "share_beta_positive",
        0.0,
        NEAR["share_beta_positive"],
        None,
    ),
    (
        "no contact near the wall's ends (share within 1 R: 0)",
        "random",
        "share_near_side",
        0.0,
        NEAR["near_side"],
        None,
    ),
    ("the letter's e > 1 at grazing incidence (largest mean e)", "random", "e_peak_grazing", 1.0),
)
NORMAL_95 = float(stats.norm.ppf(0.975))


def above(value: float, error: float, bound: float) -> str:
    """The verdict on "x > bound" (module docstring)."""
    if not math.isfinite(value):
        return "-"
    if value - SAME * error > bound:
        return "meets"
    return "misses" if value + SAME * error < bound else "undecided"


def level_error(entry: dict, quantity: str, way: str | None) -> tuple[float, float] | None:
    """(value, error) of a quantity at one level (module docstring), or None."""
    if quantity not in entry["values"]:
        return None
    value, sd = entry["values"][quantity]
    seeds = entry["seeds"]
    if error_method(seeds) == "jackknife" and seeds > 1:
        sd *= interval_factor(seeds) / NORMAL_95
    systematic = 0.0
    if way and entry["chi2"][way] > CHI2_LIMIT:
        systematic = entry["systematic"][fitted_parameter(quantity)]
    return value, math.hypot(sd, systematic)


def fitted_parameter(quantity: str) -> str:
    """Walton's parameter a fitted quantity is ("mu_paper", "beta0_gls": mu,
    beta0), whose fitting-choice systematic error (the weighted fit's eight
    choices) a failing fit carries, the covariance's fit too."""
    return quantity.removesuffix("_paper").removesuffix("_gls")


def judge(value: float, error: float, claim: tuple) -> str:
    _, _, quantity, paper, *rest = claim
    if not rest:
        return above(value, error, paper)
    if quantity in LOWER_BOUNDS:  # a lower bound rules out only what lies below it
        return "misses" if rounded(value - SAME * error) > paper + rest[0] else "undecided"
    return verdict(value, error, paper, rest[0])


def contradicted(entry: dict, quantity: str, value: float, error: float) -> str | None:
    """Where a fitted mu lies below the rows' own lower bound of mu (mu_eff
    at the most grazing angle, written as the fit writes mu: the measured e
    and K, or the paper's e 0.8 and K 3) by more than SAME combined errors,
    why the fit does not describe the data; else None. Decided on the
    numbers as written (ground.digits)."""
    where = {
        "mu": entry["values"].get("mu_eff_grazing"),
        "mu_paper": entry.get("mu_eff_grazing_paper"),
    }
    if not where.get(quantity):
        return None
    bound, sd = rounded(where[quantity])
    if rounded(value + SAME * math.hypot(error, sd)) < bound:
        return (
            f"below the most grazing angle's lower bound {bound:.3f} +- {sd:.3f}: "
            "the fit does not describe the rows"
        )
    return None


def limit_verdict(found: dict | None, claim: tuple, systematic: float = 0.0) -> dict:
    """The claim in the limit from ``analysis.statistics.extrapolation.limit``'s answer,
    with ``systematic`` (a fit's fitting-choice error) added in quadrature."""
    if not found or found["status"] != "limit":
        status = found["status"] if found else "too few"
        why = {
            "too few": "too few levels",
            "no form": "no form describes the levels",
            "not identified": "not identified: no sliding branch"
            if found and found.get("of") == "mu_branch"
            else "not identified: no upper bound on mu",
        }.get(status)
        if status == "not converged":
            why = f"not converged at {found['halvings']['finest']:,}"
        return {"value": None, "error": None, "verdict": f"undecided ({why})"}
    error = math.hypot(found["stat"], found["systematic"], systematic)
    return {
        "value": found["value"],
        "error": error,
        "verdict": judge(found["value"], error, claim),
    }


# The fit whose mu a claim rests on: Walton's, each way.
SLIDING_FROM = {"mu": "measured", "mu_gls": "gls"}
# Claims whose number is a lower bound of what the paper claims.
LOWER_BOUNDS = ("mu_eff_grazing",)


def open_above(entry: dict, claim: tuple) -> dict | None:
    """A mu claim's cell at a level whose data bound that fit's mu from below
    only, or hold no sliding branch (module docstring), or None where the fit
    or the branch gives mu."""
    if claim[2] == "mu_branch":
        value = entry["values"].get("mu_branch", (math.nan,))[0]
        if math.isfinite(value):
            return None
        return {"value": None, "error": None, "verdict": "undecided", "note": "no sliding branch"}
    bounds = entry.get("mu_bounds", {}).get(SLIDING_FROM.get(claim[2]))
    if not bounds or not math.isinf(bounds[1]):
        return None
    _, _, _, paper, near, _ = claim
    verdict = "misses" if bounds[0] > paper + near else "undecided"
    note = f"mu >= {bounds[0]:.3f}, no upper bound"
    return {"value": None, "error": None, "verdict": verdict, "note": note}


def finest_systematic(
    summary: dict, found: dict | None, reading: str, lattice: str, quantity: str, way: str | None
) -> float:
    """The fitting-choice systematic error of the finest level in the fits,
    where that level's fit fails; 0 otherwise."""
    if not way or not found or not found.get("levels"):
        return 0.0
    entry = summary[(reading, lattice, max(found["levels"]))]
    if entry["chi2"][way] <= CHI2_LIMIT:
        return 0.0
    return entry["systematic"][fitted_parameter(quantity)]


def claims_table(summary: dict, limits: dict, reading: str) -> list[dict]:
    """Per claim of one reading: ``claim``, ``cells`` (N -> value, error,
    verdict; None where the lattice has no such level) and ``limit``.

    Parameters
    ----------
    summary : dict
        ``analysis.kinds.resolution.summaries``.
    limits : dict
        (reading, lattice, quantity) -> ``analysis.statistics.extrapolation.limit``.
    """
    ns = sorted({n for (li, _, n) in summary if li == reading})
    out = []
    for claim in CLAIMS:
        text, lattice, quantity, *_ = claim
        way = claim[5] if len(claim) > 5 else None
        if not any(li == reading and la == lattice for (li, la, _) in summary):
            continue
        cells = {}
        for n in ns:
            entry = summary.get((reading, lattice, n))
            found = level_error(entry, quantity, way) if entry else None
            if found and (bound := open_above(entry, claim)):
                cells[n] = {**bound, "excluded": entry["excluded"]}
                if entry["excluded"]:
                    cells[n]["verdict"] = "not judged"
                continue
            cells[n] = (
                {
                    "value": found[0],
                    "error": found[1],
                    "verdict": "not judged" if entry["excluded"] else judge(*found, claim),
                    "excluded": entry["excluded"],
                }
                if found
                else None
            )
            if found and (why := contradicted(entry, quantity, *found)):
                cells[n]["note"] = f"{found[0]:.3f} +- {found[1]:.3f}, {why}"
        found = limits.get((reading, lattice, quantity))
        out.append(
            {
                "claim": text,
                "cells": cells,
                "limit": limit_verdict(
                    found, claim, finest_systematic(summary, found, reading, lattice, quantity, way)
                ),
            }
        )
    return out
