"""The builder's local geometry against its dense references: the KD-tree
distances, the binned polygon test and the local edge search give the very
numbers (bit for bit) of the all-pairs computations they replace."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.path import Path
from scipy.spatial import Delaunay

from builder.geometry import Polyline, distance_to_polyline, distance_to_segments, inside_polygon
from builder.network import _Mesh, _side, unique_edges


def star_polygon(rng: np.random.Generator, m: int, rough: float, scale: float) -> np.ndarray:
    """A simple polygon: m vertices at sorted angles, random radii."""
    angle = np.sort(rng.random(m)) * 2.0 * np.pi
    radius = 1.0 + rough * rng.standard_normal(m).clip(-2.5, 2.5)
    return scale * np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=1)


def wall_polygon(rng: np.random.Generator, m: int) -> np.ndarray:
    """The wall's outline: a rough top (right to left), vertical sides, a flat bottom."""
    x = np.linspace(-4.0, 4.0, m)
    top = np.stack([x, 0.03 * rng.standard_normal(m)], axis=1)[::-1]
    side = np.linspace(0.0, -2.0, 9)[1:]
    left = np.stack([np.full(8, -4.0), side], axis=1)
    right = np.stack([np.full(8, 4.0), side], axis=1)[::-1]
    bottom = np.stack([x[1:-1], np.full(m - 2, -2.0)], axis=1)
    return np.concatenate([top, left, bottom, right])


def probes(rng: np.random.Generator, polygon: np.ndarray, n: int = 1500) -> np.ndarray:
    """Points around and on a polygon: at random, its vertices, its edges'
    midpoints, and points straight above and below its vertices."""
    low, high = polygon.min(axis=0), polygon.max(axis=0)
    span = high - low
    scattered = rng.uniform(low - 0.3 * span, high + 0.3 * span, (n, 2))
    midpoints = (polygon + np.roll(polygon, -1, axis=0)) / 2.0
    pick = rng.integers(0, len(polygon), 300)
    plumb = np.stack([polygon[pick, 0], rng.uniform(low[1], high[1], 300)], axis=1)
    far = rng.uniform(-50.0, 50.0, (50, 2)) * span
    return np.concatenate([scattered, polygon, midpoints, plumb, far])


POLYGONS = [("star", seed) for seed in range(6)] + [("wall", seed) for seed in range(3)]


def polygon_case(kind: str, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    if kind == "wall":
        polygon = wall_polygon(rng, int(rng.integers(20, 400)))
    else:
        polygon = star_polygon(rng, int(rng.integers(3, 400)), 0.05 + 0.1 * seed, 10.0**seed / 100)
    return polygon, probes(rng, polygon)


@pytest.mark.parametrize("kind, seed", POLYGONS)
@pytest.mark.parametrize("closed", [True, False])
def test_kd_tree_distance_is_the_dense_minimum(kind, seed, closed):
    polygon, points = polygon_case(kind, seed)
    starts = polygon if closed else polygon[:-1]
    ends = np.roll(polygon, -1, axis=0) if closed else polygon[1:]
    dense = distance_to_segments(points, starts, ends).min(axis=1)
    assert np.array_equal(distance_to_polyline(points, polygon, closed), dense)


def test_kd_tree_distance_with_uneven_segments():
    # One long segment among short ones: each is sampled at the median length.
    rng = np.random.default_rng(7)
    vertices = np.concatenate([[[-30.0, 0.0]], np.cumsum(rng.uniform(0, 0.2, (200, 2)), axis=0)])
    points = rng.uniform(-35.0, 25.0, (3000, 2))
    dense = distance_to_segments(points, vertices[:-1], vertices[1:]).min(axis=1)
    assert np.array_equal(Polyline(vertices).distance(points), dense)


@pytest.mark.parametrize("kind, seed", POLYGONS)
def test_closer_than_is_the_dense_comparison(kind, seed):
    polygon, points = polygon_case(kind, seed)
    dense = distance_to_segments(points, polygon, np.roll(polygon, -1, axis=0)).min(axis=1)
    outline = Polyline(polygon, closed=True)
    # thresholds that some points' distances equal exactly: the test is strict
    for limit in (0.0, *np.quantile(dense, [0.1, 0.5, 0.9], method="nearest")):
        assert np.array_equal(outline.closer_than(points, limit), dense < limit)


@pytest.mark.parametrize("kind, seed", POLYGONS)
def test_polygon_test_is_matplotlibs(kind, seed):
    polygon, points = polygon_case(kind, seed)
    expected = Path(polygon).contains_points(points)
    assert expected.any() and not expected.all()
    assert np.array_equal(inside_polygon(points, polygon), expected)


def test_unique_edges_are_numpys_rows():
    triangles = Delaunay(np.random.default_rng(2).random((500, 2))).simplices
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    expected = np.unique(np.sort(edges, axis=1), axis=0)
    found = unique_edges(triangles)
    assert found.dtype == expected.dtype
    assert np.array_equal(found, expected)


def crossing_by_scan(mesh: _Mesh, a: int, b: int) -> list[tuple[int, int]]:
    """The edges crossing a-b, from every edge of the mesh in dict order (the
    builder's search before it was made local)."""
    keys = np.array(list(mesh.edges), dtype=int)
    keys = keys[~np.isin(keys, [a, b]).any(axis=1)]
    P = mesh.points
    x, y = P[keys[:, 0]], P[keys[:, 1]]
    pa, pb = P[a], P[b]
    cross = (_side(pa, pb, x) * _side(pa, pb, y) < 0) & (_side(x, y, pa) * _side(x, y, pb) < 0)
    return [tuple(e) for e in keys[cross].tolist()]


@pytest.mark.parametrize("seed", range(4))
def test_local_crossing_search_is_the_full_scan(seed):
    rng = np.random.default_rng(seed)
    points = rng.random((400, 2))
    if seed == 3:  # a grid: collinear and cocircular points
        points = np.stack(np.meshgrid(np.arange(20.0), np.arange(20.0)), axis=-1).reshape(-1, 2)
    mesh = _Mesh(points, Delaunay(points).simplices)
    pairs = rng.integers(0, len(points), (60, 2))
    # flips move edges to the end of the dict's order, which the search keeps
    for edge in [e for e in list(mesh.edges) if rng.random() < 0.2]:
        if edge in mesh.edges and (quad := mesh.quad(edge)) and mesh.is_convex(*quad):
            mesh.flip(*quad)
    crossings = 0
    for a, b in pairs.tolist():
        if a != b:
            expected = crossing_by_scan(mesh, a, b)
            assert mesh.crossing(a, b) == expected
            crossings += len(expected)
    assert crossings > 100  # long segments across many edges
