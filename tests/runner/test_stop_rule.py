"""The predictive stop rule (runner/stop_rule.py) and what it changes: nothing."""

from __future__ import annotations

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from runner.impact import run_scene
from runner.options import RunOptions
from runner.stop_rule import disk_vibration, future_contact_free
from tests.helpers import SMALL

CUTOFF, MARGIN = 0.07, 0.01
ANGLES = np.linspace(0.0, 2 * np.pi, 60, endpoint=False)
RING = np.column_stack([np.cos(ANGLES), np.sin(ANGLES)])  # a disk of radius 1 at the origin
FLAT = np.column_stack([np.linspace(-4, 4, 81), np.zeros(81)])


def disk_at(height: float) -> np.ndarray:
    return RING + [0.0, height]


def test_a_disk_moving_away_is_clear_and_one_moving_in_is_not():
    centre = np.array([0.0, 1.2])
    assert future_contact_free(
        disk_at(1.2), centre, np.array([0.05, 0.1]), 0.0, FLAT, CUTOFF, MARGIN
    )
    assert not future_contact_free(
        disk_at(1.2), centre, np.array([0.05, -0.1]), 0.0, FLAT, CUTOFF, MARGIN
    )


def test_an_asperity_ahead_is_seen():
    """Rising slowly while sliding fast towards a bump: the rule must wait."""
    bump = FLAT.copy()
    bump[(bump[:, 0] > 1.4) & (bump[:, 0] < 1.6), 1] = 0.15
    centre = np.array([0.0, 1.1])
    velocity = np.array([0.5, 0.02])
    assert future_contact_free(disk_at(1.1), centre, velocity, 0.0, FLAT, CUTOFF, MARGIN)
    assert not future_contact_free(disk_at(1.1), centre, velocity, 0.0, bump, CUTOFF, MARGIN)


def test_vibration_amplitude_of_a_breathing_disk():
    """Radius 1 + a sin(w t): |u| + |du/dt| / w is a at every phase."""
    a, w = 0.02, 0.8
    for phase in (0.0, 0.7, 1.9):
        surface = RING * (1 + a * np.sin(phase))
        velocity = RING * a * w * np.cos(phase)
        amplitude = disk_vibration(
            RING, np.zeros(2), surface, velocity, np.zeros(2), np.zeros(2), w
        )
        assert amplitude == pytest.approx(a * (abs(np.sin(phase)) + abs(np.cos(phase))), rel=1e-12)
        assert amplitude >= a * 0.999


@pytest.mark.lammps
@pytest.mark.parametrize("gamma, saves", [(20.0, False), (70.0, True)])
def test_stopping_early_changes_no_result(tmp_path, gamma, saves):
    """After the predicted stop no force acts on the disk, so the run stopped
    by the conservative clearance rule, later, gives the same rebound. (At 20
    degrees this small disk rebounds straight up, and both rules stop at the
    same check; at 70 it leaves spinning and sliding, and the rule saves steps.
    On the dense wall of the first study, held at its sides only: on the
    1,600-point wall with ten times the disk's ka the disk leaves cleanly and
    both rules stop at the same check at every angle.)"""
    spec = SceneSpec(
        **{**SMALL, "n_wall": "density"}, gamma_deg=gamma, wall_ka="same-c", wall_fixed="sides"
    )
    scene = build_scene(spec)
    results = {
        rule: run_scene(write_scene(scene, tmp_path / rule), RunOptions(stop_rule=rule))
        for rule in ("predict", "clearance")
    }
    early, late = results["predict"], results["clearance"]
    assert early["steps"] < late["steps"] if saves else early["steps"] <= late["steps"]
    for key in ("e", "beta", "omega"):
        assert early[key] == pytest.approx(late[key], rel=1e-9, abs=1e-12)
