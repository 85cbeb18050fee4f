"""Spring networks: Delaunay triangulation of one body, trimmed to its outline."""

from __future__ import annotations

import numpy as np
from scipy.spatial import Delaunay

from .errors import BuildError
from .geometry import inside_polygon


def unique_edges(triangles: np.ndarray) -> np.ndarray:
    """The distinct edges of a set of triangles, as sorted index pairs."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    return np.unique(np.sort(edges, axis=1), axis=0)


def triangulate_body(points: np.ndarray, outline: np.ndarray, max_length: float) -> np.ndarray:
    """Springs of a body: the edges of its Delaunay triangulation inside its outline.

    ``outline`` holds the indices of the boundary points in order around the
    body. Delaunay triangulates the convex hull, so a rough or non-convex body
    gets triangles across the dips of its outline; those lie outside the
    outline polygon and are dropped. Triangles with an edge longer than
    ``max_length`` are dropped as well (MODEL.md section 2).
    """
    triangles = Delaunay(points).simplices
    centroids = points[triangles].mean(axis=1)
    keep = inside_polygon(centroids, points[outline])
    corners = points[triangles]
    longest = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=-1).max(axis=1)
    keep &= longest <= max_length
    springs = unique_edges(triangles[keep])

    # The kept triangles tile the body exactly only if every outline edge is one
    # of theirs; otherwise a spring crosses the surface.
    boundary = np.sort(np.stack([outline, np.roll(outline, -1)], axis=1), axis=1)
    present = {tuple(e) for e in springs.tolist()}
    missing = [tuple(e) for e in boundary.tolist() if tuple(e) not in present]
    if missing:
        raise BuildError(
            f"{len(missing)} surface segment(s) are not Delaunay edges (first: points {missing[0]}); "
            "the roughness is too large for the spacing"
        )
    unbonded = np.setdiff1d(np.arange(len(points)), springs)
    if unbonded.size:
        raise BuildError(f"{unbonded.size} point(s) have no spring (first: point {unbonded[0]})")
    return springs
