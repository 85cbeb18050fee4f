"""Friction against the rms slope (pages/friction.py): each slope's levels
chained, the slope from the profile's record, the table and the figure."""

from __future__ import annotations

import pytest

from analysis.theory.tangential import walton_beta
from ground.errors import InputError
from pages.friction import main, rms_slope
from tests.synthetic import GAMMA_DEG, impact_rows, write_tables

ANGLES = [str(g) for g in GAMMA_DEG[-3:]]


def level(folder, mu: float, n_disk: int, length: float, profile: str = "continuous"):
    rows = impact_rows(
        "random",
        lambda psi: walton_beta(psi, 0.8, mu, -0.3, 3.0),
        seeds=16,
        offset_sd=0.02,
        noise_sd=0.005,
        rng_seed=n_disk,
    )
    study = {"n_disk": n_disk, "roughness": 0.03, "roughness_length": length}
    return write_tables(folder, rows, ["random"], roughness_profile=profile, **study)


def test_each_slope_is_a_chain_of_its_levels(tmp_path, capsys):
    folders = [
        level(tmp_path / "b1600", 0.28, 1600, 0.06),
        level(tmp_path / "a", 0.20, 800, 0.1),
        level(tmp_path / "b800", 0.30, 800, 0.06),
    ]
    figure = tmp_path / "figure" / "friction.png"
    figure.parent.mkdir()
    assert main([*map(str, folders), "--angles", *ANGLES, "--figure", str(figure)]) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.startswith("| 0.")]
    # by slope, then by the disk points; slopes h / L = 0.03 / 0.1 and 0.03 / 0.06
    assert [r.split(" | ")[:2] for r in rows] == [
        ["| 0.3", "800"],
        ["| 0.5", "800"],
        ["| 0.5", "1,600"],
    ]
    # mu on the branch is the synthetic rows' mu (Walton's sliding branch)
    assert [float(r.split(" | ")[2].split(" +- ")[0]) for r in rows] == pytest.approx(
        [0.20, 0.30, 0.28], abs=0.01
    )
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_sampled_profile_has_no_slope_h_over_l(tmp_path):
    folder = level(tmp_path / "s", 0.2, 800, 0.1, profile="sampled")
    with pytest.raises(InputError, match="not a continuous profile"):
        rms_slope(folder)
