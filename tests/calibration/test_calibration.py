"""Material calibration: strips stretched by LAMMPS against the closed forms,
the table's reproducibility, and an independent pulse measurement."""

from __future__ import annotations

import json

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.materials import (
    TABLE,
    calibrated,
    square_bulk_modulus,
    square_poisson_ratio,
    square_ratio_for_poisson,
    square_shear_modulus,
    square_wave_speed_factor,
)
from builder.scene import SceneSpec
from builder.strips import StripSpec
from calibration.pulse import pulse_speed
from calibration.stretch import run_stretch
from calibration.table import RANDOM_STRIP, anisotropy, markdown, stretch_all
from ground.errors import InputError
from tests.helpers import ROOT, SMALL


@pytest.mark.lammps
@pytest.mark.parametrize("angle", [0.0, 45.0])
def test_triangular_lattice(tmp_path, angle):
    r = run_stretch(StripSpec("triangular", angle_deg=angle), tmp_path)
    assert abs(r.nu - 1.0 / 3.0) < 0.01
    assert r.e_modulus == pytest.approx(2.0 / np.sqrt(3.0), rel=0.02)
    assert r.c2 == pytest.approx(1.0, rel=0.02)  # c^2 = k d^2 / m
    # isotropic: the Lame constants are both sqrt(3)/4 k, in every direction
    assert r.shear_modulus == pytest.approx(np.sqrt(3.0) / 4.0, rel=0.01)
    assert r.bulk_modulus == pytest.approx(np.sqrt(3.0) / 2.0, rel=0.01)
    assert r.nonlinearity < 0.01  # linear response
    assert r.imbalance < 1e-6  # settled: the grips balance


@pytest.mark.lammps
@pytest.mark.parametrize("ratio", [1.0 / 9.0, 3.0 / 7.0])
@pytest.mark.parametrize("angle", [0.0, 45.0])
def test_square_lattice_against_the_formula(tmp_path, ratio, angle):
    r = run_stretch(StripSpec("square", k2_over_k1=ratio, angle_deg=angle), tmp_path)
    assert abs(r.nu - square_poisson_ratio(ratio, angle)) < 0.01
    assert r.c2 == pytest.approx(square_wave_speed_factor(ratio, angle), rel=0.01)
    assert r.nonlinearity < 0.01
    # the pull gives the shear modulus of the frame turned by 45 degrees more
    assert r.shear_modulus == pytest.approx(square_shear_modulus(ratio, angle + 45.0), rel=0.01)
    assert r.bulk_modulus == pytest.approx(square_bulk_modulus(ratio), rel=0.01)


def rotated_shear_modulus(c11: float, c12: float, c66: float, angle_deg: float) -> float:
    """1 / S'66 of the stiffness tensor turned by the angle, by tensor algebra."""
    c = np.zeros((2, 2, 2, 2))
    c[0, 0, 0, 0] = c[1, 1, 1, 1] = c11
    c[0, 0, 1, 1] = c[1, 1, 0, 0] = c12
    c[0, 1, 0, 1] = c[1, 0, 1, 0] = c[0, 1, 1, 0] = c[1, 0, 0, 1] = c66
    a = np.radians(angle_deg)
    q = np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
    turned = np.einsum("ia,jb,kc,ld,abcd->ijkl", q, q, q, q, c)
    voigt = [(0, 0), (1, 1), (0, 1)]
    matrix = np.array([[turned[w[0], w[1], v[0], v[1]] for v in voigt] for w in voigt])
    return float(1.0 / np.linalg.inv(matrix)[2, 2])


@pytest.mark.parametrize("ratio", [1.0 / 9.0, 3.0 / 7.0, 1.0])
def test_square_moduli_closed_forms(ratio):
    """G and B of the square lattice: known values, the stiffness tensor turned
    by tensor algebra, and E / (2 (1 +- nu)) from docs/model.md's nu along the mirror lines."""
    assert square_shear_modulus(ratio, 0.0) == pytest.approx(ratio, rel=1e-12)  # C66 = k2
    assert square_shear_modulus(ratio, 45.0) == pytest.approx(0.5, rel=1e-12)  # k1 / 2
    for angle in (0.0, 10.0, 22.5, 30.0, 45.0, 80.0):
        assert square_shear_modulus(ratio, angle) == pytest.approx(
            rotated_shear_modulus(1.0 + ratio, ratio, ratio, angle), rel=1e-12
        )
    for angle in (0.0, 45.0):
        e, nu = square_wave_speed_factor(ratio, angle), square_poisson_ratio(ratio, angle)
        assert square_shear_modulus(ratio, angle + 45.0) == pytest.approx(
            e / (2.0 * (1.0 + nu)), rel=1e-12
        )
        assert square_bulk_modulus(ratio) == pytest.approx(e / (2.0 * (1.0 - nu)), rel=1e-12)


def test_square_ratio_for_a_poisson_ratio():
    for nu in (0.1, 0.3):
        assert square_ratio_for_poisson(nu) == pytest.approx(nu / (1 - nu), rel=1e-12)
        assert square_ratio_for_poisson(nu, 45.0) == pytest.approx((1 - nu) / (4 * nu), rel=1e-12)
    with pytest.raises(InputError, match="nu must be between"):
        square_ratio_for_poisson(1.2)  # nu = r / (1 + r) < 1 along the axes


@pytest.mark.lammps
@pytest.mark.slow
def test_random_lattice_is_reproducible_across_seeds():
    """Four new strips against the committed table (twelve other seeds)."""
    entry = calibrated("random")
    runs = stretch_all([StripSpec("random", seed=seed, **RANDOM_STRIP) for seed in range(101, 105)])
    for name in ("c2", "nu"):
        values = np.array([getattr(r, name) for r in runs])
        assert np.all(np.abs(values - entry[name]) < 3 * entry[f"{name}_sd"])
        tolerance = 3 * np.hypot(entry[f"{name}_se"], entry[f"{name}_sd"] / np.sqrt(len(values)))
        assert abs(values.mean() - entry[name]) < tolerance


@pytest.mark.lammps
@pytest.mark.slow
def test_pulse_speed_matches_the_stretched_bar(tmp_path):
    """Dynamics against statics on the same bar (docs/calibration.md): within 1 %.
    Against the table's bulk c the thin bar is up to a few percent faster: its
    surface rows stiffen it, and samples scatter by 1.6 % (sd of c^2 / 2)."""
    speed = pulse_speed(tmp_path / "pulse", seed=1, length=300.0, width=10.0, sigma=15.0)
    bar = run_stretch(StripSpec("random", seed=1, length=300.0, width=10.0), tmp_path / "bar")
    assert speed == pytest.approx(np.sqrt(bar.c2_strip), rel=0.01)
    assert speed == pytest.approx(np.sqrt(calibrated("random")["c2"]), rel=0.04)


def test_table_sets_the_units_of_a_scene():
    scene = build_scene(SceneSpec(**SMALL))
    entry = calibrated("random")
    d = scene.info["disk_spacing"]
    assert scene.info["ka_disk"] == pytest.approx(1.0 / (entry["c2"] * d * d), rel=1e-12)
    assert scene.info["units"]["c_source"].startswith("calibrated")
    assert scene.info["disk_material"]["nu"] == entry["nu"]


def test_uncalibrated_lattice_is_refused():
    with pytest.raises(
        InputError,
        match=r"k2_over_k1 = 0.2 is not calibrated.*python -m calibration run --square 0.2",
    ):
        build_scene(SceneSpec(lattice="square", k2_over_k1=0.2, **SMALL))


def test_table_covers_the_study():
    table = json.loads(TABLE.read_text())
    assert table["command"] == "make calibrate"
    for nu in (0.1, 0.3):
        assert calibrated("square", square_ratio_for_poisson(nu))["nu"] == pytest.approx(
            nu, abs=0.01
        )
    assert calibrated("triangular")["samples"] == 1 and calibrated("random")["samples"] >= 10


def test_the_materials_page_is_the_table_s():
    """docs/calibration/materials.md shows materials.json's numbers, both tables, and every
    lattice of the study in the moduli table, the regular ones pulled at 45 degrees."""
    table = json.loads(TABLE.read_text())
    assert markdown(table) in (ROOT / "docs" / "calibration" / "materials.md").read_text()
    rows = {(r["lattice"], r["k2_over_k1"]): r for r in anisotropy(table["materials"])}
    for nu in (0.1, 0.3):
        row = rows[("square", square_ratio_for_poisson(nu))]
        assert row["measured_45"]
        assert row["G_axes"] == pytest.approx(square_ratio_for_poisson(nu), rel=0.01)
    assert rows[("triangular", None)]["measured_45"]
    random = rows[("random", None)]
    assert not random["measured_45"] and random["G_axes"] == random["G_45"]
