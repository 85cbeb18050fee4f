"""The limit with its form as a systematic (analysis/statistics/extrapolation.py)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.extrapolation import fit_form, halvings, limit, spacing
from ground.digits import half_range

NS = [800, 1600, 3200, 6400, 12800]


def levels(q, sd=0.002, ns=NS):
    return [(n, q(spacing(n)), sd) for n in ns]


def test_each_form_gives_back_its_own_intercept():
    for form, truth in (("h", lambda h: 0.7 + 0.1 * h), ("h2", lambda h: 0.7 + 0.1 * h**2)):
        n, q, sd = zip(*levels(truth), strict=True)
        found = fit_form(n, q, sd, form)
        assert found["limit"] == pytest.approx(0.7, abs=1e-9)
        assert found["c"] == pytest.approx(0.1, abs=1e-9)
        assert found["describes"]
    n, q, sd = zip(*levels(lambda h: 0.7 + 0.1 * h**1.5), strict=True)
    power = fit_form(n, q, sd, "power")
    assert power["p"] == pytest.approx(1.5, abs=1e-6)
    assert power["limit"] == pytest.approx(0.7, abs=1e-7)


def test_the_line_in_h_has_the_weighted_least_squares_error():
    # the intercept's error of a weighted line: sqrt of (X^T W X)^-1's first element
    sd = np.array([0.01, 0.012, 0.02, 0.03, 0.04])
    n = np.array(NS, float)
    q = 0.7 + 0.1 * spacing(n) + np.array([0.003, -0.004, 0.01, -0.01, 0.02])
    found = fit_form(n, q, sd, "h")
    x = np.stack([np.ones_like(n), spacing(n)], axis=1) / sd[:, None]
    assert found["limit_sd"] == pytest.approx(np.sqrt(np.linalg.inv(x.T @ x)[0, 0]), rel=1e-6)
    assert found["dof"] == 3


def test_the_band_is_the_spread_of_the_forms_that_describe_the_levels():
    # curved between h and h^2, with errors wide enough for both to describe it
    out = limit(levels(lambda h: 0.7 + 0.1 * h**1.5, sd=0.02))
    assert out["status"] == "limit"
    intercepts = [out["forms"][f]["limit"] for f in out["described_by"]]
    assert set(out["described_by"]) == {"h", "h2", "power"}
    # half the band, of the intercepts as written (ground.digits: to their six digits)
    assert out["systematic"] == pytest.approx(0.5 * (max(intercepts) - min(intercepts)), abs=1e-6)
    assert out["systematic"] == half_range(intercepts)
    assert out["band"][0] < 0.7 < out["band"][1]
    assert out["value"] == pytest.approx(0.5 * sum(out["band"]))
    assert out["stat"] == max(out["forms"][f]["limit_sd"] for f in ("h", "h2"))
    # the 800-point level's height above the limit is the fits' c, here near 0.1
    assert out["shift_800"] == pytest.approx(0.1, abs=0.03)


def test_a_form_the_levels_reject_leaves_the_band():
    out = limit(levels(lambda h: 0.7 + 0.1 * h, sd=0.001))
    assert out["described_by"] == ["h", "power"]
    assert out["systematic"] == pytest.approx(0.0, abs=1e-6)


def test_a_quantity_whose_last_halving_does_not_shrink_is_not_converged():
    # steps -0.03 then -0.05: growing, and the last one far beyond its error
    values = {800: 0.85, 1600: 0.82, 3200: 0.78, 6400: 0.75, 12800: 0.70}
    out = limit([(n, v, 0.005) for n, v in values.items()])
    assert out["status"] == "not converged"
    assert "value" not in out
    assert out["halvings"]["finest"] == 12800
    assert out["halvings"]["last"][0] == pytest.approx(-0.05)
    assert out["halvings"]["before"][0] == pytest.approx(-0.03)
    assert out["halvings"]["last"][1] == pytest.approx(np.hypot(0.005, 0.005))


def test_a_flat_quantity_is_converged_even_if_its_noise_grows():
    values = {800: 0.30, 1600: 0.31, 3200: 0.30, 6400: 0.302, 12800: 0.32}
    out = limit([(n, v, 0.02) for n, v in values.items()])
    assert out["halvings"]["last_is_real"] is False
    assert out["status"] == "limit"


def test_coupled_steps_replace_the_independent_errors():
    values = [(n, 0.8 - 0.02 * np.log2(n / 800), 0.02) for n in (800, 1600, 3200)]
    assert halvings(values)["converged"]  # steps equal but within independent errors
    tight = halvings(values, steps={3200: (-0.02, 0.003), 1600: (-0.02, 0.003)})
    assert not tight["converged"]


def test_too_few_levels_and_coarse_ones_give_no_limit():
    out = limit([(200, 1.0, 0.1), (400, 1.0, 0.1), (800, 1.0, 0.1), (1600, 1.0, 0.1)])
    assert out["status"] == "too few" and out["levels"] == [800, 1600]
    assert halvings([(800, 1.0, 0.1), (3200, 1.0, 0.1)]) is None


def test_a_value_the_same_at_every_level_without_scatter_is_its_own_limit():
    out = limit([(n, 0.0, 0.0) for n in (800, 1600, 3200)])
    assert out["status"] == "limit" and out["value"] == 0.0 and out["systematic"] == 0.0
    assert limit([(800, 0.0, 0.0), (1600, 0.1, 0.0), (3200, 0.0, 0.0)])["status"] == "too few"


def test_a_power_law_whose_exponent_ends_on_a_bound_describes_nothing():
    # a step then flat: the best exponent runs to the largest bound
    values = {800: 0.9, 1600: 0.7, 3200: 0.7, 6400: 0.7, 12800: 0.7}
    n, q = zip(*values.items(), strict=True)
    power = fit_form(n, q, [0.01] * 5, "power")
    assert power["pinned"] and not power["describes"]


def test_at_few_seeds_a_step_is_real_only_beyond_the_t_quantile():
    # the last step 2.5 errors: real at 16 seeds (beyond 2), not at 4 (t 3.18)
    values = [(800, 0.80, 0.0), (1600, 0.78, 0.0), (3200, 0.755, 0.0)]
    steps = {3200: (-0.025, 0.01), 1600: (-0.02, 0.01)}
    many = halvings(values, steps, seeds={800: 16, 1600: 16, 3200: 16})
    few = halvings(values, steps, seeds={800: 16, 1600: 16, 3200: 4})
    assert many["last_is_real"] and not many["converged"]
    assert few["threshold"] == pytest.approx(3.182446, rel=1e-6)
    assert not few["last_is_real"] and few["converged"]


def test_correlated_levels_are_fitted_by_generalized_least_squares():
    # the GLS intercept, its error and chi^2 from the normal equations
    # (X^T C^-1 X) b = X^T C^-1 q, written here apart from curve_fit
    n = np.array(NS, float)
    q = 0.7 + 0.1 * spacing(n) + np.array([0.003, -0.004, 0.01, -0.01, 0.02])
    var = np.cumsum([0.01**2, 0.004**2, 0.003**2, 0.003**2, 0.002**2])
    cov = np.minimum.outer(var, var)  # multilevel levels share what lies below both
    found = fit_form(n, q, np.sqrt(var), "h", cov)
    x = np.stack([np.ones_like(n), spacing(n)], axis=1)
    inverse = np.linalg.inv(cov)
    normal = np.linalg.inv(x.T @ inverse @ x)
    b = normal @ x.T @ inverse @ q
    r = q - x @ b
    assert found["limit"] == pytest.approx(b[0], rel=1e-7)
    assert found["limit_sd"] == pytest.approx(np.sqrt(normal[0, 0]), rel=1e-6)
    assert found["chi2"] * found["dof"] == pytest.approx(r @ inverse @ r, rel=1e-6)
    # the same levels taken as independent: another (wrong) answer
    assert fit_form(n, q, np.sqrt(var), "h")["limit"] != pytest.approx(b[0], rel=1e-3)


def test_a_diagonal_covariance_is_the_independent_fit():
    sd = np.array([0.01, 0.012, 0.02, 0.03, 0.04])
    n = np.array(NS, float)
    q = 0.7 + 0.1 * spacing(n) ** 1.5 + np.array([0.003, -0.004, 0.01, -0.01, 0.02])
    for form in ("h", "h2", "power"):
        plain, diagonal = fit_form(n, q, sd, form), fit_form(n, q, sd, form, np.diag(sd**2))
        for key in ("limit", "limit_sd", "chi2", "p"):
            assert diagonal[key] == pytest.approx(plain[key], rel=1e-6)
    covariance = {(a, b): (s**2 if a == b else 0.0) for a, s in zip(NS, sd) for b in NS}
    found = limit(list(zip(NS, q, sd)), covariance=covariance)
    assert found["value"] == pytest.approx(limit(list(zip(NS, q, sd)))["value"], rel=1e-6)


def test_the_sandwich_fits_by_the_levels_errors_and_counts_their_covariance():
    # the weighted fit's intercept, its error A C A^T (A the weighted fit's
    # linear map) and the GLS least chi^2, written here from their formulas
    n = np.array(NS, float)
    q = 0.7 + 0.1 * spacing(n) + np.array([0.003, -0.004, 0.01, -0.01, 0.02])
    var = np.cumsum([0.01**2, 0.004**2, 0.003**2, 0.003**2, 0.002**2])
    cov = np.minimum.outer(var, var)
    found = fit_form(n, q, np.sqrt(var), "h", cov, sandwich=True)
    x = np.stack([np.ones_like(n), spacing(n)], axis=1)
    weights = np.diag(1 / var)
    linear_map = np.linalg.inv(x.T @ weights @ x) @ x.T @ weights
    assert found["limit"] == pytest.approx((linear_map @ q)[0], rel=1e-7)
    assert found["limit_sd"] == pytest.approx(
        np.sqrt((linear_map @ cov @ linear_map.T)[0, 0]), rel=1e-6
    )
    gls = fit_form(n, q, np.sqrt(var), "h", cov)
    assert found["chi2"] == pytest.approx(gls["chi2"], rel=1e-9)
    # shared errors: the sandwich's error is not the independent fit's
    assert found["limit_sd"] != pytest.approx(
        fit_form(n, q, np.sqrt(var), "h")["limit_sd"], rel=0.05
    )
