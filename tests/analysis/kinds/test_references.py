"""The symmetric references' study (analysis/kinds/references.py) and its numbers."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.kinds import references
from analysis.kinds.references import group_key, grouped, joint_numbers, pair_speed
from runner.study import Study


@pytest.mark.parametrize("reference", references.ORDER)
def test_the_one_body_references_run_at_half_the_pairs_speed(reference):
    study = Study("refs", target="disk", vn=0.1, speeds=(0.01, 0.2))
    planned = references.plan({"reference": reference}, study)
    half = reference in references.ONE_BODY
    assert planned.vn == pytest.approx(0.05 if half else 0.1)
    assert planned.speeds == pytest.approx((0.005, 0.1) if half else (0.01, 0.2))
    assert pair_speed({"reference": reference, "vn": planned.speeds[1]}) == pytest.approx(0.2)


def impact(reference: str, seed: int, gamma: float, **measured) -> dict:
    """One impact's row: its reference, seed and angle, the columns Walton's
    K is computed from (analysis.statistics.estimates.lattice_constants), and ``measured``."""
    two = {"target": "disk", "n_disk_points": 800, "n_target_points": 800}
    return {
        "reference": reference,
        "study_lattice": "random",
        "lattice": "random",
        "seed": seed,
        "gamma_deg": gamma,
        "vn": 0.05 if reference in references.ONE_BODY else 0.1,
        "cot_gamma": 1.0 / np.tan(np.radians(gamma)),
        **({"target": "wall"} if reference == "wall" else two),
        "target_held": reference in ("image-held", "surface"),
        "nu": 0.3,
        "disk_inertia_ratio": 0.5,
        "target_inertia_ratio": 0.5,
        **measured,
    }


def synthetic(reference: str, shift: float, seeds: int = 6) -> list[dict]:
    rng = np.random.default_rng(3)
    rows = []
    for seed in range(1, seeds + 1):
        disk = rng.normal(0.0, 0.05)  # the seed's own disk, shared by every reference
        for gamma in (5.7106, 30.0, 70.0):
            rows.append(
                impact(reference, seed, gamma, e=0.9 + disk + shift, beta=-0.5 + disk,
                       contact_time=8.0 + 10 * disk + 10 * shift)
            )  # fmt: skip
    return rows


def test_differences_resample_whole_seeds_of_both_references_together():
    """Two references that differ by a constant on every seed: the difference
    is that constant with no error, though each has the seeds' scatter."""
    rows = synthetic("image", 0.02) + synthetic("surface", 0.0)
    numbers = joint_numbers(grouped(rows), resamples=100)
    a, b = group_key("image", 0.1), group_key("surface", 0.1)
    value, error = numbers["value"], numbers["error"]
    assert value[("d_e_first", a, b)] == pytest.approx(0.02)
    assert value[("d_contact_time", a, b)] == pytest.approx(0.2)
    assert error[("d_e_first", a, b)] < 1e-12
    assert error[("e_first", a)] > 1e-3  # each alone scatters with its disks


def walton_rows(reference: str, shift: float, seeds: int = 8) -> list[dict]:
    """Rows whose beta follows Walton's law with each seed's own mu (its
    disk's, shared by every reference) plus a reference's shift."""
    from analysis.theory.tangential import walton_beta

    rng = np.random.default_rng(5)
    rows = []
    for seed in range(1, seeds + 1):
        mu = 0.15 + rng.normal(0.0, 0.03) + shift
        for gamma in (5.7106, 20.0, 40.0, 55.0, 65.0, 75.0, 80.0):
            psi = 1.0 / np.tan(np.radians(gamma))
            beta = float(walton_beta(np.array([psi]), 0.9, mu, 0.5, 3.0)[0])
            rows.append(
                impact(reference, seed, gamma, e=0.9, contact_time=8.0,
                       beta=beta + rng.normal(0.0, 0.002))
            )  # fmt: skip
    return rows


def test_a_mu_difference_keeps_the_correlation_of_shared_seeds():
    """Two references whose seeds' mu move together: the joint bootstrap's
    error of the difference is far below the two errors in quadrature,
    which a sum of independent errors would give."""
    rows = walton_rows("surface", 0.03) + walton_rows("wall", 0.0)
    numbers = joint_numbers(grouped(rows), resamples=100)
    a, b = group_key("surface", 0.1), group_key("wall", 0.1)
    value, error = numbers["value"], numbers["error"]
    assert value[("d_mu", a, b)] == pytest.approx(0.03, abs=0.01)
    assert error[("d_mu", a, b)] < 0.3 * np.hypot(error[("mu", a)], error[("mu", b)])


def test_the_largest_difference_counts_the_look_elsewhere_effect():
    """The largest of n independent normal differences reaches z with the
    chance 1 - (1 - p)^n: checked against draws of n normal variates; a
    withheld comparison is not among the n."""
    from analysis.kinds.references import largest_difference

    def comparison(difference, verdict="same"):
        return {"quantity": "mu", "difference": difference, "error": 0.01, "verdict": verdict,
                "speed": 0.1, "question": "q", "a": "image", "b": "surface"}  # fmt: skip

    comparisons = [comparison(0.01 * z) for z in (0.3, -1.2, 2.5, 0.8)]
    comparisons += [comparison(0.05, "withheld"), {**comparison(0.02), "quantity": "e_first"}]
    top = largest_difference(comparisons, "mu")
    assert top["count"] == 4 and top["z"] == pytest.approx(2.5)
    draws = np.random.default_rng(1).standard_normal((200_000, 4))
    chance = np.mean(np.abs(draws).max(axis=1) >= 2.5)
    assert top["p_global"] == pytest.approx(chance, abs=0.002)
    assert top["z_global"] < top["z"]
    assert largest_difference(comparisons[4:5], "mu") is None
