"""Is beta on a plateau, and mu_eff at the most grazing angle, seed by seed
(analysis/statistics/plateau.py)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.plateau import beta_rise, mu_eff_grazing, over_seeds
from analysis.statistics.seeds import seed_tables
from analysis.theory.tangential import walton_beta
from tests.synthetic import impact_rows

K = 3.0  # inertia ratio 0.5: K = 1 + 1 / 0.5


def table(beta_of, seeds=32, noise_sd=0.05, rng_seed=0):
    rows = impact_rows("random", beta_of, seeds=seeds, noise_sd=noise_sd, rng_seed=rng_seed)
    return seed_tables(rows)["random"]


def test_walton_s_plateau_at_every_angle_shows_no_rise():
    """beta0 below every sliding branch: the same beta at every angle."""
    found = beta_rise(table(lambda psi: walton_beta(psi, 0.8, 5.0, -0.9, K)))
    assert found["on_plateau"] is True
    assert abs(found["value"]) < 2 * found["sd"]


def test_a_rise_toward_normal_incidence_is_resolved_and_measured():
    """beta 0.6 higher near normal incidence than at grazing (a compliant
    contact's shape, not Walton's): the rise comes back within its error."""
    found = beta_rise(table(lambda psi: -0.9 + 0.6 * (psi >= 1.0)))
    assert found["on_plateau"] is False
    assert found["value"] == pytest.approx(0.6, abs=3 * found["sd"])
    assert found["sd"] < 0.05


def test_mu_eff_at_the_most_grazing_angle_is_mu_on_the_sliding_branch():
    """Where the disk slides at the most grazing angle, mu_eff is Walton's mu;
    where that angle is on the plateau, it is below mu (a lower bound)."""
    sliding = mu_eff_grazing(table(lambda psi: walton_beta(psi, 0.8, 0.18, 0.5, K)), K)
    assert sliding["value"] == pytest.approx(0.18, abs=3 * sliding["sd"])
    sticking = mu_eff_grazing(table(lambda psi: walton_beta(psi, 0.8, 0.18, -0.95, K)), K)
    assert sticking["value"] + 3 * sticking["sd"] < 0.18


def test_few_seeds_take_the_t_quantile():
    assert over_seeds(np.arange(20.0))["threshold"] == 2.0
    few = over_seeds([0.1, 0.3, 0.2, 0.4])
    assert few["threshold"] == pytest.approx(3.182, abs=1e-3)  # t(0.975, 3)
    assert few["sd"] == pytest.approx(np.std([0.1, 0.3, 0.2, 0.4], ddof=1) / 2)
