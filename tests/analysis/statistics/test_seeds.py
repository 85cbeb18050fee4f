"""The seed bootstrap (analysis/statistics/seeds.py): on synthetic impacts whose seeds
share an offset across all their angles, resampling whole seeds must give the
error that the offset implies, larger than resampling each angle on its own
by a known factor."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.estimates import study_estimates
from analysis.statistics.fits import fit_walton, means
from analysis.statistics.seeds import SeedTable, seed_bootstrap, seed_tables
from analysis.theory.tangential import walton_beta
from tests.synthetic import PSI, impact_rows

TAU, SIGMA = 0.05, 0.05  # sd of a seed's offset, shared by its angles, and of each impact
SEEDS = 200
RESAMPLES = 400
# An sd from 400 resamples is within about 3.5 % (1/sqrt(2 x 400)) of the
# bootstrap's exact one: against the sample's own closed form, 10 % is over
# two of those. Against the population's (the known factor), the sample of
# 200 seeds adds about 5 %: 15 %. Independent angles would miss the factors
# checked by 50 % or more.
MONTE_CARLO = 0.10
TOLERANCE = 0.15


def per_angle_resample(table: SeedTable, rng: np.random.Generator) -> SeedTable:
    """Each angle's impacts drawn with replacement on their own: the bootstrap
    that treats the angles as independent, for comparison."""
    seeds, angles = table.values["beta"].shape
    index = rng.integers(0, seeds, size=(seeds, angles))
    columns = np.arange(angles)
    return SeedTable(
        table.seeds, table.gamma_deg, {k: v[index, columns] for k, v in table.values.items()}
    )


def per_angle_sd(table: SeedTable, statistic, resamples: int = RESAMPLES) -> float:
    rng = np.random.default_rng(1)
    return float(
        np.std([statistic(per_angle_resample(table, rng)) for _ in range(resamples)], ddof=1)
    )


@pytest.fixture(scope="module")
def offset_rows():
    mu, beta0 = 0.2, 0.4  # the kink at cot gamma 1.30, between two angles
    return impact_rows(
        "random",
        lambda psi: walton_beta(psi, 0.8, mu, beta0, 3.0),
        seeds=SEEDS,
        offset_sd=TAU,
        noise_sd=SIGMA,
    )


def test_the_mean_over_angles_gets_the_error_of_whole_seeds(offset_rows):
    tables = seed_tables(offset_rows)
    angles = len(PSI)

    def mean_over_angles(table: SeedTable) -> float:
        return float(np.mean(table.mean("beta")))

    seed_sd = float(
        seed_bootstrap(tables, lambda t: {"m": mean_over_angles(t["random"])}, RESAMPLES)["m"]
    )
    independent_sd = per_angle_sd(tables["random"], mean_over_angles)
    # resampling seeds resamples their means over the angles: the sd of a mean
    per_seed = np.mean(tables["random"].values["beta"], axis=1)
    assert seed_sd == pytest.approx(np.std(per_seed) / np.sqrt(SEEDS), rel=MONTE_CARLO)
    # in the population, the mean over A angles of S seeds has var = (tau^2 +
    # sigma^2 / A) / S, where independent angles would give (tau^2 + sigma^2) / (A S)
    factor = np.sqrt((angles * TAU**2 + SIGMA**2) / (TAU**2 + SIGMA**2))
    assert seed_sd / independent_sd == pytest.approx(factor, rel=TOLERANCE)
    assert factor > 2.9  # 16 angles, tau = sigma: sqrt(8.5)


def test_a_fitted_parameter_gets_the_error_of_whole_seeds(offset_rows):
    """beta0 of the paper's-way (unweighted) Walton fit is the mean of the
    plateau's per-angle means, so its error is known in closed form."""
    fits, _ = study_estimates(offset_rows, RESAMPLES, compliant=False)
    paper = fits["lattices"]["random"]["walton"]["paper"]
    plateau = PSI > (1 + 0.4) / (0.2 * 1.8 * 3.0)
    factor = np.sqrt((plateau.sum() * TAU**2 + SIGMA**2) / (TAU**2 + SIGMA**2))
    table = seed_tables(offset_rows)["random"]
    independent_sd = per_angle_sd(table, lambda t: fit_walton(means(t), 3.0, 0.8, False)[1])
    # the table's angles increase in gamma, as PSI decreases: the same order
    per_seed = np.mean(table.values["beta"][:, plateau], axis=1)
    expected = np.std(per_seed) / np.sqrt(SEEDS)
    assert paper["beta0"] == pytest.approx(np.mean(per_seed), abs=1e-9)
    assert paper["beta0"] == pytest.approx(0.4, abs=3 * expected)
    assert paper["beta0_sd"] == pytest.approx(expected, rel=MONTE_CARLO)
    assert paper["beta0_sd"] / independent_sd == pytest.approx(factor, rel=TOLERANCE)
    assert fits["errors"]["kind"] == f"sd over {RESAMPLES} seed-bootstrap resamples"


def test_one_angle_s_mean_gets_its_standard_error(offset_rows):
    """At one angle every seed gives one impact: the seed bootstrap of its mean
    is the standard error sd / sqrt(n) (up to the bootstrap's (n-1)/n)."""
    _, errors = study_estimates(offset_rows, RESAMPLES, compliant=False)
    table = seed_tables(offset_rows)["random"]
    se = table.standard_error("beta")
    boot = np.array([errors[("random", float(g))]["beta_seed_sd"] for g in table.gamma_deg])
    assert np.median(boot / se) == pytest.approx(1.0, rel=0.05)
    assert np.all(np.abs(boot / se - 1.0) < 0.2)


def test_resamples_are_reproducible_and_keep_a_seed_s_lattices_together():
    a = impact_rows("square_nu0.1", lambda psi: 0.0 * psi, seeds=30, offset_sd=0.1, rng_seed=1)
    b = [dict(r, study_lattice="square_nu0.3") for r in a]  # the same impacts on both
    tables = seed_tables(a + b)

    def difference(t):
        return {"d": np.mean(t["square_nu0.3"].mean("beta") - t["square_nu0.1"].mean("beta"))}

    first = seed_bootstrap(tables, difference, 50)
    assert first["d"] == 0.0  # a seed's impacts of both lattices are drawn together
    again = seed_bootstrap(tables, lambda t: {"m": t["square_nu0.1"].mean("beta")}, 50)
    assert np.array_equal(
        again["m"], seed_bootstrap(tables, lambda t: {"m": t["square_nu0.1"].mean("beta")}, 50)["m"]
    )


def test_an_error_below_the_written_digit_of_its_number_is_zero():
    """A wall study's cot gamma is one angle's to 1e-14: its spread over the
    seeds is rounding, which each CPU sums differently, and is written 0; a
    real spread (beta's) is kept as it is."""
    from analysis.statistics.seeds import as_written_error

    rng = np.random.default_rng(1)
    cot = 9.99999 * (1.0 + rng.integers(-8, 9, (40, 3)) * 2.0**-52)
    beta = rng.normal(-0.9, 0.05, (40, 3))
    noise = cot.std(axis=0, ddof=1)
    assert np.all(noise > 0) and np.all(as_written_error(noise, cot) == 0.0)
    spread = beta.std(axis=0, ddof=1)
    assert np.array_equal(as_written_error(spread, beta), spread)
