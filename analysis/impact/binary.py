"""Coefficients of restitution of two free disks (a binary scene, builder/binary.py).

The disk A hits the second disk B. Two deformable, rough disks have no one
normal: the line of their centres turns during the contact. e and beta are
measured at three normals n (B to A), each with its own tangent t = n x z
(t = +x for n = +y, as on the wall) and its own incidence cot gamma:

- ``apse``: the line of centres when the centres come closest (the apse of
  their relative orbit; there the normal relative velocity of the centres
  vanishes, and a smooth elastic pair whose orbit is symmetric about it
  gives e = 1 and beta = -1). The headline ``e`` and ``beta`` are these.
- ``first_touch``: the line of centres at the first contact, the moment the
  rings, moving rigidly, first come within the contact's stand-off of each
  other (builder/binary.py aims the disk so that the line of centres makes
  the nominal angle with the relative velocity there; scene.json's
  ``aim.first_touch_time``), read from the rows; without that time, where
  the contact energy begins (the first row with it, taken midway from the
  row before: the centres move uniformly until then).
- ``impulse``: the normal of the impulse. The impulse J on A from B is the
  change of A's total momentum (the springs are internal to each disk, and
  nothing else acts, so no pair-style tally is needed); its direction is
  tilted from the contact's normal by the friction. The spins' change gives
  the tangential part: with each contact point R from its centre along the
  normal, dL_A = dL_B = R J.t, so the normal is J's direction turned by
  asin(dL / (R |J|)), dL the mean of both disks' spin changes. Without
  friction it is J's own direction (``impulse_tilt_deg`` is the angle
  between the two).

The relative velocity of the contact points, A's at x_A - R n and B's at
x_B + R n, is

    v_c = (v_A - v_B) + R (w_A + w_B) t

and e = -v_c' . n / v_c . n, beta = -v_c' . t / v_c . t, with the velocities
before the contact (') and after it, the spins w = L / I0 (I0 at rest,
as on the wall: analysis.impact.restitution).
"""

from __future__ import annotations

import numpy as np

from .restitution import Rebound, contact_window

# The three normals of a binary impact, in the order the pages give them.
NORMALS = ("apse", "first_touch", "impulse")


def apse(series: np.ndarray) -> tuple[float, np.ndarray]:
    """Time and unit normal (B's centre to A's) where the centres came closest
    during the contact, the rows' minimum refined by a parabola through it and
    its neighbours.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat (``analysis.impact.series.read_series``).

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


def first_touch(series: np.ndarray, at: float | None = None) -> tuple[float, np.ndarray]:
    """Time and unit normal (B's centre to A's) at the first contact: the line
    of centres at time ``at`` (the builder's first contact), interpolated
    between the rows around it; without ``at``, where the contact energy
    began: midway between the last row without it and the first with it (the
    centres move uniformly before the contact, so their line there is the
    mean of the two rows'), or the first row if the contact acts from it.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat.
    at : float, optional
        The time of the first contact, R/c.

    Returns
    -------
    time : float
        R/c.
    normal : numpy.ndarray
        (2,) unit vector.
    """
    if at is not None:
        r = np.array(
            [
                np.interp(at, series["time"], series["x"] - series["tx"]),
                np.interp(at, series["time"], series["y"] - series["ty"]),
            ]
        )
        return float(at), r / np.linalg.norm(r)
    touching = np.flatnonzero(series["pe_contact"] > 0.0)
    if not touching.size:
        raise ValueError("the disks never came within the contact cutoff")
    k = int(touching[0])
    rows = [k - 1, k] if k > 0 else [k]
    r = np.array(
        [
            np.mean(series["x"][rows] - series["tx"][rows]),
            np.mean(series["y"][rows] - series["ty"][rows]),
        ]
    )
    return float(np.mean(series["time"][rows])), r / np.linalg.norm(r)


def impulse(series: np.ndarray, masses: tuple[float, float]) -> np.ndarray:
    """The impulse on A from B over the run: the change of A's momentum."""
    first, last = series[0], series[-1]
    return masses[0] * np.array([last["vx"] - first["vx"], last["vy"] - first["vy"]])


def impulse_normal(
    series: np.ndarray, masses: tuple[float, float], radius: float
) -> tuple[np.ndarray, float]:
    """The impulse's normal: J's direction turned back by its tangential part,
    which the spins' change gives (module docstring).

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat.
    masses : (float, float)
        The disks' masses (A, B).
    radius : float
        R.

    Returns
    -------
    normal : numpy.ndarray
        (2,) unit vector, B to A.
    tilt_deg : float
        The angle from that normal to J's own direction (towards +x for a
        normal along +y): the friction's, atan(J.t / J.n).
    """
    first, last = series[0], series[-1]
    j = impulse(series, masses)
    spin_change = 0.5 * ((last["Lz"] - first["Lz"]) + (last["tLz"] - first["tLz"]))
    if not np.isfinite(masses[1]):  # a held target: the hold takes its share
        spin_change = last["Lz"] - first["Lz"]
    turn = float(np.arcsin(np.clip(spin_change / (radius * np.linalg.norm(j)), -1.0, 1.0)))
    angle = float(np.arctan2(j[1], j[0])) + turn
    return np.array([np.cos(angle), np.sin(angle)]), float(np.degrees(turn))


def contact_velocity(row, normal: np.ndarray, radius: float, inertia: tuple[float, float]):
    """v_c of one row: the relative velocity of the two contact points."""
    tangent = np.array([normal[1], -normal[0]])
    spin = row["Lz"] / inertia[0] + row["tLz"] / inertia[1]
    relative = np.array([row["vx"] - row["tvx"], row["vy"] - row["tvy"]])
    return relative + radius * spin * tangent, tangent


def restitution_at(
    series: np.ndarray, normal: np.ndarray, radius: float = 1.0
) -> tuple[float, float | None, float | None]:
    """e, beta and cot gamma of a binary impact at a given normal.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat.
    normal : numpy.ndarray
        (2,) unit vector, B to A.
    radius : float
        R.

    Returns
    -------
    e, beta, cot_gamma : float
        beta and cot gamma None where the contact points do not slide in.
    """
    first, last = series[0], series[-1]
    inertia = (first["Izz"], first["tIzz"])
    v_in, tangent = contact_velocity(first, normal, radius, inertia)
    v_out, _ = contact_velocity(last, normal, radius, inertia)
    normal_in, tangential_in = float(v_in @ normal), float(v_in @ tangent)
    # head-on: no tangential slip to restore (beta undefined, as on the wall)
    tangential = abs(tangential_in) > 1e-9 * abs(normal_in)
    return (
        float(-(v_out @ normal) / normal_in),
        float(-(v_out @ tangent) / tangential_in) if tangential else None,
        float(abs(normal_in) / tangential_in) if tangential else None,
    )


def from_plus_y(normal: np.ndarray) -> float:
    """A normal's angle from +y, towards +x, in degrees."""
    return float(np.degrees(np.arctan2(normal[0], normal[1])))


def binary_normals(
    series: np.ndarray,
    masses: tuple[float, float],
    radius: float = 1.0,
    touch_time: float | None = None,
) -> dict:
    """e, beta, cot gamma and the normal's angle at each of the three normals.

    Parameters
    ----------
    series : numpy.recarray
        A binary run's series.dat.
    masses : (float, float)
        The disks' masses (A, B).
    radius : float
        R.
    touch_time : float, optional
        The first contact's time (``first_touch``).

    Returns
    -------
    dict
        ``e_<normal>``, ``beta_<normal>``, ``cot_gamma_<normal>`` and
        ``normal_angle_deg_<normal>`` (from +y, towards +x) for each of
        ``NORMALS``, and ``impulse_tilt_deg``.
    """
    normal_impulse, tilt = impulse_normal(series, masses, radius)
    normals = {
        "apse": apse(series)[1],
        "first_touch": first_touch(series, touch_time)[1],
        "impulse": normal_impulse,
    }
    out: dict = {}
    for name, normal in normals.items():
        e, beta, cot_gamma = restitution_at(series, normal, radius)
        out[f"e_{name}"], out[f"beta_{name}"], out[f"cot_gamma_{name}"] = e, beta, cot_gamma
        out[f"normal_angle_deg_{name}"] = from_plus_y(normal)
    out["impulse_tilt_deg"] = tilt
    return out


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
    at, normal = apse(series)
    e, beta, cot_gamma = restitution_at(series, normal, radius)
    rebound = Rebound(
        e=e,
        beta=beta,
        cot_gamma=cot_gamma,
        omega=float(last["Lz"] / first["Izz"]),
        vx_in=float(first["vx"] - first["tvx"]),
        vy_in=float(first["vy"] - first["tvy"]),
        vx_out=float(last["vx"] - last["tvx"]),
        vy_out=float(last["vy"] - last["tvy"]),
    )
    where = {
        "apse_time": at,
        "apse_normal": normal.tolist(),
        "apse_angle_deg": from_plus_y(normal),
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
    # A held target (infinite mass) keeps no momentum: the changes are then
    # what the hold took, the disk's own change, not a conservation check.
    m_b = m_b if np.isfinite(m_b) else 0.0

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
    m_b = m_b if np.isfinite(m_b) else 0.0  # a held target does not move
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
