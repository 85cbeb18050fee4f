"""Where the disk starts: its placement above the wall, on an exact grid, and
the bodies' atoms renumbered into the scene's order."""

from __future__ import annotations

import math

import numpy as np

from .geometry import Polyline


def placement_quantum(radius: float) -> float:
    """The grid of the disk's points in its own frame and of its placement: a
    power of two near radius * 2**-40 (about 1e-12 R). Points and offsets on
    one such grid, below 2**12 R, add exactly in binary, so the disk placed by
    LAMMPS (displace_atoms) is bit for bit the disk placed here, and every
    spring's length is the same double in either frame."""
    return 2.0 ** (math.floor(math.log2(radius)) - 40)


def on_grid(values: np.ndarray, quantum: float) -> np.ndarray:
    """``values`` rounded to multiples of ``quantum`` (exact: a power of two)."""
    return np.round(np.asarray(values) / quantum) * quantum


def place_disk(
    disk_surface: np.ndarray,
    wall_row: np.ndarray,
    velocity: np.ndarray,
    target_gap: float,
    contact_x: float,
) -> np.ndarray:
    """Centre of the disk such that it is ``target_gap`` from the wall's surface.

    The disk starts high enough to clear every asperity, a little upstream so
    that it first comes into range near ``contact_x``, and then moves along its
    velocity until its closest point is ``target_gap`` from the wall's
    polyline. Each step moves the disk by its current excess distance, which no
    point can overshoot (sphere tracing).
    """
    direction = velocity / np.linalg.norm(velocity)
    touch = -disk_surface[:, 1].min() + target_gap  # centre height at contact
    wall_top = wall_row[:, 1].max()
    safe = wall_top + touch + target_gap  # no point in range up here
    centre = np.array([contact_x, touch]) - direction * (safe - touch) / -direction[1]
    lowest = np.argsort(disk_surface[:, 1])[:8]
    wall = Polyline(wall_row)  # searched near each point only
    for _ in range(10000):
        points = disk_surface + centre
        # Only points that may be nearest: a point is at least its height over
        # the wall's top from the wall, and the lowest few bound the nearest
        # distance from above. The same distances, minimum and centre, for a
        # fraction of the points.
        bound = wall.distance(points[lowest]).min()
        near = points[:, 1] - wall_top <= bound
        excess = wall.distance(points[near]).min() - target_gap
        if excess < 1e-9 * target_gap:
            return centre
        centre = centre + excess * direction
    raise RuntimeError("disk placement did not converge")


def renumbered(springs: np.ndarray, order: np.ndarray, offset: int) -> np.ndarray:
    """A body's springs in the scene's atom order: atom ``order[k]`` of the
    body becomes atom ``offset + k``; each spring's ends in increasing order."""
    new_index = np.empty(len(order), int)
    new_index[order] = np.arange(len(order)) + offset
    return np.sort(new_index[springs], axis=1)
