"""Walton's mu in the resolution kind (analysis/kinds/resolution.py): a
level's data that bound mu from below only give no limit, and levels that
bound it are extrapolated."""

from __future__ import annotations

import math

from analysis.kinds.resolution import limits, unidentified


def level(mu: float, high: float) -> dict:
    return {
        "seeds": 16,
        "excluded": None,
        "values": {"mu": (mu, 0.01)},
        "mu_bounds": {"measured": (mu - 0.02, high), "paper": (0.0, 0.1)},
    }


def test_a_mu_without_upper_bound_at_any_level_has_no_limit():
    """The fit's values fall exactly on a line in h (a limit the forms would
    find), yet one level's data leave mu open above: not identified."""
    ns = (800, 1600, 3200, 6400)
    summary = {("r", "random", n): level(0.1 + 0.05 * math.sqrt(800 / n), 0.5) for n in ns}
    found = limits(summary, ("mu",))[("r", "random", "mu")]
    assert found["status"] == "limit"
    assert abs(found["forms"]["h"]["limit"] - 0.1) < 1e-6
    summary[("r", "random", 3200)]["mu_bounds"]["measured"] = (0.11, math.inf)
    assert unidentified(summary, "r", "random", "mu") == [(3200, 0.11)]
    assert unidentified(summary, "r", "random", "mu_paper") == []
    # the paper's way unbounded says nothing of the branch; a level whose
    # rows hold no branch withholds its limit, at mu_eff's lower bound there
    summary[("r", "random", 1600)]["mu_bounds"]["paper"] = (0.02, math.inf)
    assert unidentified(summary, "r", "random", "mu_branch") == []
    summary[("r", "random", 1600)]["values"]["mu_branch"] = (math.nan, math.nan)
    summary[("r", "random", 1600)]["values"]["mu_eff_grazing"] = (0.15, 0.01)
    assert unidentified(summary, "r", "random", "mu_branch") == [(1600, 0.15)]
    found = limits(summary, ("mu",))[("r", "random", "mu")]
    assert found["status"] == "not identified" and found["open_above"] == [(3200, 0.11)]


def test_a_level_without_a_sliding_branch_keeps_it_as_nan():
    """fits.json writes a missing mu on the branch as null: the level keeps
    it as NaN, so that its claim is undecided and its limit withheld."""
    from analysis.kinds.resolution import extract

    walton = {"mu": 0.1, "mu_sd": 0.01, "beta0": -0.8, "beta0_sd": 0.01}
    measures = {"mu_branch": {"value": None, "sd": None}, "e_normal": {"value": 0.9, "sd": 0.01}}
    fits = {
        "lattices": {
            "random": {"measures": measures, "walton": {"measured": walton, "paper": walton}}
        }
    }
    values = extract(fits, "random")
    assert math.isnan(values["mu_branch"][0]) and values["e_normal"] == (0.9, 0.01)
