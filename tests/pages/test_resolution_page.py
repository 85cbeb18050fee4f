"""The resolution page's extrapolation and plan (analysis.resolution, pages.resolution)."""

import numpy as np
import pytest

from analysis import resolution
from analysis.resolution import extrapolate
from pages.resolution import verdict


def test_a_line_in_the_spacing_gives_back_its_intercept():
    ns = [800, 1600, 3200, 6400, 12800]
    points = [(n, 0.7 + 0.1 * np.sqrt(800 / n), 0.01) for n in ns]
    line = extrapolate(points)
    assert line["limit"] == pytest.approx(0.7, abs=1e-12)
    assert line["slope"] == pytest.approx(0.1, abs=1e-12)
    assert line["chi2"] == pytest.approx(0.0, abs=1e-12)
    # its error is the weighted fit's: more points or smaller errors shrink it
    tighter = extrapolate([(n, q, s / 2) for n, q, s in points])
    assert tighter["limit_sd"] == pytest.approx(line["limit_sd"] / 2)


def test_a_trend_the_line_cannot_follow_has_no_limit():
    # slopes growing as 1 / spacing (the per-point roughness) are not a line in h
    ns = [800, 1600, 3200, 6400]
    points = [(n, 0.1 * np.sqrt(n / 800), 0.005) for n in ns]
    line = extrapolate(points)
    assert line["chi2"] > 2
    assert verdict(line, (0.1, 0.005), (6400, points[-1][1])).startswith("no limit established")


def test_coarse_points_are_left_out_and_few_points_give_no_line():
    assert extrapolate([(200, 1.0, 0.1), (400, 1.0, 0.1), (800, 1.0, 0.1)]) is None


def test_the_plan_thins_seeds_with_cost_and_keeps_the_per_point_readings_small():
    from dataclasses import dataclass

    @dataclass
    class Grid:
        lattices: tuple = ("random", "triangular")
        samples: int = 16

    assert resolution.plan({"n_disk": 800, "limit": "continuum"}, Grid()).samples == 16
    assert resolution.plan({"n_disk": 3200, "limit": "continuum"}, Grid()).samples == 8
    assert resolution.plan({"n_disk": 12800, "limit": "continuum"}, Grid()).samples == 4
    assert resolution.plan({"n_disk": 12800, "limit": "continuum"}, Grid()).lattices == ("random",)
    assert resolution.plan({"n_disk": 6400, "limit": "fixed-contact"}, Grid()) is None
    assert resolution.plan({"n_disk": 800, "limit": "point-roughness"}, Grid()).lattices == (
        "random",
    )
