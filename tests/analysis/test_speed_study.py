"""The speed axis of a study, its preset and its page (analysis/speed.py)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from analysis.speed import power_law, power_law_range
from builder.scene import SceneSpec
from ground.errors import InputError
from runner.study import LATTICES, Study
from runner.study.studies import load_study
from tests.helpers import ROOT
from tests.synthetic import impact_rows, write_tables

# reads the committed pages' bytes or times, which the pages made again
# rewrite: after them (Makefile)
pytestmark = pytest.mark.last


def test_power_law_recovers_a_known_exponent():
    rng = np.random.default_rng(1)
    v = np.geomspace(0.01, 0.3, 7)
    truth = 0.4 * v**0.6
    sigma = 0.03 * truth
    fits = [power_law(v, truth + sigma * rng.standard_normal(7), sigma) for _ in range(200)]
    p = np.array([f["p"] for f in fits])
    # unbiased, and the fit's error is the spread of p over the draws
    assert abs(p.mean() - 0.6) < 3 * p.std() / np.sqrt(len(p))
    assert np.median([f["p_fit_error"] for f in fits]) == pytest.approx(p.std(), rel=0.2)
    assert np.median([f["chi2"] for f in fits]) == pytest.approx(1.0, abs=0.35)
    exact = power_law(v, truth, sigma)
    assert (exact["p"], exact["A"]) == (pytest.approx(0.6, abs=1e-9), pytest.approx(0.4, rel=1e-9))


def test_the_range_is_where_the_law_holds():
    v = np.geomspace(0.01, 0.3, 7)
    y = 0.4 * v**0.6
    y[5:] = y[4] * 1.02 ** np.arange(1, 3)  # saturates above the fifth speed
    sigma = 0.01 * y
    assert power_law_range(v, y, sigma) == (0, 5)
    y[0] = -0.01  # 1 - e below zero cannot be on a log axis
    assert power_law_range(v, y, sigma) == (1, 5)
    assert power_law_range(v[:2], y[:2], sigma[:2]) is None  # two points are not a law


def test_a_speed_axis_runs_every_speed_on_the_same_seeds():
    study = Study("x", lattices=("random", "triangular"), angles=2, samples=3, speeds=(0.2, 0.05))
    jobs = study.jobs()
    assert len(jobs) == 3 * 2 * 2 * 2
    assert study.velocities() == [0.05, 0.2]
    for job in jobs:
        spec = study.spec(job)
        assert spec.vn == job["vn"] and spec.seed == job["seed"]
        # a folder per speed, between the sample's and the angle's
        assert Path(job["folder"]).parent.name == f"v{job['vn']:g}"
    assert len({j["folder"] for j in jobs}) == len(jobs)
    plain = Study("x", lattices=("random",), angles=2, samples=1)
    assert [Path(j["folder"]).parent.name for j in plain.jobs()] == ["s1", "s1"]
    assert {plain.spec(j).vn for j in plain.jobs()} == {plain.vn}


@pytest.mark.parametrize(
    ("speeds", "words"),
    [
        ((0.1, 0.1), "speeds names an impact.s folder twice \\(v0.1\\)"),
        ((0.1, 0.5), "speeds must be a number in"),
    ],
)
def test_bad_speeds_are_refused(speeds, words):
    with pytest.raises(InputError, match=words):
        Study("x", lattices=("random",), speeds=speeds).validate()


def test_the_speed_preset_grid():
    study = load_study("speed")
    speeds = np.array(study.velocities())
    assert speeds[0] == 0.01 and speeds[-1] >= 0.3
    ratios = speeds[1:] / speeds[:-1]
    assert np.allclose(ratios, ratios.mean(), rtol=0.01)  # log-spaced
    assert set(study.lattices) == set(LATTICES) and study.samples >= 20
    gammas = study.gammas()
    assert gammas[0] < 10.0  # near-normal, then a sticking and a sliding angle
    assert len(gammas) >= 3
    study.validate()


def test_the_grazing_preset_grid():
    study = load_study("grazing")
    gammas = np.array(study.gammas())
    assert gammas.max() >= 85.0 and study.samples >= 30
    assert np.all(np.diff(gammas[gammas >= 60]) <= np.diff(gammas[gammas < 60]).min())
    # the default scene, slow enough that the disk's slide during a contact
    # (v_n tan gamma times the contact time the scene centres) keeps its edge
    # more than 1 R from a held side at the largest angle
    default = Study("x")
    assert (study.wall_width, study.n_wall, study.wall_fixed) == (
        default.wall_width,
        default.n_wall,
        default.wall_fixed,
    )
    slide = study.vn * np.tan(np.radians(gammas.max())) * SceneSpec().contact_time_guess
    assert slide / 2 + 1.0 + 1.0 < study.wall_width / 2
    study.validate()


def speed_rows(p_of: dict, seeds: int = 12) -> list[dict]:
    """Rows at three speeds whose e follows 1 - e = 0.5 v^p exactly, plus a
    per-seed offset shared by the seed's speeds and angles."""
    rows = []
    for vn in (0.02, 0.05, 0.1, 0.2):
        for lattice, p in p_of.items():
            part = impact_rows(lattice, lambda psi: -0.5, seeds=seeds, noise_sd=0.01, rng_seed=7)
            for r in part:
                offset = 0.002 * ((r["seed"] * 37) % 11 - 5)
                r.update(vn=vn, e=1.0 - 0.5 * vn**p + offset)
            rows += part
    return rows


def test_the_speed_page_comes_back_from_its_tables(tmp_path):
    from pages.report import report_from_tables

    rows = speed_rows({"random": 0.5, "triangular": 0.8})
    tables = write_tables(
        tmp_path / "tables",
        rows,
        ["random", "triangular"],
        speeds=[0.02, 0.05, 0.1, 0.2],
        samples=12,
    )
    page = tmp_path / "speed.md"
    report_from_tables(tables, page, resamples=50, preset="speed")
    numbers = json.loads((tables / "speed.json").read_text())
    for lattice, p in (("random", 0.5), ("triangular", 0.8)):
        law = numbers["lattices"][lattice]["power_law"][0]
        assert law["p"] == pytest.approx(p, abs=3 * law["p_error"] + 1e-3)
        assert law["points"] == 4
    first = page.read_text()
    assert "## The power law" in first and "## Against Gerl and Zippelius" in first
    assert re.search(r"\| random \| [^|]+ \| 0\.02 to 0\.2 \(4\) \|", first)
    page.unlink()
    report_from_tables(tables, page, resamples=50, preset="speed")
    assert page.read_text() == first


@pytest.mark.parametrize("name", ["results", "speed", "figures", "benchmarks"])
def test_a_reading_cannot_write_over_another_page_in_docs(name, capsys):
    from runner.__main__ import main

    before = {p: p.stat().st_mtime_ns for p in (ROOT / "docs").rglob("*")}
    assert main(["study", "grazing", "--name", name, "--docs", "--samples", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"--name {name}" in err[0]
    assert {p: p.stat().st_mtime_ns for p in (ROOT / "docs").rglob("*")} == before
