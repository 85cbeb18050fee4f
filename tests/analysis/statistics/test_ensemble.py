"""Paired ensemble differences of two runs of one study (analysis/statistics/ensemble.py)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.statistics.ensemble import impact_differences, paired_differences, summary
from tests.synthetic import impact_rows


def shifted(rows: list[dict], quantity: str, shift: float, noise: float, seed: int) -> list[dict]:
    """The same rows again, ``quantity`` moved by ``shift`` plus noise per impact."""
    rng = np.random.default_rng(seed)
    return [{**r, quantity: float(r[quantity]) + shift + noise * rng.normal()} for r in rows]


def test_a_run_against_itself_differs_by_nothing():
    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=20)
    differences = paired_differences(rows, rows)
    assert all(d.difference == 0.0 and d.z == 0.0 for d in differences)
    assert summary(differences)["beyond"] == 0


def test_round_off_chaos_stays_within_errors():
    """Noise of zero mean on every impact (what chaos does to one impact):
    no more cells beyond 2 errors than a normal distribution puts there."""
    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=100, noise_sd=0.05)
    after = shifted(rows, "beta", 0.0, 0.05, seed=1)
    result = summary(paired_differences(rows, after, ("beta",)))
    assert result["cells"] == 16
    assert result["beyond"] <= 3 and result["largest_z"] < 4.0


def test_a_real_shift_is_found():
    """A bias of half the noise's sd over 100 seeds: 5 standard errors."""
    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=100, noise_sd=0.05)
    after = shifted(rows, "beta", 0.025, 0.05, seed=2)
    differences = paired_differences(rows, after, ("beta",))
    assert all(d.difference == pytest.approx(0.025, abs=0.015) for d in differences)
    assert summary(differences)["beyond"] >= 14


def test_seeds_missing_from_one_run_are_left_out():
    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=10)
    after = [r for r in rows if int(r["seed"]) != 3]
    assert {d.seeds for d in paired_differences(rows, after)} == {9}


def test_studies_with_nothing_in_common_are_refused():
    with pytest.raises(ValueError, match="nothing|no lattice"):
        paired_differences(
            impact_rows("random", lambda p: 0.0), impact_rows("other", lambda p: 0.0)
        )


def test_single_impacts_are_matched_by_lattice_seed_and_angle():
    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=5)
    after = shifted(rows, "e", 0.001, 0.0, seed=0)[::-1]  # another order
    moved = impact_differences(rows, after, "e")
    assert len(moved) == len(rows) and np.allclose(moved, 0.001, rtol=0, atol=1e-12)
