"""Distances between points and polylines, and polygon membership.

``distance_to_segments`` is the dense reference: every point against every
segment, memory n_points x n_segments. ``Polyline`` gives the same numbers
(bit for bit: the same arithmetic on each point-segment pair, and the
minimum over a set of segments that holds every one that can attain it) from
the segments near each point only, found with a KD-tree, so building a body
costs memory and time in proportion to its points.
"""

from __future__ import annotations

import numpy as np
from matplotlib.path import Path
from scipy.spatial import cKDTree

# Slack on the KD-tree's search radii, relative to the radius, and absolute in
# units of the polyline's size: far above the round-off of the distances, so
# the search finds every segment whose computed distance could decide a result.
RELATIVE_SLACK = 1e-9
ABSOLUTE_SLACK = 1e-12
# Points nearer a polygon's edges than this, in median edge lengths, are
# tested by matplotlib (``inside_polygon``): farther ones have an answer
# that the round-off of any test leaves alone.
BOUNDARY_BAND = 1e-6


def distance_to_segments(points: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Distance from every point to every segment, shape (len(points), len(starts))."""
    seg = ends - starts
    rel = points[:, None, :] - starts[None, :, :]
    t = np.clip((rel * seg).sum(-1) / (seg * seg).sum(-1), 0.0, 1.0)
    foot = starts[None, :, :] + t[..., None] * seg[None, :, :]
    return np.linalg.norm(points[:, None, :] - foot, axis=-1)


def paired_distances(points: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Distance from ``points[k]`` to the segment ``starts[k]``-``ends[k]``, for each k.

    The arithmetic of ``distance_to_segments``, operation for operation, so
    each pair's distance is the same double as that matrix's entry.
    """
    seg = ends - starts
    rel = points - starts
    t = np.clip((rel * seg).sum(-1) / (seg * seg).sum(-1), 0.0, 1.0)
    foot = starts + t[:, None] * seg
    return np.linalg.norm(points - foot, axis=-1)


class Polyline:
    """A polyline's segments, indexed for distance queries near them.

    Each segment is represented by points along it no further apart than
    ``step`` (the median segment length), in a KD-tree: a segment within d of
    a point has one of its points within d + step / 2 of it, so a ball query
    finds every segment that can be the nearest.

    Parameters
    ----------
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline, in order.
    closed : bool
        Whether a segment joins the last vertex to the first (a polygon).
    """

    def __init__(self, vertices: np.ndarray, closed: bool = False) -> None:
        vertices = np.asarray(vertices, dtype=float)
        self.starts = vertices if closed else vertices[:-1]
        self.ends = np.roll(vertices, -1, axis=0) if closed else vertices[1:]
        lengths = np.linalg.norm(self.ends - self.starts, axis=1)
        step = float(np.median(lengths))
        if not step > 0.0:
            step = float(lengths.max()) or 1.0
        self.step = step
        pieces = np.maximum(np.ceil(lengths / step), 1.0).astype(int)
        self.owner = np.repeat(np.arange(len(lengths)), pieces + 1)
        first = np.concatenate([[0], np.cumsum(pieces + 1)[:-1]])
        fraction = (np.arange(len(self.owner)) - first[self.owner]) / pieces[self.owner]
        seg = self.ends - self.starts
        samples = self.starts[self.owner] + fraction[:, None] * seg[self.owner]
        self.tree = cKDTree(samples)
        # the farthest a point of a segment can be from its nearest sample
        self.reach = 0.5 * float((lengths / pieces).max())
        self.scale = float(np.abs(vertices).max()) + float(lengths.max())

    def _radius(self, distance: np.ndarray) -> np.ndarray:
        return (distance + self.reach) * (1.0 + RELATIVE_SLACK) + ABSOLUTE_SLACK * self.scale

    def _pairs(self, points: np.ndarray, radius) -> tuple[np.ndarray, np.ndarray]:
        """(point, segment) index pairs: each segment with a sample within
        ``radius`` (a number, or one per point) of the point, once, grouped by
        point in increasing order."""
        if np.ndim(radius) == 0:  # one radius: a tree of the points finds all pairs at once
            found = cKDTree(points).sparse_distance_matrix(
                self.tree, float(radius), output_type="ndarray"
            )
            point, sample = found["i"].astype(np.int64), found["j"].astype(np.int64)
        else:
            lists = self.tree.query_ball_point(points, radius)
            counts = np.fromiter(map(len, lists), dtype=np.int64, count=len(lists))
            sample = np.fromiter((s for f in lists for s in f), np.int64, count=counts.sum())
            point = np.repeat(np.arange(len(points)), counts)
        key = np.unique(point * len(self.starts) + self.owner[sample])
        return key // len(self.starts), key % len(self.starts)

    def _distances(self, points: np.ndarray, point: np.ndarray, segment: np.ndarray):
        return paired_distances(points[point], self.starts[segment], self.ends[segment])

    def distance(self, points: np.ndarray) -> np.ndarray:
        """(n,) distance from each of the (n, 2) ``points`` to the nearest
        segment: ``distance_to_segments(...).min(axis=1)``, bit for bit."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(points) == 0:
            return np.zeros(0)
        # The nearest sample lies on a segment (to round-off): it bounds the answer.
        bound = self.tree.query(points)[0]
        point, segment = self._pairs(points, self._radius(bound))
        distances = self._distances(points, point, segment)
        starts = np.flatnonzero(np.r_[True, point[1:] != point[:-1]])
        return np.minimum.reduceat(distances, starts)

    def closer_than(self, points: np.ndarray, distance: float) -> np.ndarray:
        """(n,) True where a point's distance to the polyline is below
        ``distance``: ``distance(points) < distance``, without the far segments."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        close = np.zeros(len(points), bool)
        if len(points) == 0:
            return close
        point, segment = self._pairs(points, self._radius(np.float64(distance)))
        hit = self._distances(points, point, segment) < distance
        close[point[hit]] = True
        return close


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
        (n,) distances to the closest segment or vertex; the dense
        ``distance_to_segments``'s minima, bit for bit (``Polyline``).
    """
    return Polyline(vertices, closed).distance(points)


def inside_polygon(points: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """True for the points strictly inside a simple polygon (vertices in order).

    matplotlib's ``Path.contains_points``'s answers, from a test of each point
    against the few edges below or above it only: a point more than
    ``BOUNDARY_BAND`` spacings from every edge, whose answer no round-off can
    change, counts the edges that a vertical ray from it crosses; the points
    closer than that are matplotlib's.

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
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    polygon = np.asarray(polygon, dtype=float)
    outline = Polyline(polygon, closed=True)
    near = outline.closer_than(points, BOUNDARY_BAND * outline.step)
    inside = np.zeros(len(points), bool)
    if near.any():
        inside[near] = Path(polygon).contains_points(points[near])
    far = ~near
    inside[far] = ray_crossings(points[far], outline.starts, outline.ends) % 2 == 1
    return inside


def ray_crossings(points: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """How many of the segments the ray from each point straight up (+y) crosses.

    A segment counts if one end is left of the point (x <= the point's) and
    the other right (x >), and it passes above the point: a vertex on the ray
    is counted once, a vertical segment never. The segments are binned by
    their span in x, so each point meets only those of its bin.
    """
    if len(points) == 0 or len(starts) == 0:
        return np.zeros(len(points), np.int64)
    left = np.minimum(starts[:, 0], ends[:, 0])
    right = np.maximum(starts[:, 0], ends[:, 0])
    origin = float(left.min())
    width = float(np.median(right - left)) or float((right - left).max()) or 1.0
    # floor((x - origin) / width) rises with x, so a segment whose span holds
    # a point's x is in that point's bin
    first = np.floor((left - origin) / width).astype(np.int64)
    last = np.floor((right - origin) / width).astype(np.int64)
    spans = last - first + 1
    segment = np.repeat(np.arange(len(starts)), spans)
    offset = np.arange(len(segment)) - np.repeat(np.cumsum(spans) - spans, spans)
    segment_bin = np.repeat(first, spans) + offset
    order = np.argsort(segment_bin, kind="stable")
    segment, segment_bin = segment[order], segment_bin[order]
    point_bin = np.floor((points[:, 0] - origin) / width).astype(np.int64)
    low = np.searchsorted(segment_bin, point_bin, side="left")
    high = np.searchsorted(segment_bin, point_bin, side="right")
    per_point = high - low
    point = np.repeat(np.arange(len(points)), per_point)
    index = np.arange(len(point)) - np.repeat(np.cumsum(per_point) - per_point, per_point)
    segment = segment[np.repeat(low, per_point) + index]
    x = points[point, 0]
    spanned = (starts[segment, 0] > x) != (ends[segment, 0] > x)
    point, segment = point[spanned], segment[spanned]
    p, s, e = points[point], starts[segment], ends[segment]
    # the point is below the segment (the ray crosses it) when it is on its
    # right going left to right, or on its left going right to left
    dx = e[:, 0] - s[:, 0]
    turn = dx * (p[:, 1] - s[:, 1]) - (e[:, 1] - s[:, 1]) * (p[:, 0] - s[:, 0])
    below = (turn < 0) == (dx > 0)
    return np.bincount(point[below], minlength=len(points))
