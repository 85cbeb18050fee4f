"""One tensile test: a strip stretched by decks/stretch.lmp, and what it gives.

Units of the strip: spacing d, spring constant ka and point mass m are 1.
Under uniaxial stress the bulk stress is the number density times the mean
per-atom virial, so c^2 = E / rho = d<virial_xx>/d(strain_xx) / m: the
density cancels. E itself is c^2 rho, with the density counted in the inner
part of the strip.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial import ConvexHull, Voronoi

from builder.lammps_data import read_data
from builder.strips import StripSpec, make_strip, write_strip
from ground.launch import run_lmp
from ground.paths import DECKS

DECK = DECKS / "stretch.lmp"


@dataclass
class Stretch:
    """The settled states of one strip and the moduli fitted to them."""

    spec: StripSpec
    strain_xx: np.ndarray  # of the inner part
    strain_yy: np.ndarray
    gauge_xx: np.ndarray  # of the middle third, between bands and edges
    gauge_yy: np.ndarray
    virial_xx: np.ndarray  # mean per-atom virial of the inner part
    force: np.ndarray  # mean of the two grip forces (they balance)
    imbalance: float  # largest |F_left + F_right| / |F_right|
    kinetic: float  # largest kinetic energy left at a settled state
    inner_density: float  # points per unit area (d^-2) in the inner part
    line_density: float  # points per unit length of the strip

    @property
    def c2(self) -> float:
        """c^2 in units of ka d^2 / m: the linear coefficient of virial vs strain."""
        return linear_coefficient(self.strain_xx, self.virial_xx)

    @property
    def nu(self) -> float:
        return -linear_coefficient(self.strain_xx, self.strain_yy)

    @property
    def nu_gauge(self) -> float:
        """The Poisson ratio from the middle third's length and width (edges included)."""
        return -linear_coefficient(self.gauge_xx, self.gauge_yy)

    @property
    def e_modulus(self) -> float:
        """E in units of ka (2-D)."""
        return self.c2 * self.inner_density

    @property
    def shear_modulus(self) -> float:
        """E / (2 (1 + nu)) in units of ka: the shear modulus of the frame at 45
        degrees to the pull. Shearing that frame is tension along the pull and as
        much compression across it; exact for a pull along a mirror line of a
        lattice whose elastic constants repeat every 90 degrees (the square one
        at 0 and 45 degrees) and for an isotropic one (triangular, random)."""
        return self.e_modulus / (2.0 * (1.0 + self.nu))

    @property
    def bulk_modulus(self) -> float:
        """E / (2 (1 - nu)) in units of ka: the 2-D bulk modulus, on the same
        lattices and pulls (then the same for every pull)."""
        return self.e_modulus / (2.0 * (1.0 - self.nu))

    @property
    def c2_strip(self) -> float:
        """c^2 of the strip as a whole (force / strain / mass per length): edges included."""
        return linear_coefficient(self.gauge_xx, self.force) / self.line_density

    @property
    def nonlinearity(self) -> float:
        """Quadratic over linear term of virial vs strain, at the largest strain."""
        linear, quadratic = np.polyfit(self.strain_xx, self.virial_xx, 2)[::-1][1:]
        return float(abs(quadratic * self.strain_xx.max() / linear))


def linear_coefficient(x: np.ndarray, y: np.ndarray) -> float:
    """b in the least-squares fit y = b x + c x^2 (through the unstrained state)."""
    design = np.stack([x, x * x], axis=1)
    return float(np.linalg.lstsq(design, y, rcond=None)[0][0])


def run_stretch(
    spec: StripSpec,
    folder: Path | str,
    strain: float = 2e-4,
    steps: int = 5,
    area_floor: float = 0.0,
) -> Stretch:
    """Write the strip, stretch it with LAMMPS and read back the settled states
    (``area_floor``: with the barrier's angles, builder/triangles.py)."""
    folder = write_strip(spec, folder, area_floor)
    variables = {"strip": str(folder), "strain": repr(strain), "nsteps": str(steps)}
    run_lmp(variables, folder / "log.lammps", deck=DECK)
    return read_stretch(spec, folder)


def bulk_density(spec: StripSpec) -> float:
    """Points per unit area in the strip's inner part: one over the mean area of
    their Voronoi cells (exact for the regular lattices, no edge effects)."""
    points = make_strip(spec)[0]
    voronoi = Voronoi(points)
    inner = (np.abs(points[:, 0]) < spec.length / 6.0) & (np.abs(points[:, 1]) < spec.width / 4.0)
    areas = [
        ConvexHull(voronoi.vertices[voronoi.regions[voronoi.point_region[i]]]).volume
        for i in np.flatnonzero(inner)
    ]
    return float(1.0 / np.mean(areas))


def read_stretch(spec: StripSpec, folder: Path) -> Stretch:
    table = np.loadtxt(folder / "stretch.dat", comments="#")
    _, _, left, right, length, width, inner_length, inner_width, sxx, _, ke = table.T
    total_atoms = len(read_data(folder / "strip.data").x)
    stretched = slice(1, None)
    return Stretch(
        spec=spec,
        strain_xx=inner_length / inner_length[0] - 1.0,
        strain_yy=inner_width / inner_width[0] - 1.0,
        gauge_xx=length / length[0] - 1.0,
        gauge_yy=width / width[0] - 1.0,
        virial_xx=sxx,
        force=0.5 * (left - right),
        imbalance=float(np.max(np.abs(left + right)[stretched] / np.abs(right[stretched]))),
        kinetic=float(ke.max()),
        inner_density=bulk_density(spec),
        line_density=total_atoms / spec.length,
    )
