"""Walton's fit with the seeds' covariance (analysis/statistics/walton_gls.py):
with a diagonal covariance it is the weighted fit of fits.py, found
independently; its least is the least over any (mu, beta0); on seeds whose
offsets are shared across angles it recovers the truth and bounds it, where
the weighted fit's profile, counting the same seeds at every angle, is too
narrow."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.fits import Means, fit_walton, walton_mu_bounds, walton_profile
from analysis.statistics.seeds import seed_tables
from analysis.statistics.walton_gls import (
    CorrelatedMeans,
    correlated_means,
    estimates,
    fit,
    mu_bounds,
    profile,
)
from analysis.theory.tangential import walton_beta
from tests.synthetic import PSI, impact_rows

K = 3.0
E = 0.8
RNG = np.random.default_rng(7)


def e_of(psi):
    return 0.92 - 0.25 / (1.0 + 4.0 * psi)


def diagonal(beta: np.ndarray, se: np.ndarray) -> tuple[CorrelatedMeans, Means]:
    """The same means with independent errors, in both modules' forms."""
    psi, e = PSI, e_of(PSI)
    return (
        CorrelatedMeans(psi, e, beta, np.diag(1.0 / se), 0.0, 16),
        Means(psi, e, beta, se),
    )


@pytest.mark.parametrize("case", range(12))
def test_with_independent_errors_it_is_the_weighted_fit(case):
    """Two implementations (cumulative sums over splits; whitened least
    squares) of the same exact fit and profile agree."""
    rng = np.random.default_rng(case)
    mu, beta0 = rng.uniform(0.05, 0.4), rng.uniform(-0.8, 0.7)
    se = rng.uniform(0.005, 0.1, len(PSI))
    beta = walton_beta(PSI, e_of(PSI), mu, beta0, K) + se * rng.standard_normal(len(PSI))
    gls, weighted = diagonal(beta, se)
    found = fit(gls, K)
    assert np.allclose(
        [found["mu"], found["beta0"]], fit_walton(weighted, K), rtol=1e-9, atol=1e-12
    )
    for m in (0.01, mu, 0.7, 5.0):
        assert profile(gls, K, m) == pytest.approx(walton_profile(weighted, K, m), rel=1e-9)
    assert np.allclose(mu_bounds(gls, K), walton_mu_bounds(weighted, K, rise=4.0), rtol=1e-7)


def correlated(n: int, offset: float, noise: float, rng_seed: int, beta_of) -> CorrelatedMeans:
    rows = impact_rows(
        "random", beta_of, e_of, seeds=n, offset_sd=offset, noise_sd=noise, rng_seed=rng_seed
    )
    return correlated_means(seed_tables(rows)["random"])


def test_its_least_is_the_least_over_every_mu_and_beta0():
    data = correlated(12, 0.05, 0.03, 3, lambda p: walton_beta(p, e_of(p), 0.2, 0.3, K))
    found = fit(data, K)
    mu, beta0 = np.meshgrid(np.linspace(0.0, 1.0, 401), np.linspace(-1.0, 1.0, 401))
    model = walton_beta(PSI, data.e, mu.ravel()[:, None], beta0.ravel()[:, None], K)
    brute = np.sum(((model - data.beta) @ data.whiten.T) ** 2, axis=1).min()
    assert found["chi2"] <= brute + 1e-12
    assert found["dof"] == len(PSI) - 2


def test_the_covariance_is_positive_definite_with_fewer_seeds_than_angles():
    data = correlated(8, 0.1, 0.02, 4, lambda p: walton_beta(p, e_of(p), 0.2, 0.3, K))
    assert data.seeds == 8 < len(PSI) and 0.0 < data.shrinkage <= 1.0
    inverse = data.whiten.T @ data.whiten
    assert np.all(np.linalg.eigvalsh(inverse) > 0)
    assert (
        correlated_means(seed_tables(impact_rows("random", lambda p: -0.5, seeds=3))["random"])
        is None
    )


def test_seeds_shared_across_angles_widen_the_bounds_and_keep_the_truth():
    """Each seed's beta moves by one offset at every angle (sd 0.1) and by
    little else: the per-angle errors counted as independent make the
    weighted profile's two-sigma interval too narrow to hold the truth in
    many of 30 studies; the covariance's holds it about as often as two
    errors should."""
    truth = 0.2
    held_gls = held_diag = 0
    for k in range(30):
        data = correlated(24, 0.1, 0.01, 100 + k, lambda p: walton_beta(p, e_of(p), truth, 0.3, K))
        low, high = mu_bounds(data, K)
        held_gls += low <= truth <= high
        se = np.sqrt(np.diag(np.linalg.inv(data.whiten.T @ data.whiten)))
        weighted = Means(data.psi, data.e, data.beta, se)
        low, high = walton_mu_bounds(weighted, K, rise=4.0)
        held_diag += low <= truth <= high
    assert held_gls >= 25  # two errors: 95 % of 30, less the noise of 30
    assert held_diag < held_gls


def test_a_level_of_fewer_than_8_seeds_gets_no_fit():
    rows = impact_rows("random", lambda p: walton_beta(p, e_of(p), 0.2, 0.3, K), e_of, seeds=7)
    assert estimates(seed_tables(rows)["random"], K) is None
    rows = impact_rows("random", lambda p: walton_beta(p, e_of(p), 0.2, 0.3, K), e_of, seeds=8)
    found = estimates(seed_tables(rows)["random"], K, resamples=20)
    assert found["errors"] == "jackknife" and found["seeds"] == 8
    assert abs(found["mu"] - 0.2) < 3 * found["mu_sd"] and found["mu_sd"] > 0
