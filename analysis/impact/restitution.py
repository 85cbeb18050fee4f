"""Coefficients of restitution from the disk's motion before and after impact.

Conventions of docs/model.md section 5: wall normal +y, tangent +x, incoming
tangential velocity positive; the contact point is the bottom of the disk, so
its tangential velocity is V_x + R omega_z.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np


@dataclass
class Rebound:
    e: float  # -V'_y / V_y
    beta: float | None  # -(V'_x + R w') / (V_x + R w); None for a head-on impact
    cot_gamma: float | None  # |V_y| / (V_x + R w) before
    omega: float  # angular velocity after, L' / I0
    vx_in: float
    vy_in: float
    vx_out: float
    vy_out: float

    def as_dict(self) -> dict:
        return asdict(self)


def rebound(
    v_in: np.ndarray,
    v_out: np.ndarray,
    omega_in: float,
    omega_out: float,
    radius: float = 1.0,
    tangential: bool | None = None,
) -> Rebound:
    """e, beta and cot(gamma) from centre-of-mass velocities and angular velocities.

    Parameters
    ----------
    v_in, v_out : numpy.ndarray
        The disk's centre-of-mass velocity (x, y) before and after the impact.
    omega_in, omega_out : float
        Its angular velocity before and after.
    radius : float
        The disk's radius R.
    tangential : bool, optional
        Whether the impact is oblique; by default it is taken as oblique unless
        the incoming slip is round-off (head-on: beta undefined).

    Returns
    -------
    Rebound
        e, beta (None if head-on), cot gamma, the spin after, and the velocities.
    """
    slip_in = v_in[0] + radius * omega_in
    slip_out = v_out[0] + radius * omega_out
    if tangential is None:
        tangential = abs(slip_in) > 1e-9 * abs(v_in[1])
    return Rebound(
        e=float(-v_out[1] / v_in[1]),
        beta=float(-slip_out / slip_in) if tangential else None,
        cot_gamma=float(abs(v_in[1]) / slip_in) if tangential else None,
        omega=float(omega_out),
        vx_in=float(v_in[0]),
        vy_in=float(v_in[1]),
        vx_out=float(v_out[0]),
        vy_out=float(v_out[1]),
    )


def rebound_from_series(
    series: np.ndarray, radius: float = 1.0, tangential: bool | None = None
) -> Rebound:
    """Rebound from the first row (before contact) and the last (after it).

    After the contact the angular momentum is constant but the moment of
    inertia oscillates with the disk's vibrations (about 1 percent), so the
    angular velocity is taken as L / I0 with I0 the moment of inertia at rest.

    Parameters
    ----------
    series : numpy.recarray
        series.dat (``analysis.impact.series.read_series``).
    radius : float
        The disk's radius R.
    tangential : bool, optional
        Whether the impact is oblique (see ``rebound``).

    Returns
    -------
    Rebound
        e, beta, cot gamma and the spin after the impact.
    """
    first, last = series[0], series[-1]
    inertia = first["Izz"]
    return rebound(
        np.array([first["vx"], first["vy"]]),
        np.array([last["vx"], last["vy"]]),
        first["Lz"] / inertia,
        last["Lz"] / inertia,
        radius,
        tangential,
    )


def contact_window(series: np.ndarray) -> tuple[float, float]:
    """First and last time at which a disk point was within the contact cutoff.

    Parameters
    ----------
    series : numpy.recarray
        series.dat (``analysis.impact.series.read_series``).

    Returns
    -------
    start, end : float
        Times, R/c, of the first and last rows with contact energy.

    Raises
    ------
    ValueError
        If the disk never came within the cutoff.
    """
    touching = series["pe_contact"] > 0.0
    if not touching.any():
        raise ValueError("the disk never came within the contact cutoff of the wall")
    times = series["time"][touching]
    return float(times[0]), float(times[-1])


def touches(series: np.ndarray) -> int:
    """Separate touches: runs of rows in which a disk point was within the cutoff.

    A gap shorter than the series' row interval is not seen.
    """
    touching = (series["pe_contact"] > 0.0).astype(int)
    return int(np.count_nonzero(np.diff(np.concatenate([[0], touching])) == 1))


def side_clearance(series: np.ndarray, wall_width: float, radius: float = 1.0) -> float:
    """Least distance, during contact, from the disk's centre to a fixed side of the wall.

    Parameters
    ----------
    series : numpy.recarray
        series.dat (``analysis.impact.series.read_series``).
    wall_width : float
        The wall's width in units of R.
    radius : float
        The disk's radius R.

    Returns
    -------
    float
        The distance, in R (the unit of ``series``); below R the contact felt
        the wall's end.
    """
    start, end = contact_window(series)
    during = (series["time"] >= start) & (series["time"] <= end)
    return float((wall_width * radius / 2.0 - np.abs(series["x"][during])).min())


def energy_split(series: np.ndarray, energies: np.ndarray, mass: float) -> dict:
    """Where the disk's initial kinetic energy went, as fractions of it.

    Vibrations of the disk: its kinetic and spring energy less its rigid-body
    kinetic energy (translation, and rotation L^2 / 2 I0). Of the wall: all its
    energy (it starts at rest and unstressed).

    Parameters
    ----------
    series : numpy.recarray
        series.dat (``analysis.impact.series.read_series``).
    energies : numpy.recarray
        energy.dat (``analysis.impact.series.read_energies``).
    mass : float
        The disk's mass.

    Returns
    -------
    dict
        ``vibration_disk``, ``vibration_wall`` and ``energy_drift`` (change of
        the total energy), each a fraction of the initial kinetic energy.
    """
    start, end = energies[0], energies[-1]
    first, last = series[0], series[-1]
    e_in = start["ke_disk"]
    rigid_out = (
        0.5 * mass * (last["vx"] ** 2 + last["vy"] ** 2) + 0.5 * last["Lz"] ** 2 / first["Izz"]
    )
    e_total_in = (
        start["ke_disk"]
        + start["pe_disk"]
        + start["ke_wall"]
        + start["pe_wall"]
        + start["pe_contact"]
    )
    e_total_out = (
        end["ke_disk"] + end["pe_disk"] + end["ke_wall"] + end["pe_wall"] + end["pe_contact"]
    )
    return {
        "vibration_disk": float((end["ke_disk"] + end["pe_disk"] - rigid_out) / e_in),
        "vibration_wall": float((end["ke_wall"] + end["pe_wall"]) / e_in),
        "energy_drift": float((e_total_out - e_total_in) / e_in),
    }
