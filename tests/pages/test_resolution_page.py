"""The resolution page (pages.resolution, pages.resolution_tables) from rows
of any reading and any levels, and the study's plan (analysis.kinds.resolution)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from analysis.kinds import resolution
from analysis.kinds.readings import Setup
from analysis.theory.tangential import walton_beta
from pages import resolution_tables
from pages.resolution import page
from tests.synthetic import impact_rows

LEVELS = (800, 1600, 3200, 6400)


def reading_rows(limit: str = "profile", drifting: int | None = None) -> list[dict]:
    """Four seeds per level whose e near normal falls as 0.72 + 0.1 h."""
    rows = []
    rng = np.random.default_rng(5)
    for n in LEVELS:
        h = np.sqrt(800 / n)
        level = impact_rows(
            "random",
            lambda psi: walton_beta(psi, 0.8, 0.15, 0.4, 3.0),
            e_of=lambda psi, h=h: 0.72 + 0.1 * h,
            seeds=4,
            offset_sd=0.05,
            rng_seed=n,
        )
        for r in level:
            r.update(
                reading=f"{limit}_n{n}",
                limit=limit,
                n_disk=n,
                e=r["e"] + rng.normal(0.0, 0.01),
                dt=0.008 * h,
                steps=1000,
                n_wall_points=2 * n,
                drift_exceeded=n == drifting,
            )
        rows += [{k: str(v) for k, v in r.items()} for r in level]
    return rows


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    folder = tmp_path_factory.mktemp("figures")
    study = {"angles": 16, "vn": 0.1, "samples": 4, "lattices": ["random"]}
    text = page(reading_rows(drifting=3200), Setup(study=study, choices=()), folder)
    return text, folder


def test_a_new_reading_gets_its_page_with_its_errors_named(made):
    text, folder = made
    assert "profile, random: 800 (4), 1,600 (4), 3,200 (4), 6,400 (4)" in text
    assert "4 (jackknife)" in text and "(bootstrap)" not in text
    assert (folder / "limits.csv").is_file() and (folder / "levels.csv").is_file()
    assert len(text.encode()) < 20_000


def test_a_level_over_the_drift_limit_is_left_out_and_said_to_be(made):
    text, _ = made
    assert "profile, random, 3,200 points (64 of 64 impacts over the drift limit)" in text
    assert "| 3,200 (left out) | 4 (jackknife) |" in text


def test_the_limit_of_e_comes_from_the_levels_it_keeps():
    summary = resolution.summaries(reading_rows())
    found = resolution.limits(summary)[("profile", "random", "e_normal")]
    assert found["levels"] == list(LEVELS)
    assert found["status"] == "limit"
    assert abs(found["value"] - 0.72) < 2 * np.hypot(found["stat"], found["systematic"]) + 0.01
    kept = resolution.limits({k: v for k, v in summary.items() if k[2] != 1600})
    assert kept[("profile", "random", "e_normal")]["levels"] == [800, 3200, 6400]


def test_limit_words_say_not_converged_with_its_finest_level_and_steps():
    found = {
        "status": "not converged",
        "halvings": {"finest": 12800, "last": (-0.093, 0.016), "before": (-0.054, 0.021)},
    }
    assert resolution_tables.limit_text(found) == "not converged at N = 12,800"
    assert resolution_tables.steps_text(found["halvings"]) == (
        "-0.054 +- 0.021, then -0.093 +- 0.016 (to 12,800)"
    )


def test_the_plan_thins_seeds_with_cost_and_keeps_the_per_point_readings_small():
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


def test_past_its_size_the_page_leaves_the_tables_against_n_to_the_csv(tmp_path, monkeypatch):
    import pages.resolution as module

    study = {"angles": 16, "vn": 0.1, "samples": 4, "lattices": ["random"]}
    monkeypatch.setattr(module, "PAGE_BYTES", 1000)
    text = page(reading_rows(), Setup(study=study, choices=()), tmp_path)
    assert "### profile\n" in text  # its claims
    assert "| 1,600 | 4 (jackknife) |" not in text
    assert "(not on this page, which would pass 20 KB)" in text
    with (tmp_path / "levels.csv").open() as handle:
        assert sum(line.startswith("profile,random,") for line in handle) == len(LEVELS)
