"""Spring networks: Delaunay triangulation of one body, trimmed to its outline.

When the roughness makes a surface segment a non-Delaunay edge (a steep step
between two neighbouring surface points, whose empty circle would have to
reach past a neighbour), the triangulation is made to keep it: the segments
are inserted into scipy's Delaunay triangulation by edge flips, and the flips
that follow restore the Delaunay property everywhere the surface allows. The
result is the constrained Delaunay triangulation of the body (docs/model.md,
"Steep surface segments"). A body that the plain Delaunay triangulation
builds is untouched, so it keeps its springs byte for byte.
"""

from __future__ import annotations

from collections import deque

import numpy as np
from scipy.spatial import Delaunay

from ground.errors import BuildError

from .geometry import inside_polygon

# Two triangles are flipped to the other diagonal only if the opposite point is
# inside the circumcircle by more than this, relative to the fourth power of
# the quad's size: cocircular points (a square lattice's cells) have either
# diagonal, and round-off must not flip them back and forth.
INCIRCLE_TOLERANCE = 1e-10


def unique_edges(triangles: np.ndarray) -> np.ndarray:
    """The distinct edges of a set of triangles, as sorted index pairs in
    lexicographic order (``np.unique(..., axis=0)``'s, in the triangles' dtype)."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    edges = np.sort(edges, axis=1)
    # One integer per pair sorts as the pairs do, and a 1-D unique is far
    # quicker than np.unique over rows.
    size = int(edges.max()) + 1 if len(edges) else 1
    key = np.unique(edges[:, 0].astype(np.int64) * size + edges[:, 1])
    return np.stack([key // size, key % size], axis=1).astype(triangles.dtype, copy=False)


def edge_keys(edges: np.ndarray, size: int) -> np.ndarray:
    """One integer per sorted index pair (points fewer than ``size``)."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    return edges[:, 0] * size + edges[:, 1]


def outline_edges(outline: np.ndarray) -> np.ndarray:
    """The segments of a closed outline, as sorted index pairs in outline order."""
    return np.sort(np.stack([outline, np.roll(outline, -1)], axis=1), axis=1)


def triangulate_body(
    points: np.ndarray, outline: np.ndarray, max_length: float
) -> tuple[np.ndarray, np.ndarray]:
    """Springs of a body, the edges of its triangulation inside its outline.

    ``outline`` holds the indices of the boundary points in order around the
    body, a simple polygon that holds every other point. Delaunay triangulates
    the convex hull, so a rough or non-convex body gets triangles across the
    dips of its outline; those lie outside the outline polygon and are
    dropped, and so are triangles with an edge longer than ``max_length``
    (docs/model.md section 2).

    If that leaves an outline segment without its triangle (a steep step of
    the roughness) or a point without a spring, the body is triangulated
    exactly instead: the missing segments that are not Delaunay edges are
    flipped in (``constrain``), and every triangle inside the outline is kept.
    Returns the springs (sorted index pairs) and those missing segments
    (shape (k, 2); k = 0 for almost every body, which is then built as before).
    """
    triangles = Delaunay(points).simplices
    boundary = outline_edges(outline)
    corners = points[triangles]
    longest = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=-1).max(axis=1)
    inside = inside_polygon(corners.mean(axis=1), points[outline])
    springs = unique_edges(triangles[inside & (longest <= max_length)])
    missing = _missing(springs, boundary)
    if not missing and _all_bonded(springs, len(points)):
        return springs, np.zeros((0, 2), dtype=springs.dtype)

    # The exact triangulation. With every outline segment an edge, each
    # triangle lies wholly inside or wholly outside the body, so the centroid
    # test alone trims it, and no length prune is needed: the long triangles
    # left are the roughness's own steps.
    delaunay = edge_keys(unique_edges(triangles), len(points))
    known = np.isin(edge_keys(missing, len(points)), delaunay)
    steep = [e for e, is_edge in zip(missing, known.tolist()) if not is_edge]
    if steep:
        triangles = constrain(points, triangles, steep, [tuple(e) for e in boundary.tolist()])
    inside = inside_polygon(points[triangles].mean(axis=1), points[outline])
    springs = unique_edges(triangles[inside])
    still = _missing(springs, boundary)
    if still:  # not expected: the outline is a simple polygon
        raise BuildError(
            f"{len(still)} surface segment(s) have no triangle inside the body "
            f"(first: points {still[0]})"
        )
    if not _all_bonded(springs, len(points)):
        unbonded = np.setdiff1d(np.arange(len(points)), springs)
        raise BuildError(f"{unbonded.size} point(s) have no spring (first: point {unbonded[0]})")
    return springs, np.array(missing, dtype=springs.dtype).reshape(-1, 2)


def _missing(springs: np.ndarray, boundary: np.ndarray) -> list[tuple[int, int]]:
    """The outline segments that are not springs: a spring would cross the surface there."""
    size = int(max(springs.max(initial=0), boundary.max(initial=0))) + 1
    absent = ~np.isin(edge_keys(boundary, size), edge_keys(springs, size))
    return [tuple(e) for e in boundary[absent].tolist()]


def _all_bonded(springs: np.ndarray, n_points: int) -> bool:
    return np.array_equal(np.unique(springs), np.arange(n_points))


def _side(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Twice the signed area of p, q, r (arrays of points): > 0 when they turn left."""
    return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (
        r[..., 0] - p[..., 0]
    )


def _orient(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> float:
    """Twice the signed area of the points p, q, r: > 0 when they turn counter-clockwise."""
    return float(_side(p, q, r))


class _Mesh:
    """A triangulation that can flip edges: triangles by id, and each edge's triangles."""

    def __init__(self, points: np.ndarray, triangles: np.ndarray) -> None:
        self.points = points
        self.xy = points.tolist()  # plain floats, for the bounding boxes of ``crossing``
        self.triangles: dict[int, tuple[int, int, int]] = {}
        self.edges: dict[tuple[int, int], list[int]] = {}
        # when each edge entered ``edges`` (dict order, which ``crossing`` keeps)
        self.born: dict[tuple[int, int], int] = {}
        self.around: dict[int, set[int]] = {}  # each point's triangles
        self.next_id = 0
        self.next_edge = 0
        triangles = np.asarray(triangles)
        # ``add``'s orientation test, for all at once (the same arithmetic per triangle)
        P = points
        turn = _side(P[triangles[:, 0]], P[triangles[:, 1]], P[triangles[:, 2]])
        ordered = np.where((turn < 0)[:, None], triangles[:, [0, 2, 1]], triangles)
        for a, b, c in ordered.tolist():
            self._insert(a, b, c)

    def add(self, a: int, b: int, c: int) -> None:
        if _orient(self.points[a], self.points[b], self.points[c]) < 0:
            b, c = c, b  # counter-clockwise
        self._insert(a, b, c)

    def _insert(self, a: int, b: int, c: int) -> None:
        """Add the counter-clockwise triangle a, b, c."""
        tid = self.next_id
        self.triangles[tid] = (a, b, c)
        for u, v in ((a, b), (b, c), (c, a)):
            key = (u, v) if u < v else (v, u)
            if key not in self.edges:
                self.edges[key] = []
                self.born[key] = self.next_edge
                self.next_edge += 1
            self.edges[key].append(tid)
        for point in (a, b, c):
            self.around.setdefault(point, set()).add(tid)
        self.next_id += 1

    def remove(self, tid: int) -> None:
        a, b, c = self.triangles.pop(tid)
        for edge in ((a, b), (b, c), (c, a)):
            key = tuple(sorted(edge))
            self.edges[key].remove(tid)
            if not self.edges[key]:
                del self.edges[key]
                del self.born[key]
        for point in (a, b, c):
            self.around[point].discard(tid)

    def quad(self, edge: tuple[int, int]) -> tuple[int, int, int, int] | None:
        """(u, v, p, q): the edge u-v with p on its left and q on its right; None on the hull."""
        tids = self.edges[edge]
        if len(tids) < 2:
            return None
        u, v = edge
        p, q = (sum(self.triangles[t]) - u - v for t in tids)
        if _orient(self.points[u], self.points[v], self.points[p]) < 0:
            p, q = q, p
        return u, v, p, q

    def is_convex(self, u: int, v: int, p: int, q: int) -> bool:
        """Whether the quad u-q-v-p is strictly convex, so that u-v can flip to p-q."""
        P = self.points
        return _orient(P[p], P[q], P[u]) * _orient(P[p], P[q], P[v]) < 0

    def flip(self, u: int, v: int, p: int, q: int) -> tuple[int, int]:
        for tid in list(self.edges[(u, v)]):
            self.remove(tid)
        self.add(p, q, u)
        self.add(q, p, v)
        return tuple(sorted((p, q)))

    def crossing(self, a: int, b: int) -> list[tuple[int, int]]:
        """The edges that cross the segment a-b at an inner point of both, in
        the order of ``edges``.

        Only the edges of the triangles near the segment are tested: those
        whose bounding box meets the segment's, reached from a's triangles
        across shared edges. The triangles that meet the segment are such a
        connected set, so every crossing edge is among them.
        """
        xy = self.xy
        low = (min(xy[a][0], xy[b][0]), min(xy[a][1], xy[b][1]))
        high = (max(xy[a][0], xy[b][0]), max(xy[a][1], xy[b][1]))
        seen: set[int] = set()
        stack = list(self.around[a])
        near: set[tuple[int, int]] = set()
        while stack:
            tid = stack.pop()
            if tid in seen:
                continue
            seen.add(tid)
            corners = [xy[v] for v in self.triangles[tid]]
            if (
                min(p[0] for p in corners) > high[0]
                or max(p[0] for p in corners) < low[0]
                or min(p[1] for p in corners) > high[1]
                or max(p[1] for p in corners) < low[1]
            ):
                continue
            u, v, w = self.triangles[tid]
            for edge in ((u, v), (v, w), (w, u)):
                key = edge if edge[0] < edge[1] else (edge[1], edge[0])
                near.add(key)
                stack.extend(t for t in self.edges[key] if t not in seen)
        keys = np.array(sorted(near, key=self.born.__getitem__), dtype=int).reshape(-1, 2)
        keys = keys[~np.isin(keys, [a, b]).any(axis=1)]
        P = self.points
        x, y = P[keys[:, 0]], P[keys[:, 1]]
        pa, pb = P[a], P[b]
        cross = (_side(pa, pb, x) * _side(pa, pb, y) < 0) & (_side(x, y, pa) * _side(x, y, pb) < 0)
        return [tuple(e) for e in keys[cross].tolist()]

    def crosses(self, edge: tuple[int, int], a: int, b: int) -> bool:
        if set(edge) & {a, b}:
            return False
        P = self.points
        x, y = P[edge[0]], P[edge[1]]
        return (
            _orient(P[a], P[b], x) * _orient(P[a], P[b], y) < 0
            and _orient(x, y, P[a]) * _orient(x, y, P[b]) < 0
        )

    def locally_delaunay(self, u: int, v: int, p: int, q: int) -> bool:
        """Whether q is not inside the circumcircle of u, v, p (counter-clockwise)."""
        rows = self.points[[u, v, p]] - self.points[q]
        size = float((rows * rows).sum(axis=1).max())
        matrix = np.column_stack([rows, (rows * rows).sum(axis=1)])
        return float(np.linalg.det(matrix)) <= INCIRCLE_TOLERANCE * size * size


def constrain(
    points: np.ndarray,
    triangles: np.ndarray,
    segments: list[tuple[int, int]],
    constraints: list[tuple[int, int]],
) -> np.ndarray:
    """A triangulation of ``points`` that has ``segments`` as edges, by edge flips.

    ``triangles`` is a triangulation of the points (scipy's Delaunay);
    ``segments`` (sorted index pairs) must cross no other of ``constraints``,
    and no point may lie on one. Each segment is inserted by flipping the
    edges that cross it (Sloan, Adv. Eng. Software 1993): an edge whose two
    triangles form a convex quad flips to the quad's other diagonal, one that
    does not waits until its neighbours have flipped. Lawson flips of every
    changed edge but the constraints then make the result the constrained
    Delaunay triangulation: each edge's triangles have empty circumcircles as
    seen from within the body. Only the triangles around the segments change.
    """
    mesh = _Mesh(points, triangles)
    limit = 100 * len(triangles)
    changed: list[tuple[int, int]] = []
    for a, b in segments:
        queue = deque(mesh.crossing(a, b))
        steps = 0
        while queue:
            steps += 1
            if steps > limit:
                raise BuildError(f"surface segment {(a, b)} could not be flipped into the network")
            edge = queue.popleft()
            u, v, p, q = mesh.quad(edge)
            if not mesh.is_convex(u, v, p, q):
                queue.append(edge)  # try again after its neighbours
                continue
            new = mesh.flip(u, v, p, q)
            changed += [new, *(tuple(sorted(e)) for e in ((u, p), (p, v), (v, q), (q, u)))]
            if mesh.crosses(new, a, b):
                queue.append(new)
        if (a, b) not in mesh.edges:
            raise BuildError(f"surface segment {(a, b)} could not be flipped into the network")

    fixed = set(constraints)
    pending = deque(dict.fromkeys(changed))  # unique, in a fixed order
    steps = 0
    while pending:
        steps += 1
        if steps > limit:
            raise BuildError("the flips around the steep surface segments did not settle")
        edge = pending.popleft()
        if edge in fixed or edge not in mesh.edges:
            continue
        quad = mesh.quad(edge)
        # A non-Delaunay edge's quad is convex; the test guards against round-off.
        if quad is None or mesh.locally_delaunay(*quad) or not mesh.is_convex(*quad):
            continue
        u, v, p, q = quad
        mesh.flip(u, v, p, q)
        pending.extend(tuple(sorted(e)) for e in ((u, p), (p, v), (v, q), (q, u)))
    return np.array(list(mesh.triangles.values()), dtype=triangles.dtype)
