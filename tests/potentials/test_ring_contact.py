"""pair_style polyline/exp with two closed rings (two disks in contact)
against the independent Python implementation (reference.contact)."""

from __future__ import annotations

import numpy as np
import pytest

from reference.contact import (
    InsideWall,
    closest_features,
    ring_contact,
    two_ring_contact,
)
from tests.contact_case import CUTOFF, V0, A, lammps_forces

pytestmark = pytest.mark.lammps

N_RING = 120  # vertices per ring: spacing 0.052, below the cutoff 0.0673 as in a scene


def rough_ring(rng: np.random.Generator, centre, roughness: float = 0.004) -> np.ndarray:
    """A unit circle's N_RING points, counter-clockwise, moved along the radius."""
    angle = np.arange(N_RING) * 2 * np.pi / N_RING + rng.uniform(0, 2 * np.pi / N_RING)
    radius = 1.0 + roughness * rng.standard_normal(N_RING)
    return np.asarray(centre) + radius[:, None] * np.stack([np.cos(angle), np.sin(angle)], axis=1)


def two_rings(seed: int, gap: float = 0.02, shift: float = 0.0):
    """Ring B around the origin, ring A above it, ``gap`` between the nominal
    circles: a few of each ring's points within the cutoff of the other."""
    rng = np.random.default_rng(seed)
    ring_b = rough_ring(rng, (0.0, 0.0))
    ring_a = rough_ring(rng, (shift, 2.0 + gap))
    return ring_a, ring_b


def ring_keywords(n_b: int, n_a: int) -> tuple[str, ...]:
    """Ring B is tags 1..n_b (type 3, the data file's vertices), ring A the
    next n_a tags (type 1, its points)."""
    return ("-var", "keywords", f"closed yes partner {n_b + 1} {n_b + n_a}")


def lammps_two_rings(tmp_path, ring_a, ring_b, nprocs=1, rule="lever"):
    """Energy, forces on ring A and on ring B from LAMMPS."""
    energy, on_b, on_a = lammps_forces(
        tmp_path, ring_b, ring_a, rule, nprocs, extra=ring_keywords(len(ring_b), len(ring_a))
    )
    return energy, on_a, on_b


def relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


def in_contact(ring_a, ring_b) -> int:
    """Points of either ring within the cutoff of the other ring."""
    closed_b, closed_a = np.vstack([ring_b, ring_b[:1]]), np.vstack([ring_a, ring_a[:1]])
    near_a = np.linalg.norm(closest_features(ring_a, closed_b)[2], axis=1) < CUTOFF
    near_b = np.linalg.norm(closest_features(ring_b, closed_a)[2], axis=1) < CUTOFF
    return int(near_a.sum() + near_b.sum())


@pytest.mark.parametrize("rule", ["lever", "gradient"])
@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("nprocs", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_two_rings_equal_the_python_implementation(tmp_path, seed, rule, nprocs):
    """Both directions, every vertex of both rings, to 1e-12; the domain of
    two ranks is cut at x = 0, through the contact."""
    ring_a, ring_b = two_rings(seed)
    assert in_contact(ring_a, ring_b) >= 6
    energy, on_a, on_b = lammps_two_rings(tmp_path, ring_a, ring_b, nprocs, rule)
    expected = two_ring_contact(ring_a, ring_b, A, V0, CUTOFF, rule)
    assert relative(on_a, expected.on_points) < 1e-12
    assert relative(on_b, expected.on_vertices) < 1e-12
    assert energy == pytest.approx(expected.energy, rel=1e-12)


def test_both_directions_act(tmp_path):
    """The energy is that of ring A's points against ring B plus ring B's
    points against ring A, each of them non-zero: neither is left out."""
    ring_a, ring_b = two_rings(3)
    energy = lammps_two_rings(tmp_path, ring_a, ring_b)[0]
    a_on_b = ring_contact(ring_a, ring_b, A, V0, CUTOFF).energy
    b_on_a = ring_contact(ring_b, ring_a, A, V0, CUTOFF).energy
    assert a_on_b > 0 and b_on_a > 0
    assert energy == pytest.approx(a_on_b + b_on_a, rel=1e-12)


def test_the_ring_closes_where_its_tags_wrap(tmp_path):
    """Turn ring B so that its last and first vertices face ring A: the
    segment joining them must act as any other."""
    ring_a, ring_b = two_rings(4)
    top = int(np.argmax(ring_b[:, 1]))
    ring_b = np.roll(ring_b, -top - 1, axis=0)  # the top vertex is now the last
    assert np.argmax(ring_b[:, 1]) == N_RING - 1
    energy, on_a, on_b = lammps_two_rings(tmp_path, ring_a, ring_b)
    expected = two_ring_contact(ring_a, ring_b, A, V0, CUTOFF)
    assert np.any(on_b[0]) and np.any(on_b[-1])
    assert relative(on_b, expected.on_vertices) < 1e-12
    assert relative(on_a, expected.on_points) < 1e-12


@pytest.mark.parametrize(
    "where, angle",
    [
        ("over a segment's interior", np.pi / 2 + np.pi / N_RING),
        ("over a vertex", np.pi / 2),
    ],
)
def test_each_point_and_its_segment_balance_with_no_couple(tmp_path, where, angle):
    """The lever rule: the force on a point and the reactions on its
    segment's ends sum to zero, and so do their moments about any point
    (the force acts along the line from the foot of the perpendicular)."""
    step = 2 * np.pi / N_RING
    ring = np.stack([np.cos(np.arange(N_RING) * step), np.sin(np.arange(N_RING) * step)], axis=1)
    point = 1.02 * np.array([[np.cos(angle), np.sin(angle)]])
    _, on_ring, on_point = lammps_forces(
        tmp_path, ring, point, extra=("-var", "keywords", "closed yes")
    )
    loaded = np.count_nonzero(np.any(on_ring, axis=1))
    assert loaded == (1 if where == "over a vertex" else 2) and np.linalg.norm(on_point) > 0
    forces, xy = np.vstack([on_ring, on_point]), np.vstack([ring, point])
    scale = np.abs(forces).sum()
    assert np.abs(forces.sum(axis=0)).max() < 1e-14 * scale
    for origin in ([0.0, 0.0], [5.0, -3.0]):
        arm = xy - origin
        torque = np.sum(arm[:, 0] * forces[:, 1] - arm[:, 1] * forces[:, 0])
        assert abs(torque) < 1e-14 * scale * np.abs(arm).max()


def test_two_rings_exert_no_net_force_or_torque(tmp_path):
    ring_a, ring_b = two_rings(5, shift=0.3)
    _, on_a, on_b = lammps_two_rings(tmp_path, ring_a, ring_b)
    forces, xy = np.vstack([on_a, on_b]), np.vstack([ring_a, ring_b])
    scale = np.abs(forces).sum()
    assert np.abs(forces.sum(axis=0)).max() < 1e-13 * scale
    torque = np.sum(xy[:, 0] * forces[:, 1] - xy[:, 1] * forces[:, 0])
    assert abs(torque) < 1e-13 * scale * np.abs(xy).max()


@pytest.mark.parametrize("side", ["under a segment", "at a vertex"])
def test_a_point_inside_the_other_ring_stops_the_run(tmp_path, side):
    """LAMMPS tells inside from a ray's crossings with the nearby segments;
    the reference from every edge's crossing: both refuse ring A's lowest
    point moved just inside ring B."""
    ring_a, ring_b = two_rings(6, gap=0.03)
    top, low = int(np.argmax(ring_b[:, 1])), int(np.argmin(ring_a[:, 1]))
    spot = ring_b[top] if side == "at a vertex" else 0.5 * (ring_b[top] + ring_b[top + 1])
    ring_a[low] = spot * (1.0 - 0.005)
    with pytest.raises(InsideWall):
        two_ring_contact(ring_a, ring_b, A, V0, CUTOFF)
    with pytest.raises(RuntimeError, match=r"atom \d+ is inside the ring \d+\.\.\d+ at step 0"):
        lammps_two_rings(tmp_path, ring_a, ring_b)


@pytest.mark.parametrize(
    "keywords, message",
    [
        ("partner 130 140", "partner needs closed rings"),
        ("closed maybe", "closed must be yes or no, got maybe"),
        ("closed yes partner 100 140", "the rings 1..120 and 100..140 overlap"),
        ("closed yes partner 130", "Illegal pair_style polyline/exp partner command"),
    ],
)
def test_ring_keywords_are_checked(tmp_path, keywords, message):
    ring_a, ring_b = two_rings(1)
    with pytest.raises(RuntimeError, match=message):
        lammps_forces(tmp_path, ring_b, ring_a, extra=("-var", "keywords", keywords))


def folded_ring() -> tuple[np.ndarray, np.ndarray]:
    """A ring folded as a sliding contact folded one (seen in the binary
    study: a vertex pushed past its neighbour, two segments crossing), and a
    point outside it whose closest feature is the folded vertex."""
    step = 2 * np.pi / N_RING
    ring = np.stack([np.cos(np.arange(N_RING) * step), np.sin(np.arange(N_RING) * step)], axis=1)
    top = N_RING // 4
    ring[top - 1 : top + 3] = [[0.040, 0.995], [-0.0386, 1.0555], [0.018, 1.022], [-0.052, 1.054]]
    return ring, np.array([[0.065, 1.070]])


def test_a_folded_ring_does_not_take_a_point_outside_for_inside(tmp_path):
    ring, point = folded_ring()
    closed = np.vstack([ring, ring[:1]])
    k, t, _ = closest_features(point, closed)
    vertex = (k[0] + 1) % N_RING if t[0] >= 1.0 else k[0]
    # the closest feature's side says inside: the fold (the ring's segments cross)
    d = point[0] - ring[vertex]
    e_in, e_out = ring[vertex] - ring[vertex - 1], ring[vertex + 1] - ring[vertex]
    left = [a[0] * d[1] - a[1] * d[0] > 0 for a in (e_in, e_out)]
    convex = e_in[0] * e_out[1] - e_in[1] * e_out[0] >= 0
    assert all(left) if convex else any(left), "not the fold's case"
    expected = ring_contact(point, ring, A, V0, CUTOFF)  # every edge's crossing: outside
    energy, on_ring, on_point = lammps_forces(
        tmp_path, ring, point, extra=("-var", "keywords", "closed yes")
    )
    assert expected.energy > 0
    assert energy == pytest.approx(expected.energy, rel=1e-12)
    assert relative(on_point, expected.on_points) < 1e-12
    assert relative(on_ring, expected.on_vertices) < 1e-12


def test_a_ring_too_short_for_its_outward_direction_is_refused(tmp_path):
    """A ring's outward direction spans 4 vertices either side of one: a ring
    needs 9, else the chord folds onto itself."""
    step = 2 * np.pi / 8
    ring = np.stack([np.cos(np.arange(8) * step), np.sin(np.arange(8) * step)], axis=1)
    with pytest.raises(RuntimeError, match="need 1 <= first < last and 9 vertices to a ring"):
        lammps_forces(
            tmp_path, ring, np.array([[0.0, 1.05]]), extra=("-var", "keywords", "closed yes")
        )
