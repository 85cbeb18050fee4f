"""--area-floor (builder/triangles.py): the barrier's angles on the bodies'
triangles, nothing else changed; J_c 0 is the scene as before; bad values
refused; and the calibration's moduli unchanged with the barrier."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.lammps_data import data_file_text, settings_text
from builder.scene import DISK, SceneSpec
from builder.strips import StripSpec
from builder.triangles import AREA_STEP, signed_areas
from calibration.stretch import run_stretch
from ground.errors import InputError
from tests.helpers import ROOT

ROUGH = {"roughness_length": 0.2, "roughness_profile": "continuous", "contact_scaling": "physical"}


@pytest.fixture(scope="module")
def scenes():
    return {floor: build_scene(SceneSpec(area_floor=floor, **ROUGH)) for floor in (0.0, 0.5)}


def test_zero_is_no_barrier_and_the_barrier_adds_only_angles(scenes):
    plain, barrier = scenes[0.0], scenes[0.5]
    assert plain.angles is None and "area_barrier" not in plain.info
    text = data_file_text(plain)
    assert "ngle" not in text and "angles" not in settings_text(plain)
    # the barrier's file is the plain one with the angles' counts and sections added
    lines = data_file_text(barrier).split("\nAngle Coeffs")[0].splitlines(keepends=True)
    counts = [line for line in lines if line.endswith((" angles\n", " angle types\n"))]
    assert len(counts) == 2
    assert "".join(line for line in lines if line not in counts) == text
    assert "variable angles      index area/barrier" in settings_text(barrier)


def test_every_angle_is_a_counter_clockwise_triangle_of_springs(scenes):
    scene = scenes[0.5]
    angles = scene.angles
    springs = {tuple(sorted(s)) for s in scene.springs.tolist()}
    for a, b, c in angles.atoms.tolist():
        assert {tuple(sorted(e)) for e in ((a, b), (b, c), (c, a))} <= springs
    areas = signed_areas(scene.positions, angles.atoms)
    assert np.all(areas > 0.0)
    # A0 of each angle's type is its area at rest within half the grid's step
    a0, k, jc = angles.coefficients[angles.types - 1].T
    assert np.abs(np.log(areas / a0)).max() <= AREA_STEP / 2 * (1 + 1e-9)
    assert np.all(jc == 0.5)
    # one body per triangle; k its 2-D bulk modulus B ka
    in_disk = scene.molecule[angles.atoms] == DISK
    assert np.all(in_disk.all(axis=1) | ~in_disk.any(axis=1))
    info = scene.info["area_barrier"]
    assert np.all(k[in_disk[:, 0]] == info["k_disk"])
    assert np.all(k[~in_disk[:, 0]] == info["k_wall"])
    assert info["k_disk"] == scene.info["disk_material"]["B"] * scene.info["ka_disk"]
    # a triangulated disk of n points with s on its outline has 2n - s - 2 triangles
    n, s = int((scene.molecule == DISK).sum()), int((scene.types == 1).sum())
    assert info["disk_angles"] == 2 * n - s - 2
    # far fewer types than angles once the disk is fine enough to share them
    assert len(angles.coefficients) < len(angles.atoms)


@pytest.mark.parametrize("value", [-0.1, 0.95, float("nan")])
def test_bad_values_are_refused_in_one_line(value):
    with pytest.raises(InputError, match=r"area_floor must be a number in \[0, 0.9\]"):
        SceneSpec(area_floor=value).validate()
    proc = subprocess.run(
        [sys.executable, "-m", "builder", "scene", "--area-floor", str(value), "--out", "/tmp/x"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2 and proc.stdout == ""
    error = proc.stderr.strip().splitlines()[-1]  # argparse's usage, then one line
    assert "--area-floor" in error and "[0, 0.9]" in error


@pytest.mark.lammps
@pytest.mark.slow
def test_the_calibration_moduli_are_unchanged_by_the_barrier(tmp_path):
    """decks/stretch.lmp on a random strip, with and without the barrier at
    its highest J_c: the same settled states to the last bit, hence the same
    E and nu (the strip's strains of 1e-3 keep every triangle far above J_c)."""
    spec = StripSpec("random", seed=101, length=40.0, width=16.0)
    plain = run_stretch(spec, tmp_path / "plain")
    barrier = run_stretch(spec, tmp_path / "barrier", area_floor=0.9)
    assert "Angles" in (tmp_path / "barrier" / "strip.data").read_text()
    assert np.array_equal(plain.virial_xx, barrier.virial_xx)
    assert np.array_equal(plain.strain_yy, barrier.strain_yy)
    assert plain.e_modulus == barrier.e_modulus and plain.nu == barrier.nu
