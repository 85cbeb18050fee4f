"""Coefficients of restitution of two free disks (a binary scene, builder/binary.py).

The disk A hits the second disk B. The normal n is the line of centres,
B to A, when the centres come closest (the apse of their relative orbit:
there the normal relative velocity of the centres vanishes, and a smooth
elastic pair, whose orbit is symmetric about it, gives e = 1 and beta = -1).
The tangent is t = n x z, so that t = +x for n = +y as on the wall. The
relative velocity of the contact points, A's at x_A - R n and B's at
x_B + R n, is

    v_c = (v_A - v_B) + R (w_A + w_B) t

and e = -v_c' . n / v_c . n, beta = -v_c' . t / v_c . t, with the velocities
before the contact (') and after it, the spins w = L / I0 (I0 at rest,
as on the wall: analysis.restitution).
"""

from __future__ import annotations

import numpy as np

from .restitution import Rebound, contact_window


def apse(series: np.ndarray) -> tuple[float, np.ndarray]:
    """Time and unit normal (B's centre to A's) where the centres came closest
    during the contact, the rows' minimum refined by a parabola through it and
    its neighbours.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat (``analysis.series.read_series``).

    Returns
    -------
    time : float
        R/c.
    normal : numpy.ndarray
        (2,) unit vector.
    """
    start, end = contact_window(series)
    during = np.flatnonzero((series["time"] >= start) & (series["time"] <= end))
    rx, ry = series["x"] - series["tx"], series["y"] - series["ty"]
    distance = np.hypot(rx, ry)
    k = int(during[np.argmin(distance[during])])
    k = min(max(k, 1), len(series) - 2)
    times = series["time"][k - 1 : k + 2]
    # a parabola through three rows; its vertex, within them
    curve = np.polyfit(times - times[1], distance[k - 1 : k + 2], 2)
    offset = -curve[1] / (2 * curve[0]) if curve[0] > 0 else 0.0
    offset = float(np.clip(offset, times[0] - times[1], times[2] - times[1]))
    at = times[1] + offset
    r = np.array(
        [
            np.polyval(np.polyfit(times - times[1], rx[k - 1 : k + 2], 2), offset),
            np.polyval(np.polyfit(times - times[1], ry[k - 1 : k + 2], 2), offset),
        ]
    )
    return float(at), r / np.linalg.norm(r)


def contact_velocity(row, normal: np.ndarray, radius: float, inertia: tuple[float, float]):
    """v_c of one row: the relative velocity of the two contact points."""
    tangent = np.array([normal[1], -normal[0]])
    spin = row["Lz"] / inertia[0] + row["tLz"] / inertia[1]
    relative = np.array([row["vx"] - row["tvx"], row["vy"] - row["tvy"]])
    return relative + radius * spin * tangent, tangent


def binary_rebound(series: np.ndarray, radius: float = 1.0) -> tuple[Rebound, dict]:
    """e, beta and cot gamma of a binary impact, and where the normal was.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat.
    radius : float
        The disks' radius R.

    Returns
    -------
    Rebound
        e, beta and cot gamma at the apse's normal (``vx_in``... are the
        relative velocity of the centres, omega the disk's spin after).
    dict
        ``apse_time``, ``apse_normal`` and ``apse_angle_deg``, the normal's
        angle from +y (towards +x).
    """
    first, last = series[0], series[-1]
    inertia = (first["Izz"], first["tIzz"])
    at, normal = apse(series)
    v_in, tangent = contact_velocity(first, normal, radius, inertia)
    v_out, _ = contact_velocity(last, normal, radius, inertia)
    normal_in, tangential_in = float(v_in @ normal), float(v_in @ tangent)
    # head-on: no tangential slip to restore (beta undefined, as on the wall)
    tangential = abs(tangential_in) > 1e-9 * abs(normal_in)
    rebound = Rebound(
        e=float(-(v_out @ normal) / normal_in),
        beta=float(-(v_out @ tangent) / tangential_in) if tangential else None,
        cot_gamma=float(abs(normal_in) / tangential_in) if tangential else None,
        omega=float(last["Lz"] / inertia[0]),
        vx_in=float(first["vx"] - first["tvx"]),
        vy_in=float(first["vy"] - first["tvy"]),
        vx_out=float(last["vx"] - last["tvx"]),
        vy_out=float(last["vy"] - last["tvy"]),
    )
    where = {
        "apse_time": at,
        "apse_normal": normal.tolist(),
        "apse_angle_deg": float(np.degrees(np.arctan2(normal[0], normal[1]))),
    }
    return rebound, where


def momentum_change(series: np.ndarray, masses: tuple[float, float], radius: float) -> dict:
    """Relative change of the total linear and angular momentum over the run.

    The total linear momentum is zero at the start (the centre of mass is at
    rest), so both changes are relative to the bodies' own momenta: the sum
    of M |v| of both disks at the start, and that times R.

    Returns
    -------
    dict
        ``momentum_change`` (|P_end - P_start| / sum M |v|) and
        ``angular_momentum_change`` (|L_end - L_start| / (R sum M |v|)), L
        about the origin: each disk's orbital r x M v plus its own spin Lz.
    """
    m_a, m_b = masses

    def totals(row):
        momentum = np.array(
            [m_a * row["vx"] + m_b * row["tvx"], m_a * row["vy"] + m_b * row["tvy"]]
        )
        angular = (
            m_a * (row["x"] * row["vy"] - row["y"] * row["vx"])
            + m_b * (row["tx"] * row["tvy"] - row["ty"] * row["tvx"])
            + row["Lz"]
            + row["tLz"]
        )
        return momentum, angular

    first, last = series[0], series[-1]
    p0, l0 = totals(first)
    p1, l1 = totals(last)
    scale = m_a * np.hypot(first["vx"], first["vy"]) + m_b * np.hypot(first["tvx"], first["tvy"])
    return {
        "momentum_change": float(np.linalg.norm(p1 - p0) / scale),
        "angular_momentum_change": float(abs(l1 - l0) / (scale * radius)),
    }


def binary_energy_split(
    series: np.ndarray, energies: np.ndarray, masses: tuple[float, float]
) -> dict:
    """Where the kinetic energy of the approach went, as fractions of it.

    Each disk's vibration: its kinetic and spring energy less its rigid-body
    kinetic energy (translation, and rotation L^2 / 2 I0).

    Returns
    -------
    dict
        ``vibration_disk``, ``vibration_target`` and ``energy_drift`` (change
        of the total energy), each a fraction of the initial kinetic energy.
    """
    start, end = energies[0], energies[-1]
    first, last = series[0], series[-1]
    m_a, m_b = masses
    e_in = start["ke_disk"] + start["ke_target"]
    rigid_a = 0.5 * m_a * (last["vx"] ** 2 + last["vy"] ** 2) + 0.5 * last["Lz"] ** 2 / first["Izz"]
    rigid_b = (
        0.5 * m_b * (last["tvx"] ** 2 + last["tvy"] ** 2) + 0.5 * last["tLz"] ** 2 / first["tIzz"]
    )
    names = ("ke_disk", "pe_disk", "ke_target", "pe_target", "pe_contact")
    total_in = sum(start[name] for name in names)
    total_out = sum(end[name] for name in names)
    return {
        "vibration_disk": float((end["ke_disk"] + end["pe_disk"] - rigid_a) / e_in),
        "vibration_target": float((end["ke_target"] + end["pe_target"] - rigid_b) / e_in),
        "energy_drift": float((total_out - total_in) / e_in),
    }
