"""Distances between points and polylines, and polygon membership."""

from __future__ import annotations

import numpy as np
from matplotlib.path import Path


def distance_to_segments(points: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Distance from every point to every segment, shape (len(points), len(starts))."""
    seg = ends - starts
    rel = points[:, None, :] - starts[None, :, :]
    t = np.clip((rel * seg).sum(-1) / (seg * seg).sum(-1), 0.0, 1.0)
    foot = starts[None, :, :] + t[..., None] * seg[None, :, :]
    return np.linalg.norm(points[:, None, :] - foot, axis=-1)


def distance_to_polyline(
    points: np.ndarray, vertices: np.ndarray, closed: bool = False
) -> np.ndarray:
    """Distance from each point to the nearest feature of a polyline.

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points.
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline, in order.
    closed : bool
        Whether a segment joins the last vertex to the first (a polygon).

    Returns
    -------
    numpy.ndarray
        (n,) distances to the closest segment or vertex.
    """
    ends = np.roll(vertices, -1, axis=0) if closed else vertices[1:]
    starts = vertices if closed else vertices[:-1]
    return distance_to_segments(points, starts, ends).min(axis=1)


def inside_polygon(points: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """True for the points strictly inside a simple polygon (vertices in order).

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points.
    polygon : numpy.ndarray
        (m, 2) vertices of a simple polygon, in order.

    Returns
    -------
    numpy.ndarray
        (n,) booleans.
    """
    return Path(polygon).contains_points(points)
