"""The sliding branch read from the rows (analysis/statistics/sliding.py):
Walton's rows give back their branch and mu, rows without a constant run
give none, and the seeds' covariance decides what each angle's own error
cannot."""

from __future__ import annotations

import numpy as np
from scipy import stats

from analysis.statistics.measures import measures
from analysis.statistics.seeds import SeedTable
from analysis.statistics.sliding import BRANCH_P, constant_p, per_seed_mu_eff, sliding_branch
from analysis.theory.tangential import walton_beta

K = 3.0
PSI = np.array([5.0, 2.0, 1.0, 0.5, 0.2, 0.14, 0.1, 0.08, 0.065, 0.05, 0.035])  # normal first


def table(beta: np.ndarray, e: np.ndarray) -> SeedTable:
    """A lattice's impacts, seeds x angles (PSI's), from their beta and e."""
    seeds = len(beta)
    cot = np.broadcast_to(PSI, beta.shape).copy()
    return SeedTable(
        np.arange(1, seeds + 1),
        np.degrees(np.arctan(1.0 / PSI)),
        {"cot_gamma": cot, "e": e, "beta": beta, "side_clearance": np.full(beta.shape, 5.0)},
    )


def walton_rows(mu: float, beta0: float, seeds: int = 16, noise: float = 0.01, rng_seed: int = 1):
    rng = np.random.default_rng(rng_seed)
    e = 0.85 + 0.01 * rng.standard_normal((seeds, len(PSI)))
    beta = walton_beta(PSI, e, mu, beta0, K) + noise * rng.standard_normal((seeds, len(PSI)))
    return table(beta, e)


def test_walton_rows_give_back_their_branch_and_mu():
    """Fifty draws of Walton's rows: the branch is the angles below the kink
    in about 46 (the test's own 5 % of false stops, and a run past the kink
    now and then); a run that stopped at its first failing angle would find
    it in about 34 (seed by seed, 1 to 50: 45 against 34). mu on the
    branch is mu within its error."""
    mu, beta0 = 0.3, -0.6  # the kink at cot gamma 0.24: the six most grazing angles
    kink = (1 + beta0) / (mu * 1.85 * K)
    exact = 0
    for draw in range(50):
        rows = walton_rows(mu, beta0, rng_seed=draw)
        branch, p = sliding_branch(rows, K)
        exact += np.array_equal(branch, PSI < kink)
        if branch.any():
            assert p >= BRANCH_P
            found = measures(rows, K, branch)["mu_branch"]
            assert abs(found - mu) < 0.01
    assert exact >= 42  # two binomial errors below 46


def test_rows_whose_mu_eff_climbs_to_the_last_angle_hold_no_branch():
    """mu_eff rising at every angle toward grazing (no Coulomb sliding):
    no two grazing angles share one constant, and mu on the branch is NaN."""
    rng = np.random.default_rng(2)
    e = np.full((16, len(PSI)), 0.85)
    mu_eff = 0.1 + 0.5 * (0.2 - np.minimum(PSI, 0.2))  # 0.1 to 0.18, steepest where grazing
    beta = mu_eff * (1 + e) * K * PSI - 1 + 0.002 * rng.standard_normal(e.shape)
    rows = table(beta, e)
    branch, p = sliding_branch(rows, K)
    assert not branch.any() and p is None
    assert np.isnan(measures(rows, K, branch)["mu_branch"])


def test_a_trend_every_seed_shares_is_no_branch_though_each_angles_error_hides_it():
    """Each seed's surface shifts its mu_eff at every angle alike (sd 0.05),
    and mu_eff falls by 0.005 per angle: each angle's own error (0.0125)
    hides the trend, each seed's own differences show it."""
    rng = np.random.default_rng(3)
    seeds = 16
    e = np.full((seeds, len(PSI)), 0.85)
    trend = 0.3 - 0.005 * np.arange(len(PSI))[::-1]  # the most grazing highest
    offset = 0.05 * rng.standard_normal((seeds, 1))
    mu_eff = trend + offset + 0.003 * rng.standard_normal((seeds, len(PSI)))
    rows = table(mu_eff * (1 + e) * K * PSI - 1, e)
    grazing = slice(-6, None)
    values = per_seed_mu_eff(rows, K)[:, grazing]
    means, errors = values.mean(axis=0), values.std(axis=0, ddof=1) / np.sqrt(seeds)
    level = np.average(means, weights=errors**-2)
    independent = stats.chi2.sf(np.sum(((means - level) / errors) ** 2), values.shape[1] - 1)
    assert independent > 0.5  # the angles taken as independent: one constant
    assert constant_p(values) < 1e-6
    branch, _ = sliding_branch(rows, K)
    assert not branch.any()


def test_a_run_needs_more_seeds_than_angles():
    rows = walton_rows(0.3, -0.6, seeds=2)
    assert constant_p(per_seed_mu_eff(rows, K)[:, -2:]) is None
    branch, p = sliding_branch(rows, K)
    assert not branch.any() and p is None
    branch, _ = sliding_branch(walton_rows(0.3, -0.6, seeds=4), K)
    assert 2 <= branch.sum() <= 3
