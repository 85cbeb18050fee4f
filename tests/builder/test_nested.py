"""Nested interiors (builder/nested.py, --interior nested; experimental)."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree
from scipy.stats import qmc

from builder import bodies, nested
from builder.bodies import INTERIOR
from builder.sample import build_bodies
from builder.scene import SceneSpec


def spec(n_disk: int, interior: str = "nested", seed: int = 2) -> SceneSpec:
    return SceneSpec(
        n_disk=n_disk,
        seed=seed,
        roughness_length=0.2,
        roughness_profile="continuous",
        contact_scaling="physical",
        interior=interior,
    )


def interior_points(body: bodies.Body) -> np.ndarray:
    """The body's points cut from its Poisson sample (not its rim's rows)."""
    points = body.points[body.role == INTERIOR]
    return points[contained(points, body.candidates)]


def contained(small: np.ndarray, large: np.ndarray) -> np.ndarray:
    """For each point of ``small``, whether ``large`` holds it exactly."""
    distance, _ = cKDTree(large).query(small)
    return distance == 0.0


def test_the_800_point_interiors_are_subsets_of_the_1600_point_ones():
    """Every interior point of the 800-point disk and of its 1,600-point wall
    is a point of the nested 1,600-point disk and 3,200-point wall; drawn
    anew, almost none is."""
    disk, wall = build_bodies(spec(800))
    fine_disk, fine_wall = build_bodies(spec(1600))
    for coarse, fine in ((disk, fine_disk), (wall, fine_wall)):
        assert len(interior_points(coarse)) > 0.8 * len(coarse.points)
        assert contained(interior_points(coarse), fine.points).all()
    drawn_disk, _ = build_bodies(spec(1600, "drawn"))
    assert contained(interior_points(disk), drawn_disk.points).mean() < 0.05


def test_the_base_level_is_the_drawn_one():
    """At 800 points (the chain's base) nested and drawn are the same bodies."""
    for a, b in zip(build_bodies(spec(800)), build_bodies(spec(800, "drawn"))):
        np.testing.assert_array_equal(a.points, b.points)
        np.testing.assert_array_equal(a.springs, b.springs)


def plain_and_grown(n: int, seed: int) -> tuple[np.ndarray, np.ndarray, float]:
    """A plain Poisson sample of an n-point disk's density in the square
    [-1, 1]^2, one grown from a sample of half that density, and the radius."""
    box = ([-1.0, -1.0], [1.0, 1.0])
    spacing = bodies.triangular_spacing(n / np.pi)
    plain = bodies.poisson_points(np.random.default_rng([seed, 1]), spacing, *box)
    coarse = bodies.poisson_points(np.random.default_rng([seed, 2]), spacing * np.sqrt(2), *box)
    grown = bodies.poisson_points(np.random.default_rng([seed, 3]), spacing, *box, coarse)
    assert contained(coarse, grown).all()
    density = 2.0 / (np.sqrt(3.0) * spacing**2)
    return plain, grown, float(np.sqrt(bodies.POISSON_FILL / density))


def test_a_grown_sample_has_the_plain_samples_density_and_spacing():
    """Grown from the coarser level, a sample keeps the minimum distance and
    has a plain sample's number density and nearest-neighbour distances
    within 3 % (in the inner square, away from the box's edges); dropping
    the fine points that come too close to the coarse ones would leave 0.41
    points per radius squared against 0.60."""
    for seed in (1, 2):
        plain, grown, radius = plain_and_grown(1600, seed)
        measured = {}
        for name, points in (("plain", plain), ("grown", grown)):
            inner = points[np.all(np.abs(points) < 0.8, axis=1)]
            distance, _ = cKDTree(points).query(inner, k=2)
            assert distance[:, 1].min() >= radius * (1 - 1e-6)
            measured[name] = (len(inner), distance[:, 1].mean())
        assert abs(measured["grown"][0] / measured["plain"][0] - 1.0) < 0.03
        assert abs(measured["grown"][1] / measured["plain"][1] - 1.0) < 0.03


def test_coarse_points_closer_than_the_radius_are_refused():
    sampler = qmc.PoissonDisk(d=2, radius=0.1, rng=np.random.default_rng(1))
    points = np.array([[0.5, 0.5], [0.51, 0.5]])
    try:
        nested.grow(sampler, points)
    except ValueError:
        return
    raise AssertionError("two coarse points in one grid cell were accepted")


def test_levels():
    assert nested.coarser_level(799, 800) is None
    assert nested.coarser_level(1599, 800) is None
    assert nested.coarser_level(1600, 800) == 800
    assert nested.coarser_level(25_600, 800) == 12_800
