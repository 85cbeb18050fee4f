"""The binary study's comparison with the wall (analysis.binary_comparison, pages.binary);
its committed pages are made again by tests/docs/test_pages_reproducible.py."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from analysis.binary_comparison import comparison, verdict
from tests.synthetic import impact_rows

WALL_BETA = lambda psi: np.minimum(0.2, -1 + 0.3 * psi)  # noqa: E731


def binary(rows: list[dict], shift: float) -> list[dict]:
    """The same impacts between two disks, e higher by ``shift``."""
    return [
        {**r, "target": "disk", "e": float(r["e"]) + shift, "side_clearance": "",
         "momentum_change": 1e-15, "angular_momentum_change": 2e-15,
         "n_disk_points": 800, "n_target_points": 790,
         "target_inertia_ratio": r["disk_inertia_ratio"]}
        for r in rows
    ]  # fmt: skip


@pytest.mark.parametrize(
    "difference, error, expected",
    [(0.1, 0.05, "same"), (0.1, 0.04, "undecided"), (-0.1, 0.03, "differs"), (0.1, np.nan, "-")],
)
def test_the_verdict_is_the_claims_rule(difference, error, expected):
    assert verdict(difference, error) == expected


def test_pairs_by_seed_cancel_what_a_seed_shares():
    """Two disks with e higher by 0.05 than on the wall, beta the same: the
    seed-paired differences are exact (their errors 0) although each mean's
    error is not, and the verdicts follow."""
    wall = impact_rows("random", WALL_BETA, seeds=12, offset_sd=0.1, noise_sd=0.03)
    numbers = comparison(binary(wall, 0.05), wall, resamples=20)
    entry = numbers["lattices"]["random"]
    assert numbers["pairs"] == len(wall)
    assert np.allclose(entry["e_difference"], 0.05, atol=1e-12)
    assert np.allclose(entry["beta_difference"], 0.0, atol=1e-12)
    assert max(entry["e_difference_error"]) < 1e-12
    assert min(entry["beta_disk_error"]) > 0.01  # each mean scatters with the seeds
    assert set(entry["e_verdict"]) == {"differs"} and set(entry["beta_verdict"]) == {"same"}
    assert numbers["largest_angular_change"] == pytest.approx(2e-15)


def test_only_impacts_both_studies_have_are_compared():
    wall = impact_rows("random", WALL_BETA, seeds=8)
    disks = binary([r for r in wall if int(r["seed"]) <= 5], 0.0)
    numbers = comparison(disks, wall, resamples=10)
    assert numbers["pairs"] == len(disks)
    assert max(numbers["lattices"]["random"]["impacts"]) == 5


def test_two_identical_disks_have_the_walls_k_and_a_lighter_partner_more():
    """K = (1/M_A + 1/M_B + R^2/I_A + R^2/I_B) / (1/M_A + 1/M_B): one disk's
    1 + MR^2/I for two alike; a partner of half the mass and inertia, 1 + (1/rA
    + 2/rB) / 3."""
    from analysis.statistics.estimates import two_body_k

    alike = {"n_disk_points": 800, "n_target_points": 800}
    alike.update(disk_inertia_ratio=0.51, target_inertia_ratio=0.51)
    assert two_body_k(alike) == pytest.approx(1.0 + 1.0 / 0.51, rel=1e-14)
    light = dict(alike, n_target_points=400, target_inertia_ratio=0.4)
    assert two_body_k(light) == pytest.approx(1.0 + (1 / 0.51 + 2 / 0.4) / 3.0, rel=1e-14)


def test_the_same_friction_on_both_targets_is_the_same_mu():
    """Both targets with the same beta(psi) and e: the paired difference of
    Walton's mu is 0 (exactly, seed by seed), and the verdict is 'same'."""
    wall = impact_rows("random", WALL_BETA, seeds=12, offset_sd=0.05, noise_sd=0.03)
    numbers = comparison(binary(wall, 0.0), wall, resamples=20)
    difference = numbers["mu_difference"]["random"]
    assert difference["value"] == pytest.approx(0.0, abs=1e-9)
    assert difference["sd"] < 1e-9
    assert difference["verdict"] == "same"


def test_a_grip_of_its_own_between_two_disks_differs_and_counts_its_systematic():
    """Two disks whose beta lies 0.1 above the wall's on the sliding branch:
    a positive mu difference; where the fits fail (chi2/dof > 2), the
    combined error includes the spread over the fitting choices."""
    wall = impact_rows("random", WALL_BETA, seeds=16, offset_sd=0.02, noise_sd=0.02)
    disks = binary(wall, 0.0)
    for r in disks:
        psi = float(r["cot_gamma"])
        r["beta"] = float(r["beta"]) + (0.1 if psi < 3.0 else 0.0)
    d = comparison(disks, wall, resamples=20)["mu_difference"]["random"]
    assert d["value"] > 0.0
    expected = np.hypot(d["sd"], d["systematic"] if d["fits_fail"] else 0.0)
    assert d["error"] == pytest.approx(expected)
    assert d["verdict"] == verdict(d["value"], d["error"])


def test_the_fits_compare_the_targets_over_the_cot_gamma_range_both_cover():
    """Two disks whose measured cot gamma is half the wall's at every angle:
    each target is fitted only at the angles inside the common range."""
    from analysis.binary_comparison import common_range
    from analysis.statistics.seeds import seed_tables

    wall = impact_rows("random", WALL_BETA, seeds=6)
    disks = binary(wall, 0.0)
    for r in disks:
        r["cot_gamma"] = 0.5 * float(r["cot_gamma"])
    tables = seed_tables(disks + [{**r, "study_lattice": "wall"} for r in wall])
    keep_disk, keep_wall, (low, high) = common_range(tables["random"], tables["wall"])
    cot_disk, cot_wall = tables["random"].mean("cot_gamma"), tables["wall"].mean("cot_gamma")
    assert low == pytest.approx(cot_wall.min()) and high == pytest.approx(cot_disk.max())
    assert not keep_disk.all() and not keep_wall.all()
    assert np.all((cot_disk[keep_disk] >= low) & (cot_disk[keep_disk] <= high))
    assert np.all((cot_wall[keep_wall] >= low) & (cot_wall[keep_wall] <= high))


def test_an_e_the_normals_disagree_on_is_withheld_on_the_page(tmp_path):
    """The comparison's table (comparison.csv beside the page) shows e only
    where the normals' check finds it robust on both targets; elsewhere it
    is blank and its verdict 'withheld', which the page counts."""
    from pages.binary import section

    wall = impact_rows("random", WALL_BETA, seeds=8)
    numbers = comparison(binary(wall, 0.0), wall, resamples=10)
    gammas = numbers["lattices"]["random"]["gamma_deg"]
    robust = [j != 2 for j in range(len(gammas))]
    check = {
        "normals": ["apse", "first_touch", "impulse"],
        "lattices": {
            "random": {
                "gamma_deg": gammas,
                "e_robust": robust,
                "beta_robust": [True] * len(gammas),
            }
        },
    }
    text = section({"w": numbers}, "figures", {"two disks (this study)": check}, tmp_path)
    with (tmp_path / "comparison.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == len(gammas)
    assert rows[2]["e_disk"] == rows[2]["e_difference"] == "" and rows[2]["e_wall"] != ""
    assert rows[2]["e_verdict"] == "withheld"
    assert all(
        r["e_disk"] != "" and r["e_verdict"] != "withheld" for j, r in enumerate(rows) if j != 2
    )
    assert "withheld at 1;" in text and "(comparison.csv)" in text
