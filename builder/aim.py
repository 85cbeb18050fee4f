"""How a binary scene's disk is aimed by the contact (builder/binary.py): the
first contact of two rough rings moving rigidly, the incidence it happens
at, the line of motion that makes it gamma, and the contact's stand-off."""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from ground.errors import InputError

from .geometry import distance_to_polyline


def gap_between(ring_a: np.ndarray, ring_b: np.ndarray) -> float:
    """Least distance of either ring's points to the other closed ring."""
    return float(
        min(
            distance_to_polyline(ring_a, ring_b, closed=True).min(),
            distance_to_polyline(ring_b, ring_a, closed=True).min(),
        )
    )


def entry(points: np.ndarray, ring: np.ndarray, direction: np.ndarray, reach: float) -> float:
    """How far ``points`` move along ``direction`` (a unit vector) before the
    first of them comes within ``reach`` of the closed polyline ``ring``: the
    first entry of each point's ray into any segment's capsule (the segment
    widened by ``reach``: its slab between the ends, or a circle at a vertex).

    Returns
    -------
    float
        The distance; inf if no point comes that close, 0 if one already is.
    """
    start, end = ring, np.roll(ring, -1, axis=0)
    along = end - start
    length = np.linalg.norm(along, axis=1)
    unit = along / length[:, None]
    side = np.column_stack([-unit[:, 1], unit[:, 0]])
    w = points[:, None, :] - start[None, :, :]  # (points, segments, 2)
    height = np.einsum("psk,sk->ps", w, side)
    approach = side @ direction  # (segments,)
    with np.errstate(divide="ignore", invalid="ignore"):
        s_slab = (np.sign(height) * reach - height) / approach[None, :]
    foot_now = np.einsum("psk,sk->ps", w, unit)
    foot = foot_now + s_slab * (unit @ direction)[None, :]
    slab = np.where(
        (np.abs(height) > reach) & (s_slab >= 0) & (foot >= 0) & (foot <= length[None, :]),
        s_slab,
        np.inf,
    )
    # the circles at the vertices (each vertex starts one segment)
    b = w @ direction
    c = np.einsum("psk,psk->ps", w, w) - reach * reach
    disc = b * b - c
    with np.errstate(invalid="ignore"):
        s_circle = -b - np.sqrt(disc)
    circle = np.where((disc >= 0) & (s_circle >= 0), s_circle, np.inf)
    inside = (c <= 0) | (
        (np.abs(height) <= reach) & (foot_now >= 0) & (foot_now <= length[None, :])
    )
    if inside.any():
        return 0.0
    return float(min(slab.min(), circle.min()))


def first_contact(
    ring_a: np.ndarray, ring_b: np.ndarray, centre: np.ndarray, direction: np.ndarray, reach: float
) -> float:
    """How far the disk (``ring_a`` about its centre, now at ``centre``) moves
    along ``direction`` before the rings first come within ``reach`` of each
    other, either ring's points against the other's segments (inf if never)."""
    return min(
        entry(ring_a + centre, ring_b, direction, reach),
        entry(ring_b, ring_a + centre, -direction, reach),
    )


def incidence(
    ring_a: np.ndarray,
    ring_b: np.ndarray,
    direction: np.ndarray,
    offset: float,
    reach: float,
    radius: float,
) -> float:
    """Angle of incidence (radians) at the first touch of the disk coming
    along ``direction`` on the line ``offset`` from the target's centre: the
    angle from the relative velocity's reverse to the line of centres there,
    positive towards the offset's side; pi / 2 if the disk passes by."""
    across = np.array([-direction[1], direction[0]])
    start = offset * across - 4.0 * radius * direction
    distance = first_contact(ring_a, ring_b, start, direction, reach)
    if not np.isfinite(distance):
        return float(np.copysign(np.pi / 2, offset))
    centre = start + distance * direction
    return float(np.arctan2(centre @ across, -(centre @ direction)))


# An aimed incidence within this of the nominal one is a line that first
# touches there (the aim's own tolerance is 5e-11 rad, and placing the disk
# on the binary grid moves it by at most 1e-5 degrees); one further away is
# the nearest line past a jump of the incidence onto another asperity.
AIM_TOLERANCE_DEG = 1e-3


def aim(
    ring_a: np.ndarray,
    ring_b: np.ndarray,
    direction: np.ndarray,
    gamma: float,
    reach: float,
    radius: float,
) -> tuple[float, float]:
    """The offset of the line of motion from the target's centre that makes
    the first touch (at ``reach``) happen at the incidence ``gamma`` (radians):
    the root of ``incidence`` - gamma, which rises with the offset.

    Returns
    -------
    tuple of float
        The offset, and the incidence there minus ``gamma`` (radians): within
        ``AIM_TOLERANCE_DEG`` where a line first touches at ``gamma``. Where
        none does (another asperity takes over first, and the incidence jumps
        across ``gamma`` or to a miss, pi / 2), the line just beside the jump
        whose incidence is nearer ``gamma``, among those on which the rings meet.
    """
    if gamma == 0.0:
        return 0.0, 0.0

    def miss(offset: float) -> float:
        return incidence(ring_a, ring_b, direction, offset, reach, radius) - gamma

    tolerance = 1e-10 * radius  # 5e-11 rad of incidence at 86 degrees
    # the contact's diameter is within 1.9 R and 2.3 R (roughness and reach
    # well below R / 10): the root is between those lines, else anywhere
    low, high = 1.9 * radius * np.sin(gamma), min(2.3 * radius * np.sin(gamma), 3.0 * radius)
    if not miss(low) < 0.0 < miss(high):
        low, high = -3.0 * radius, 3.0 * radius
    root = float(brentq(miss, low, high, xtol=tolerance))
    sides = [(b, miss(b)) for b in (root - 4.0 * tolerance, root + 4.0 * tolerance)]
    meeting = [(b, m) for b, m in sides if abs(m + gamma) < np.pi / 2 - 1e-12]
    if not meeting:
        raise RuntimeError("the aim found no line on which the disks meet")
    return min(meeting, key=lambda side: abs(side[1]))


def hits(miss: float) -> bool:
    """Whether an aim's miss (radians) is a line that first touches at the
    nominal incidence, not the nearest line past a jump."""
    return abs(np.degrees(miss)) <= AIM_TOLERANCE_DEG


def turned(direction: np.ndarray, angle: float) -> np.ndarray:
    """``direction`` turned counter-clockwise by ``angle`` (radians)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([c * direction[0] - s * direction[1], s * direction[0] + c * direction[1]])


# How many turns of the pair either way the aim tries (``aim_turned``).
MAX_TURNS = 8


def aim_turned(
    ring_a: np.ndarray,
    ring_b: np.ndarray,
    direction: np.ndarray,
    gamma: float,
    reach: float,
    radius: float,
    step: float,
) -> tuple[np.ndarray, float, float, float]:
    """The aim (``aim``) of a pair that may be turned: along ``direction`` if
    a line there first touches at ``gamma``; else along ``direction`` turned
    by step, -step, 2 step, ... (radians, up to MAX_TURNS steps either way),
    the first that has one. Turning the direction of approach with both
    bodies fixed is turning both bodies the other way under a fixed
    approach: the same sample met at another point of its surface. Where no
    turn has such a line, the turn whose nearest line misses least.

    Returns
    -------
    tuple
        The direction of approach (unit vector), the offset, the miss
        (radians, as ``aim``'s) and the turn (radians, counter-clockwise).
    """
    best = None
    for k in range(2 * MAX_TURNS + 1):
        turn = (k + 1) // 2 * step * (1 if k % 2 else -1)  # 0, step, -step, 2 step, ...
        along = turned(direction, turn) if turn else direction
        offset, miss = aim(ring_a, ring_b, along, gamma, reach, radius)
        if best is None or abs(miss) < abs(best[2]):
            best = (along, offset, miss, turn)
        if hits(miss):
            break
    return best


def stand_off(v0: float, a: float, reduced_mass: float, speed: float, cutoff: float) -> float:
    """The distance at which one point's contact energy V0 exp(-a l) equals
    the normal kinetic energy of the approach, (1/2) mu v_n^2, within (0, cutoff].

    Parameters
    ----------
    v0 : float
        The contact's V0.
    a : float
        Its decay rate, 1/length.
    reduced_mass : float
        M_A M_B / (M_A + M_B).
    speed : float
        The relative normal speed v_n.
    cutoff : float
        The contact's cutoff.
    """
    energy = 0.5 * reduced_mass * speed * speed
    return float(np.clip(np.log(v0 / energy) / a, 1e-9 * cutoff, cutoff))


def place_projectile(
    ring_a: np.ndarray,
    ring_b: np.ndarray,
    direction: np.ndarray,
    offset: float,
    radius: float,
    gap: float,
) -> np.ndarray:
    """Centre of the disk (ring ``ring_a`` about its centre) at ``gap`` from
    the target (``ring_b`` about the origin), on the line along ``direction``
    at ``offset`` from the target's centre."""
    across = np.array([-direction[1], direction[0]])
    start = offset * across - 4.0 * radius * direction
    distance = first_contact(ring_a, ring_b, start, direction, gap)
    if not np.isfinite(distance) or distance == 0.0:
        raise InputError("the disks do not meet on the aimed line: the roughness exceeds R / 2")
    return start + distance * direction
