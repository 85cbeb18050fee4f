"""The step of mu on the sliding branch between two levels that share their
seeds (analysis/branch/steps.py): the levels' own mu, and a step
whose error pairs the seeds."""

from __future__ import annotations

import csv

import pytest

from analysis.branch.steps import main, steps
from analysis.theory.tangential import walton_beta
from tests.synthetic import impact_rows, write_tables


def level(folder, mu: float, seeds: int = 16):
    """Walton's rows (kink at cot gamma 0.43: the four most grazing angles
    slide), each seed's beta shifted alike at every angle and at every level
    (the same surface), as a level's committed tables."""
    rows = impact_rows(
        "random",
        lambda psi: walton_beta(psi, 0.8, mu, -0.3, 3.0),
        seeds=seeds,
        offset_sd=0.02,
        noise_sd=0.005,
        inertia_ratio=0.5,
        rng_seed=7,
    )
    return write_tables(folder, rows, ["random"])


def test_the_step_pairs_the_seeds(tmp_path):
    coarse, fine = level(tmp_path / "coarse", 0.30), level(tmp_path / "fine", 0.28)
    first, second = steps([coarse, fine], resamples=400)
    assert first["mu"] == pytest.approx(0.30, abs=0.005)
    assert second["step"] == pytest.approx(-0.02, abs=0.002)
    # the seeds' shifts cancel in the step: far below either level's error
    assert second["step_sd"] < 0.2 * min(first["sd"], second["sd"])


def test_levels_of_other_seeds_are_refused(tmp_path, capsys):
    coarse, fine = level(tmp_path / "coarse", 0.30), level(tmp_path / "fine", 0.28, seeds=12)
    with pytest.raises(ValueError, match="same seeds"):
        steps([coarse, fine], resamples=10)
    assert main([str(coarse)]) == 0
    assert capsys.readouterr().out.startswith("coarse: mu on the branch 0.29")


def test_fixed_angles_give_the_same_step_at_every_level(tmp_path, capsys):
    """--angles: the mean mu_eff over the same angles at both levels (here
    the branch's two most grazing), and an angle a level lacks is one line."""
    coarse, fine = level(tmp_path / "coarse", 0.30), level(tmp_path / "fine", 0.28)
    gammas = sorted(
        {float(r["gamma_deg"]) for r in csv.DictReader((coarse / "impacts.csv").open())}
    )
    first, second = steps([coarse, fine], resamples=200, angles=gammas[-2:])
    assert first["mu"] == pytest.approx(0.30, abs=0.01)
    assert second["step"] == pytest.approx(-0.02, abs=0.003)
    with pytest.raises(SystemExit) as stop:
        main([str(coarse), str(fine), "--angles", "12.34"])
    assert stop.value.code == 2
    assert "does not have every angle of [12.34]" in capsys.readouterr().err
