"""The seed jackknife and the choice of error by seed count (analysis/statistics/seeds.py)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.seeds import (
    BOOTSTRAP_FROM,
    SeedTable,
    error_method,
    interval_factor,
    seed_errors,
    seed_jackknife,
)


def table(values: np.ndarray) -> dict[str, SeedTable]:
    seeds, angles = values.shape
    return {
        "random": SeedTable(np.arange(1, seeds + 1), np.linspace(10.0, 80.0, angles), {"e": values})
    }


def mean_of_e(tables: dict[str, SeedTable]) -> dict:
    return {"e": tables["random"].mean("e"), "all": np.nanmean(tables["random"].values["e"])}


@pytest.mark.parametrize("seeds", [2, 4, 5, 8, 15])
def test_the_jackknife_of_a_mean_is_the_standard_error_of_the_mean(seeds):
    values = np.random.default_rng(seeds).normal(0.8, 0.03, size=(seeds, 3))
    sd = seed_jackknife(table(values), mean_of_e)
    # the identity: exactly sd (ddof 1) / sqrt(n), angle by angle
    expected = values.std(axis=0, ddof=1) / np.sqrt(seeds)
    np.testing.assert_allclose(sd["e"], expected, rtol=1e-12)
    # a mean over angles of whole seeds: the sd of the seeds' own means
    per_seed = values.mean(axis=1)
    assert sd["all"] == pytest.approx(per_seed.std(ddof=1) / np.sqrt(seeds), rel=1e-12)


def test_the_jackknife_leaves_out_whole_seeds():
    # a seed's offset shared by its angles makes the angles' errors move together
    rng = np.random.default_rng(3)
    values = rng.normal(0.0, 1.0, size=(6, 1)) + rng.normal(0.0, 0.01, size=(6, 4))
    seen = []

    def statistic(tables):
        seen.append(tables["random"].values["e"].shape)
        return mean_of_e(tables)

    seed_jackknife(table(values), statistic)
    assert seen == [(5, 4)] * 6


def test_the_method_follows_the_seed_count():
    assert BOOTSTRAP_FROM == 16
    assert error_method(4) == "jackknife"
    assert error_method(8) == "jackknife"
    assert error_method(15) == "jackknife"
    assert error_method(16) == "bootstrap"
    values = np.random.default_rng(0).normal(size=(4, 2))
    sd, described = seed_errors(table(values), mean_of_e)
    assert described["method"] == "jackknife" and described["dof"] == 3
    assert "jackknife" in described["kind"]
    np.testing.assert_allclose(sd["e"], values.std(axis=0, ddof=1) / 2, rtol=1e-12)
    _, described = seed_errors(table(np.random.default_rng(0).normal(size=(16, 2))), mean_of_e)
    assert described["method"] == "bootstrap" and "bootstrap" in described["kind"]


def test_intervals_at_few_seeds_use_t():
    assert interval_factor(4) == pytest.approx(3.182446, rel=1e-6)
    assert interval_factor(1000) == pytest.approx(1.96, abs=0.003)
