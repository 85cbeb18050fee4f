"""The virial of pair style polyline/exp (potentials/README.md: "tallies
energy and virial, global and per atom").

For forces that sum to zero, the virial is the sum over the atoms of r f, in
any origin; the style tallies it contact by contact instead (ev_tally for a
vertex, ev_tally3 for a segment's interior), and the two must agree, globally
(compute pressure) and summed per atom (compute stress/atom), on one rank and
with the contact region cut between two.

Tolerance: 1e-12 of the largest component. The two sides are the same sums
of products of the same forces and separations in a different order and
origin, so they differ by rounding only: some 1e-16 per term over about a
hundred contacts, times the ratio of the coordinates (about 1.5) to the
separations (about 0.05). A wrong sign, share or missing term shows at 1e-2
or more.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.contact_case import lammps_virial, random_case

pytestmark = pytest.mark.lammps

TOLERANCE = 1e-12


def r_dot_f(
    vertices: np.ndarray, points: np.ndarray, on_vertices: np.ndarray, on_points: np.ndarray
) -> np.ndarray:
    """xx, yy, xy of the sum over the atoms of r_a f_b."""
    r = np.concatenate([vertices, points])
    f = np.concatenate([on_vertices, on_points])
    return np.array([r[:, 0] @ f[:, 0], r[:, 1] @ f[:, 1], r[:, 0] @ f[:, 1]])


@pytest.mark.parametrize(
    "rule, nprocs", [("lever", 1), ("gradient", 1), pytest.param("lever", 2, marks=pytest.mark.mpi)]
)
def test_virial_is_the_sum_of_r_dot_f(tmp_path, rule, nprocs):
    vertices, points = random_case(8)
    on_vertices, on_points, global_virial, per_atom_sum = lammps_virial(
        tmp_path, vertices, points, rule, nprocs
    )
    assert np.count_nonzero(np.any(on_points, axis=1)) > 10  # many contacts
    if nprocs == 2:  # the cut is at x = 0
        assert np.any(points[:, 0] < 0) and np.any(points[:, 0] > 0)
    expected = r_dot_f(vertices, points, on_vertices, on_points)
    scale = np.abs(expected).max()
    assert scale > 0
    assert np.abs(global_virial - expected).max() <= TOLERANCE * scale
    assert np.abs(per_atom_sum - expected).max() <= TOLERANCE * scale


@pytest.mark.parametrize("nprocs", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_two_rings_virial_is_the_sum_of_r_dot_f(tmp_path, nprocs):
    """Two disks' rings (closed yes partner): both directions tallied."""
    from tests.potentials.test_ring_contact import ring_keywords, two_rings

    ring_a, ring_b = two_rings(2)
    extra = ring_keywords(len(ring_b), len(ring_a))
    on_b, on_a, global_virial, per_atom_sum = lammps_virial(
        tmp_path, ring_b, ring_a, "lever", nprocs, extra=extra
    )
    expected = r_dot_f(ring_b, ring_a, on_b, on_a)
    scale = np.abs(expected).max()
    assert scale > 0 and np.any(on_a) and np.any(on_b)
    assert np.abs(global_virial - expected).max() <= TOLERANCE * scale
    assert np.abs(per_atom_sum - expected).max() <= TOLERANCE * scale
