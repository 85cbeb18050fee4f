"""Per-seed differences between resolutions and Giles's allocation
(analysis/statistics/levels.py)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.kinds.resolution import coupled_levels
from analysis.statistics.levels import (
    allocation,
    cost_per_impact,
    coupled_differences,
    multilevel_levels,
)

GAMMAS = {5.0: 11.43, 20.0: 2.75, 40.0: 1.19, 60.0: 0.58, 70.0: 0.36, 80.0: 0.18}


def rows(coupled: bool, seeds: int = 40, rng_seed: int = 0) -> list[dict]:
    """e = 0.8 - 0.05 (N / 1600) + a seed's surface term (the same at every N
    if coupled) + a small per-impact noise."""
    rng = np.random.default_rng(rng_seed)
    surface = rng.normal(0.0, 0.03, seeds)
    out = []
    for n in (800, 1600, 3200):
        redrawn = rng.normal(0.0, 0.03, seeds)
        for s in range(seeds):
            for gamma, cot in GAMMAS.items():
                e = 0.8 - 0.05 * n / 1600 + (surface[s] if coupled else redrawn[s])
                e += rng.normal(0.0, 0.005)
                out.append(
                    {
                        "n_disk": str(n),
                        "seed": str(s + 1),
                        "gamma_deg": str(gamma),
                        "cot_gamma": str(cot),
                        "e": str(e),
                        "beta": "0.1",
                        "steps": "1000",
                        "n_wall_points": str(2 * n),
                        "error": "",
                    }
                )
    return out


def test_coupled_seeds_cancel_in_the_differences():
    coupled = coupled_differences(rows(True), "e_normal")
    fresh = coupled_differences(rows(False), "e_normal")
    assert [d["n"] for d in coupled] == [1600, 3200]
    for d in coupled:
        # the trend: -0.025 per halving... each step's mean within its error
        assert d["mean"] == pytest.approx(-0.025 * d["n"] / 1600, abs=3 * d["se"] + 1e-3)
        assert d["sd_difference"] < 0.2 * d["sd_level"]
        assert d["variance_ratio"] < 0.05
    for d in fresh:  # redrawn surfaces: the difference of two draws, about sqrt(2) sd
        assert d["sd_difference"] > d["sd_level"]


def test_pairs_are_made_by_seed_and_angle():
    data = rows(True, seeds=5)
    # a failed fine impact and a seed the coarse level lacks
    data = [r for r in data if not (r["n_disk"] == "1600" and r["seed"] == "2")]
    for r in data:
        if r["n_disk"] == "3200" and r["seed"] == "1" and r["gamma_deg"] == "5.0":
            r["error"], r["e"] = "went unstable", ""
    found = {d["n"]: d for d in coupled_differences(data, "e_normal")}
    assert found[1600]["seeds"] == 4
    assert found[3200]["seeds"] == 4  # seed 2 has no 1600-point impacts
    grazing = coupled_differences(data, "e_grazing")
    assert all(d["seeds"] == 4 for d in grazing)


def test_the_allocation_is_giles_and_reaches_its_target():
    v, c, target = [0.03**2, 0.01**2, 0.004**2], [1.0, 3.0, 9.0], 0.005
    out = allocation(v, c, target)
    total = sum(np.sqrt(np.multiply(v, c)))
    expected = np.ceil(np.sqrt(np.divide(v, c)) * total / target**2)
    assert out["seeds"] == expected.astype(int).tolist()
    assert out["error"] <= target
    assert out["cost"] == pytest.approx(float(np.dot(out["seeds"], c)))
    # any other split at the same error costs more (continuous optimum)
    n = np.sqrt(np.divide(v, c)) * total / target**2
    rng = np.random.default_rng(1)
    for _ in range(50):
        other = n * rng.uniform(0.5, 1.5, 3)
        other *= np.sum(np.divide(v, other)) / target**2  # rescaled to the same variance
        assert np.dot(other, c) >= np.dot(n, c) * (1 - 1e-12)


def test_one_level_needs_v_over_target_squared_and_bad_input_is_refused():
    assert allocation([0.03**2], [5.0], 0.005)["seeds"] == [36]
    assert allocation([0.0, 1e-8], [1.0, 1.0], 0.1)["seeds"] == [2, 2]
    with pytest.raises(ValueError, match="target"):
        allocation([0.1], [1.0], 0.0)


def test_cost_is_atom_steps_without_timings_and_seconds_with_them():
    data = rows(True, seeds=2)
    assert cost_per_impact(data) == {800: 1000 * 2400, 1600: 1000 * 4800, 3200: 1000 * 9600}
    for r in data:
        r["wall_seconds"] = str(float(r["n_disk"]) / 100)
    assert cost_per_impact(data)[3200] == pytest.approx(32.0)


def plain_mean(data: list[dict], n: int) -> float:
    """e_normal of level n as the page takes it: the mean over the seeds of
    each seed's mean e at cot gamma >= 1."""
    by_seed: dict[str, list[float]] = {}
    for r in data:
        if int(r["n_disk"]) == n and float(r["cot_gamma"]) >= 1.0:
            by_seed.setdefault(r["seed"], []).append(float(r["e"]))
    return float(np.mean([np.mean(v) for v in by_seed.values()]))


def test_multilevel_levels_telescope_to_the_levels_on_shared_seeds():
    # every seed at every level: Q(800) + the paired steps is Q(N) itself
    data = rows(True, seeds=12)
    steps = {d["n"]: (d["mean"], d["se"]) for d in coupled_differences(data, "e_normal")}
    base = (800, plain_mean(data, 800), 0.01)
    found, covariance = multilevel_levels(base, steps)
    assert [n for n, _, _ in found] == [800, 1600, 3200]
    for n, value, _ in found:
        assert value == pytest.approx(plain_mean(data, n), abs=1e-12)
    # errors add up the halvings; two levels share the coarser one's
    assert found[2][2] ** 2 == pytest.approx(0.01**2 + steps[1600][1] ** 2 + steps[3200][1] ** 2)
    assert covariance[800, 3200] == pytest.approx(0.01**2)
    assert covariance[3200, 1600] == pytest.approx(found[1][2] ** 2)


def test_multilevel_levels_correct_a_fine_level_drawn_on_lucky_seeds():
    # the fine level on its first 6 seeds only, which happen to be high: the
    # multilevel estimate (all 40 seeds at 800 points plus the paired steps)
    # lands near the level over all 40 seeds, the fine level's own mean does not
    data = rows(True, seeds=40, rng_seed=3)
    high = sorted(
        {r["seed"] for r in data},
        key=lambda s: -plain_mean([r for r in data if r["seed"] == s], 800),
    )[:6]
    thin = [r for r in data if r["n_disk"] != "3200" or r["seed"] in high]
    steps = {d["n"]: (d["mean"], d["se"]) for d in coupled_differences(thin, "e_normal")}
    found, _ = multilevel_levels((800, plain_mean(thin, 800), 0.005), steps)
    whole, own = plain_mean(data, 3200), plain_mean(thin, 3200)
    assert abs(found[-1][1] - whole) < 0.005 < abs(own - whole)


def test_coupled_levels_need_every_fitted_level_joined():
    found = [(400, 0.9, 0.01), (800, 0.8, 0.01), (1600, 0.79, 0.01), (3200, 0.78, 0.01)]
    joined, covariance = coupled_levels(found, {1600: (-0.01, 0.002), 3200: (-0.01, 0.002)})
    assert covariance is not None and joined[0] == (400, 0.9, 0.01)
    assert [round(v, 12) for _, v, _ in joined[1:]] == [0.8, 0.79, 0.78]
    # a step missing (too few paired seeds): the levels as they are
    assert coupled_levels(found, {3200: (-0.01, 0.002)}) == (found, None)
