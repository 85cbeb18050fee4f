"""Elastic constants of the lattices: the calibrated table, and the closed forms.

Every scene sets its spring constants so that the disk's wave speed
c = sqrt(E / rho) is 1 with m = 1 and R = 1. That needs the measured factor in
c^2 = factor * ka * d^2 / m, from calibration/materials.json (`make
calibrate`). A lattice that is not in the table is refused.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from ground.errors import InputError
from ground.paths import ROOT

TABLE = ROOT / "calibration" / "materials.json"


def square_poisson_ratio(k2_over_k1: float, angle_deg: float = 0.0) -> float:
    """Poisson ratio of the square lattice pulled along (cos a, sin a) (docs/model.md).

    Parameters
    ----------
    k2_over_k1 : float
        Diagonal over nearest-neighbour spring constant.
    angle_deg : float
        Direction of the pull from the lattice's axis, degrees.

    Returns
    -------
    float
        The Poisson ratio of the continuum limit.
    """
    k1, k2 = 1.0, k2_over_k1
    a = np.radians(angle_deg)
    s = (k1 * k1 - 4.0 * k2 * k2) * (np.cos(a) * np.sin(a)) ** 2
    return float((k2 * k2 + s) / (k2 * (k1 + k2) + s))


def _square_compliances(k2_over_k1: float) -> tuple[float, float, float]:
    """S11, S12, S66 of the square lattice's continuum limit, in units of 1/k1.

    The stiffnesses are C11 = k1 + k2, C12 = C66 = k2 (2-D, per unit length).
    """
    c11, c12, c66 = 1.0 + k2_over_k1, k2_over_k1, k2_over_k1
    return c11 / (c11 * c11 - c12 * c12), -c12 / (c11 * c11 - c12 * c12), 1.0 / c66


def square_wave_speed_factor(k2_over_k1: float, angle_deg: float = 0.0) -> float:
    """c^2 / (k1 d^2 / m) of the square lattice along (cos a, sin a).

    From the stiffnesses C11 = k1 + k2, C12 = C66 = k2 of the continuum limit:
    1/E(a) = S11 - (2 S11 - 2 S12 - S66) sin^2 a cos^2 a; the density is 1/d^2.
    """
    s11, s12, s66 = _square_compliances(k2_over_k1)
    a = np.radians(angle_deg)
    compliance = s11 - (2.0 * s11 - 2.0 * s12 - s66) * (np.sin(a) * np.cos(a)) ** 2
    return float(1.0 / compliance)


def square_shear_modulus(k2_over_k1: float, angle_deg: float = 0.0) -> float:
    """Shear modulus G / k1 of the square lattice in the frame turned by ``angle_deg``.

    Shear along (cos a, sin a) and its normal: 1/G(a) = S66 + (2 (S11 - S12)
    - S66) sin^2 2a, the compliance turned by a. Along the axes G = C66 = k2,
    at 45 degrees G = (C11 - C12) / 2 = k1 / 2.
    """
    s11, s12, s66 = _square_compliances(k2_over_k1)
    a = np.radians(angle_deg)
    return float(1.0 / (s66 + (2.0 * (s11 - s12) - s66) * np.sin(2.0 * a) ** 2))


def square_bulk_modulus(k2_over_k1: float) -> float:
    """2-D bulk modulus B / k1 = (C11 + C12) / 2 of the square lattice (any direction)."""
    return (1.0 + 2.0 * k2_over_k1) / 2.0


def square_ratio_for_poisson(nu: float, angle_deg: float = 0.0) -> float:
    """k2/k1 that gives the square lattice the Poisson ratio ``nu`` along ``angle_deg``.

    Parameters
    ----------
    nu : float
        The Poisson ratio wanted.
    angle_deg : float
        Direction of the pull from the lattice's axis, degrees.

    Returns
    -------
    float
        k2 / k1.

    Raises
    ------
    ground.errors.InputError
        If no ratio gives ``nu`` along that direction.
    """
    low, high = 1e-6, 1e3
    f = lambda r: square_poisson_ratio(r, angle_deg) - nu  # noqa: E731
    if f(low) * f(high) > 0:
        raise InputError(
            f"nu must be between {square_poisson_ratio(low, angle_deg):.3f} and "
            f"{square_poisson_ratio(high, angle_deg):.3f} along {angle_deg} degrees, got {nu}"
        )
    return float(brentq(f, low, high, xtol=1e-14, rtol=1e-14))


@lru_cache(maxsize=1)
def _table(path: str) -> tuple[dict, ...]:
    return tuple(json.loads(Path(path).read_text())["materials"])


def calibrated(
    lattice: str, k2_over_k1: float | None = None, angle_deg: float = 0.0, table: Path | str = TABLE
) -> dict:
    """The table's entry for a lattice; InputError if it was not calibrated.

    Parameters
    ----------
    lattice : str
        ``random``, ``triangular`` or ``square``.
    k2_over_k1 : float, optional
        The square lattice's spring ratio (ignored for the others).
    angle_deg : float
        Direction of the calibration pull, degrees.
    table : pathlib.Path or str
        The materials table (default calibration/materials.json).

    Returns
    -------
    dict
        The entry: E, nu and c2 (the wave speed squared in units of
        ka d^2 / m), with their standard deviations and errors, and the strips
        they were measured on.

    Raises
    ------
    ground.errors.InputError
        If the lattice is not in the table (``python -m calibration run``).
    """
    ratio = k2_over_k1 if lattice == "square" else None
    if Path(table).exists():
        for entry in _table(str(table)):
            if (
                entry["lattice"] == lattice
                and entry["angle_deg"] == angle_deg
                and (ratio is None or np.isclose(entry["k2_over_k1"], ratio, rtol=1e-9))
            ):
                return entry
    what = f"lattice {lattice}" + (f" with k2_over_k1 = {ratio:.6g}" if ratio is not None else "")
    extra = f" --square {ratio:.6g}" if ratio is not None else ""
    raise InputError(
        f"{what} is not calibrated (not in {Path(table).name}); "
        f"run: python -m calibration run{extra}"
    )


def spring_constant(
    lattice: str,
    spacing: float,
    k2_over_k1: float | None = None,
    wave_speed: float = 1.0,
    mass: float = 1.0,
) -> tuple[float, dict]:
    """ka that gives the lattice the wave speed ``wave_speed``, and the table entry.

    Parameters
    ----------
    lattice : str
        ``random``, ``triangular`` or ``square``.
    spacing : float
        The lattice's mean spacing.
    k2_over_k1 : float, optional
        The square lattice's spring ratio.
    wave_speed : float
        The wave speed wanted, in units of c.
    mass : float
        Mass of a point.

    Returns
    -------
    ka : float
        The quadratic spring constant.
    entry : dict
        The lattice's entry of the materials table (``calibrated``).
    """
    entry = calibrated(lattice, k2_over_k1)
    return wave_speed**2 * mass / (entry["c2"] * spacing**2), entry


# The lattices a study names, and the disk each stands for: the square
# lattice at two Poisson ratios (runner.study's grids, the pages' order).
STUDY_LATTICES = {
    "random": {"lattice": "random"},
    "triangular": {"lattice": "triangular"},
    "square_nu0.1": {"lattice": "square", "k2_over_k1": square_ratio_for_poisson(0.1)},
    "square_nu0.3": {"lattice": "square", "k2_over_k1": square_ratio_for_poisson(0.3)},
}
