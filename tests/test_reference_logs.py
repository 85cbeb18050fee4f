"""A fresh one-rank run of the default impact reproduces the committed
reference log, decks/log.<date>.impact.g++.1 (``make reference-logs``).

Tolerance: every thermo value within 1e-6 of its column's largest magnitude,
with the same steps. LAMMPS prints 8 significant digits, so identical runs
agree to about 5e-9 of that scale; the committed one- and two-rank logs, whose
forces are summed in different orders (as another compiler or CPU would),
agree to 1e-8 over the whole impact. 1e-6 leaves a factor of 100 for such
rounding differences, and any change of the scene, the deck or the contact
style moves these values by 1e-3 or more.
"""

from __future__ import annotations

import numpy as np

from tests.reference_logs import build_scene, committed_log, run_impact, thermo_rows

TOLERANCE = 1e-6


def assert_same_rows(ours: np.ndarray, reference: np.ndarray) -> None:
    assert ours.shape == reference.shape, "a different number of thermo rows (steps)"
    assert np.array_equal(ours[:, 0], reference[:, 0]), "different steps"
    scale = np.abs(reference).max(axis=0)
    worst = (np.abs(ours - reference).max(axis=0) / np.where(scale > 0, scale, 1.0)).max()
    assert worst <= TOLERANCE, f"thermo rows differ by {worst:.2e} of their scale"


def test_fresh_run_matches_the_reference_log(tmp_path):
    reference = thermo_rows(committed_log(1))
    scene = build_scene(tmp_path / "scene")
    fresh = thermo_rows(run_impact(scene, tmp_path / "log.lammps", nprocs=1))
    assert len(reference) > 20  # rows through the whole contact
    assert_same_rows(fresh, reference)


def test_one_and_two_rank_reference_logs_agree():
    assert_same_rows(thermo_rows(committed_log(2)), thermo_rows(committed_log(1)))
