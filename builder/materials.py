"""Elastic wave speed of each lattice, which sets the units of a scene.

Every spring constant is chosen so that the disk's wave speed c = sqrt(E / rho)
is 1 with point mass m = 1 and radius R = 1. That needs c in terms of the
spring constant ka and the spacing d: c^2 = factor * ka * d^2 / m.

Until the calibration measures E for each lattice, the factors are estimates:
exact for the triangular lattice (E = 2 ka / sqrt(3)), the continuum value
along the axes for the square lattice (E = k1 (k1 + 2 k2) / (k1 + k2)), and the
triangular value at the same number density for the random lattice.
"""

from __future__ import annotations

SOURCE_ESTIMATE = "estimate: triangular-lattice formula (uncalibrated)"


def wave_speed_factor(lattice: str, k2_over_k1: float = 0.0) -> tuple[float, str]:
    """The factor in c^2 = factor * ka * d^2 / m, and where it comes from."""
    if lattice == "triangular":
        return 1.0, "exact: triangular lattice, c^2 = k d^2 / m"
    if lattice == "square":
        r = k2_over_k1
        return (1.0 + 2.0 * r) / (1.0 + r), "estimate: square lattice along its axes (uncalibrated)"
    return 1.0, SOURCE_ESTIMATE


def spring_constant(lattice: str, spacing: float, k2_over_k1: float = 0.0,
                    wave_speed: float = 1.0, mass: float = 1.0) -> tuple[float, str]:
    """ka that gives the lattice the wave speed ``wave_speed``."""
    factor, source = wave_speed_factor(lattice, k2_over_k1)
    return wave_speed**2 * mass / (factor * spacing**2), source
