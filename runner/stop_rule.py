"""When an impact is over: no force acts on the disk, and none ever will.

The deck's conservative rule waits until the disk's lowest possible point
(its centre minus its reach) clears the wall's highest surface point: safe
against re-contacts by a spinning rough disk, but slow, and blind to a wall
that springs back up. This rule extrapolates instead: the disk as a rigid body
from its present motion, the wall's surface where it is, and stops once no
disk surface point comes within the cutoff plus a margin for the vibrations of
both bodies. The margin comes from the present state: for each body the
largest |displacement from rest| + |velocity| / omega over its surface points,
omega a lower bound of the body's slowest mode. bench/stop_rule.py checks it
against runs continued long after the stop.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

MAX_SAMPLES = 20000
DISK_OMEGA = 0.5  # c/R; the free disk's slowest (elliptic) mode is near 0.8
WALL_OMEGA = 0.2  # c/R; the 8 R x 2 R wall's slowest flexural mode, clamped at its sides


def vibration_amplitude(displacement: np.ndarray, velocity: np.ndarray, omega: float) -> float:
    """An upper bound of a mode's amplitude, |u| + |du/dt| / omega, over points."""
    if displacement.size == 0:
        return 0.0
    return float(np.max(np.abs(displacement) + np.abs(velocity) / omega))


def disk_vibration(
    rest: np.ndarray,
    rest_centre: np.ndarray,
    surface: np.ndarray,
    surface_velocity: np.ndarray,
    centre: np.ndarray,
    centre_velocity: np.ndarray,
    omega: float = DISK_OMEGA,
) -> float:
    """Amplitude of the disk's breathing: changes of its surface points' distances
    from its centre, and their rates."""
    relative = surface - centre
    radius = np.linalg.norm(relative, axis=1)
    rate = np.sum(relative * (surface_velocity - centre_velocity), axis=1) / radius
    rest_radius = np.linalg.norm(rest - rest_centre, axis=1)
    return vibration_amplitude(radius - rest_radius, rate, omega)


def wall_vibration(
    rest: np.ndarray, row: np.ndarray, row_velocity: np.ndarray, omega: float = WALL_OMEGA
) -> float:
    """Amplitude of the wall surface's motion along its normal (y)."""
    return vibration_amplitude(row[:, 1] - rest[:, 1], row_velocity[:, 1], omega)


def future_contact_free(
    surface: np.ndarray,
    centre: np.ndarray,
    velocity: np.ndarray,
    omega: float,
    wall_row: np.ndarray,
    cutoff: float,
    margin: float,
) -> bool:
    """True if the disk's surface points, moving rigidly, stay farther than
    ``cutoff + margin`` from the polyline ``wall_row`` for all later times.

    Parameters
    ----------
    surface : numpy.ndarray
        (n, 2) positions of the disk's surface points.
    centre : numpy.ndarray
        The disk's centre of mass.
    velocity : numpy.ndarray
        Its centre-of-mass velocity.
    omega : float
        Its angular velocity.
    wall_row : numpy.ndarray
        (m, 2) the wall's surface polyline, frozen where it is.
    cutoff : float
        The contact's cutoff.
    margin : float
        Room for the vibrations of disk and wall.

    Returns
    -------
    bool
        Whether the impact is over.
    """
    if velocity[1] <= 0.0:
        return False
    relative = surface - centre
    reach = np.linalg.norm(relative, axis=1).max()
    top = wall_row[:, 1].max()
    clear = cutoff + margin
    horizon = (top + clear + reach - centre[1]) / velocity[1]
    if horizon <= 0.0:
        return True

    # Samples of the motion and of the polyline, fine enough that the distance
    # between samples errs by at most margin / 2 in all.
    speed = np.linalg.norm(velocity) + abs(omega) * reach
    step = 0.25 * margin / speed
    samples = int(np.ceil(horizon / step)) + 1
    if samples > MAX_SAMPLES:
        return False
    spacing = 0.25 * margin
    segments = np.diff(wall_row, axis=0)
    counts = np.maximum(np.ceil(np.linalg.norm(segments, axis=1) / spacing).astype(int), 1)
    dense = np.concatenate(
        [wall_row[k] + np.outer(np.arange(n) / n, segments[k]) for k, n in enumerate(counts)]
        + [wall_row[-1:]]
    )
    tree = cKDTree(dense)

    times = np.linspace(0.0, horizon, samples)
    angle = omega * times
    cos, sin = np.cos(angle)[:, None], np.sin(angle)[:, None]
    x = centre[0] + velocity[0] * times[:, None] + cos * relative[:, 0] - sin * relative[:, 1]
    y = centre[1] + velocity[1] * times[:, None] + sin * relative[:, 0] + cos * relative[:, 1]
    low = y < top + clear
    if not low.any():
        return True
    distance, _ = tree.query(np.stack([x[low], y[low]], axis=1))
    return bool(distance.min() > clear + 0.5 * margin)
