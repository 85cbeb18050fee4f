"""The point-to-polyline contact of docs/model.md section 2, vectorised with numpy."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


class InsideWall(RuntimeError):
    """A point is inside the body below the polyline."""


@dataclass
class ContactForces:
    energy: float
    on_points: np.ndarray  # (n_points, 2)
    on_vertices: np.ndarray  # (n_vertices, 2)


def closest_features(points: np.ndarray, vertices: np.ndarray):
    """For each point: index k of the closest segment (vertices k, k+1), its
    parameter t in [0, 1], and the vector from the closest point to the point.

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points.
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline, in order.

    Returns
    -------
    k : numpy.ndarray
        (n,) index of each point's closest segment.
    t : numpy.ndarray
        (n,) the closest point's parameter on it, w_k + t (w_k+1 - w_k).
    away : numpy.ndarray
        (n, 2) from the closest point to the point.
    """
    starts, ends = vertices[:-1], vertices[1:]
    seg = ends - starts
    rel = points[:, None, :] - starts[None, :, :]
    t = np.clip(np.einsum("psd,sd->ps", rel, seg) / np.einsum("sd,sd->s", seg, seg), 0.0, 1.0)
    away = rel - t[..., None] * seg[None, :, :]
    k = np.argmin(np.einsum("psd,psd->ps", away, away), axis=1)
    rows = np.arange(len(points))
    return k, t[rows, k], away[rows, k]


def inside(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """True for points below the polyline: an odd number of crossings of the
    vertical ray upwards from the point (the polyline may fold).

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points.
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline, in order.

    Returns
    -------
    numpy.ndarray
        (n,) booleans.
    """
    xa, xb = vertices[:-1, 0], vertices[1:, 0]
    ya, yb = vertices[:-1, 1], vertices[1:, 1]
    px, py = points[:, 0:1], points[:, 1:2]
    straddles = (xa <= px) != (xb <= px)
    with np.errstate(divide="ignore", invalid="ignore"):
        y_cross = ya + (px - xa) * (yb - ya) / (xb - xa)
    return (np.count_nonzero(straddles & (y_cross > py), axis=1) % 2) == 1


def polyline_contact(
    points: np.ndarray,
    vertices: np.ndarray,
    a: float,
    v0: float,
    cutoff: float,
    rule: str = "lever",
) -> ContactForces:
    """Energy and forces of points repelled by the polyline through ``vertices``.

    E = v0 exp(-a l) for each point within ``cutoff`` of the polyline, l the
    distance to its closest feature. ``rule`` "lever" shares the reaction by the
    lever rule; "gradient" differentiates E by the chain rule
    through the closest point (the two agree: envelope theorem).

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points (the disk's surface).
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline (the wall's surface), in order.
    a : float
        Decay rate of the repulsion, 1 / length.
    v0 : float
        Energy scale.
    cutoff : float
        Range of the contact.
    rule : str
        ``lever`` or ``gradient``.

    Returns
    -------
    ContactForces
        The energy and the forces on the points and on the vertices.

    Raises
    ------
    InsideWall
        If a point within the cutoff is inside the body below the polyline.
    """
    k, t, away = closest_features(points, vertices)
    dist = np.linalg.norm(away, axis=1)
    near = dist < cutoff
    bad = near & ((dist == 0.0) | inside(points, vertices))
    if bad.any():
        raise InsideWall(
            f"{np.count_nonzero(bad)} point(s) inside the wall, first: point {np.argmax(bad)}"
        )
    on_points = np.zeros_like(points)
    on_vertices = np.zeros_like(vertices)
    if not near.any():
        return ContactForces(0.0, on_points, on_vertices)

    k, t, away, dist = k[near], t[near], away[near], dist[near]
    energy = v0 * np.exp(-a * dist)
    unit = away / dist[:, None]
    if rule == "lever":
        force = (a * energy)[:, None] * unit
        share_start, share_end = (1.0 - t)[:, None], t[:, None]
        np.add.at(on_vertices, k, -share_start * force)
        np.add.at(on_vertices, k + 1, -share_end * force)
    elif rule == "gradient":
        force, grad_start, grad_end = _gradient_forces(points[near], vertices, k, t, a, energy)
        np.add.at(on_vertices, k, grad_start)
        np.add.at(on_vertices, k + 1, grad_end)
    else:
        raise ValueError(f"rule must be lever or gradient, got {rule!r}")
    on_points[near] = force
    return ContactForces(float(energy.sum()), on_points, on_vertices)


def _gradient_forces(points, vertices, k, t, a, energy):
    """-dE/dx for the point and both ends, E = v0 exp(-a l(p, w1, w2)).

    At a vertex l = |p - v|. Inside a segment l = |cross(s, u)| / |s| with
    u = p - w1 and s = w2 - w1, differentiated with respect to u and s.
    """
    w1, w2 = vertices[k], vertices[k + 1]
    s = w2 - w1
    u = points - w1
    length = np.linalg.norm(s, axis=1)
    signed = (s[:, 0] * u[:, 1] - s[:, 1] * u[:, 0]) / length
    sign = np.where(signed < 0.0, -1.0, 1.0)
    dl_du = sign[:, None] * np.stack([-s[:, 1], s[:, 0]], axis=1) / length[:, None]
    dl_ds = sign[:, None] * (
        np.stack([u[:, 1], -u[:, 0]], axis=1) / length[:, None] - (signed / length**2)[:, None] * s
    )
    scale = (a * energy)[:, None]
    on_point, on_start, on_end = scale * dl_du, -scale * (dl_du + dl_ds), scale * dl_ds

    vertex = (t <= 0.0) | (t >= 1.0)
    if vertex.any():
        corner = np.where(t[vertex] <= 0.0, 0, 1)[:, None]
        v = np.where(corner == 0, w1[vertex], w2[vertex])
        d = points[vertex] - v
        f = scale[vertex] * d / np.linalg.norm(d, axis=1)[:, None]
        on_point[vertex] = f
        on_start[vertex] = np.where(corner == 0, -f, 0.0)
        on_end[vertex] = np.where(corner == 1, -f, 0.0)
    return on_point, on_start, on_end


def ring_contact(
    points: np.ndarray, ring: np.ndarray, a: float, v0: float, cutoff: float, rule: str = "lever"
) -> ContactForces:
    """Energy and forces of points repelled by a closed ring around a body.

    The ring is the polyline through ``ring`` and back to its first vertex;
    its body is the polygon inside, and a point inside it within the cutoff
    raises InsideWall (every edge's crossing of a vertical ray counts here,
    where LAMMPS, which sees only nearby edges, casts its ray along the ring's
    outward direction).

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points (the other body's surface).
    ring : numpy.ndarray
        (m, 2) the ring's vertices, in order around it.
    a, v0, cutoff, rule
        As for ``polyline_contact``.

    Returns
    -------
    ContactForces
        The energy, the forces on the points and on the ring's vertices.
    """
    closed = polyline_contact(points, np.concatenate([ring, ring[:1]]), a, v0, cutoff, rule)
    on_ring = closed.on_vertices[:-1].copy()
    on_ring[0] += closed.on_vertices[-1]
    return ContactForces(closed.energy, closed.on_points, on_ring)


def two_ring_contact(
    ring_a: np.ndarray, ring_b: np.ndarray, a: float, v0: float, cutoff: float, rule: str = "lever"
) -> ContactForces:
    """Two rough bodies in contact: each ring's vertices repelled by the other
    ring, both directions at the same V0 (docs/model.md, "Two disks").

    Returns
    -------
    ContactForces
        The energy of both directions, the forces on ``ring_a`` (as
        ``on_points``) and on ``ring_b`` (as ``on_vertices``).
    """
    a_on_b = ring_contact(ring_a, ring_b, a, v0, cutoff, rule)
    b_on_a = ring_contact(ring_b, ring_a, a, v0, cutoff, rule)
    return ContactForces(
        a_on_b.energy + b_on_a.energy,
        a_on_b.on_points + b_on_a.on_vertices,
        a_on_b.on_vertices + b_on_a.on_points,
    )
