"""pair_style polyline/exp against an independent Python implementation."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

from reference.contact import polyline_contact
from tests.contact_case import CUTOFF, V0, A, lammps_forces, random_case
from tests.helpers import ROOT

pytestmark = pytest.mark.lammps


def relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


@pytest.mark.parametrize("rule", ["lever", "gradient"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_forces_equal_the_python_implementation(tmp_path, rule, seed):
    vertices, points = random_case(seed)
    energy, on_vertices, on_points = lammps_forces(tmp_path, vertices, points, rule)
    expected = polyline_contact(points, vertices, A, V0, CUTOFF, rule)
    assert np.count_nonzero(np.any(expected.on_points, axis=1)) > 10  # many points in contact
    assert relative(on_points, expected.on_points) < 1e-10
    assert relative(on_vertices, expected.on_vertices) < 1e-10
    assert energy == pytest.approx(expected.energy, rel=1e-12)


def test_gradient_rule_is_the_derivative_of_the_energy(tmp_path):
    vertices, points = random_case(4, n_points=20)
    _, on_vertices, on_points = lammps_forces(tmp_path, vertices, points, "gradient")
    forces = np.concatenate([on_vertices, on_points])
    xy = np.concatenate([vertices, points])
    h = 1e-7
    for atom in np.argsort(-np.abs(forces).sum(axis=1))[:6]:  # the most loaded atoms
        for d in range(2):
            shifted = []
            for sign in (1, -1):
                moved = xy.copy()
                moved[atom, d] += sign * h
                shifted.append(
                    lammps_forces(
                        tmp_path, moved[: len(vertices)], moved[len(vertices) :], "gradient"
                    )[0]
                )
            derivative = (shifted[0] - shifted[1]) / (2 * h)
            assert -derivative == pytest.approx(
                forces[atom, d], rel=1e-6, abs=1e-6 * np.abs(forces).max()
            )


def test_lever_rule_equals_the_gradient(tmp_path):
    """Envelope theorem: the lever rule is already the full gradient."""
    vertices, points = random_case(5)
    lever = lammps_forces(tmp_path, vertices, points, "lever")
    gradient = lammps_forces(tmp_path, vertices, points, "gradient")
    assert relative(lever[1], gradient[1]) < 1e-12
    assert relative(lever[2], gradient[2]) < 1e-12


def test_no_net_force_or_torque(tmp_path):
    vertices, points = random_case(6)
    _, on_vertices, on_points = lammps_forces(tmp_path, vertices, points)
    xy = np.concatenate([vertices, points])
    f = np.concatenate([on_vertices, on_points])
    scale = np.abs(f).sum()
    assert np.abs(f.sum(axis=0)).max() < 1e-13 * scale
    torque = np.sum(xy[:, 0] * f[:, 1] - xy[:, 1] * f[:, 0])
    assert abs(torque) < 1e-13 * scale * np.abs(xy).max()


# A polyline with a flat part, a peak (convex vertex), a valley (concave
# vertex) and a steep segment, and points placed on its special spots.
SPECIAL = np.array(
    [[-0.2, 0.0], [-0.1, 0.0], [0.0, 0.02], [0.05, -0.03], [0.08, 0.05], [0.15, 0.05], [0.25, 0.05]]
)


def special_forces(tmp_path, points):
    return lammps_forces(tmp_path, SPECIAL, np.asarray(points, float))[2]


@pytest.mark.parametrize(
    "name, point, direction",
    [
        ("over a peak vertex", [0.0, 0.04], [1.0, 0.0]),
        ("over a segment's end", [-0.1, 0.02], [1.0, 0.0]),
        # below the extended line of the flat top segment, closest to the steep one
        ("over a steep segment", [0.06, 0.01], [1.0, 0.0]),
    ],
)
def test_forces_are_finite_and_continuous(tmp_path, name, point, direction):
    eps = 1e-7
    p = np.array(point)
    d = np.array(direction)
    f = special_forces(tmp_path, [p - eps * d, p, p + eps * d])
    expected = polyline_contact(np.array([p]), SPECIAL, A, V0, CUTOFF).on_points[0]
    assert np.all(np.isfinite(f)) and np.linalg.norm(f[1]) > 0
    assert f[1] == pytest.approx(expected, rel=1e-10)
    # a Lipschitz bound: |df| <= |d2E/dx2| eps, with |d2E/dx2| <= a |F| (1 + 1/(a l))
    bound = A * np.linalg.norm(f[1]) * 10 * eps
    assert np.linalg.norm(f[0] - f[1]) < bound and np.linalg.norm(f[2] - f[1]) < bound


def test_valley_vertex_has_a_finite_force_of_continuous_size(tmp_path):
    """Over a concave vertex two segments are equally close: the direction of
    the force jumps there (the distance has a kink) but not its size."""
    valley = SPECIAL[3]
    bisector = np.array([0.0, 1.0])
    p = valley + 0.01 * bisector
    f = special_forces(tmp_path, [p - [1e-7, 0], p + [1e-7, 0]])
    assert np.all(np.isfinite(f))
    assert np.linalg.norm(f[0]) == pytest.approx(np.linalg.norm(f[1]), rel=1e-4)


def test_force_at_the_cutoff(tmp_path):
    """Just inside the cutoff the force is a V0 exp(-a rc), 7.5e-5 here; outside, 0."""
    eps = 1e-9
    f = special_forces(tmp_path, [[-0.15, CUTOFF - eps], [-0.19, CUTOFF + eps]])
    assert f[0] == pytest.approx([0.0, A * V0 * np.exp(-A * CUTOFF)], rel=1e-6, abs=1e-12)
    assert np.all(f[1] == 0.0)


def test_a_point_inside_the_wall_stops_the_run(tmp_path):
    points = np.array([[-0.15, 0.01], [-0.12, -0.005]])  # the second is inside
    with pytest.raises(RuntimeError, match=r"atom \d+ is inside the wall at step 0"):
        lammps_forces(tmp_path, SPECIAL, points)


@pytest.mark.mpi
def test_one_and_two_ranks_give_the_same_forces(tmp_path):
    """The domain is cut at x = 0, through the contact region."""
    vertices, points = random_case(7)
    one = lammps_forces(tmp_path, vertices, points, nprocs=1)
    two = lammps_forces(tmp_path, vertices, points, nprocs=2)
    assert np.any(points[:, 0] < 0) and np.any(points[:, 0] > 0)
    assert relative(two[1], one[1]) < 1e-12 and relative(two[2], one[2]) < 1e-12
    assert two[0] == pytest.approx(one[0], rel=1e-12)


@pytest.mark.parametrize(
    "keywords, message",
    [
        ("reach", "Illegal pair_style polyline/exp reach command: missing argument(s)"),
        ("reach 0.25 rule", "Illegal pair_style polyline/exp rule command: missing argument(s)"),
        ("bogus 1", "Pair polyline/exp: unknown keyword bogus"),
    ],
)
def test_pair_style_arguments_are_checked(tmp_path, keywords, message):
    """A keyword without its value is reported as such (LAMMPS's wording for
    missing arguments), not as an unknown keyword."""
    deck = tmp_path / "in.args"
    deck.write_text(
        "units lj\ndimension 2\natom_style bond\n"
        "region box block 0 1 0 1 -0.5 0.5\ncreate_box 3 box\n"
        "include decks/polyline_exp.lmp\n"
        f"pair_style polyline/exp {A} {V0} {CUTOFF} 1 2 {keywords}\n"
    )
    proc = subprocess.run(
        ["lmp", "-in", str(deck), "-log", "none", "-nocite"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode != 0
    assert f"ERROR: {message}" in proc.stdout
