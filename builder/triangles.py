"""The barrier against a triangle of a spring network turning inside out
(``--area-floor``; angle style area/barrier, potentials/angle_area_barrier.cpp).

Under a hard contact the disk's central springs let a Delaunay triangle flatten
and turn over, which an elastic continuum cannot do (docs/rough_contact.md).
With ``area_floor`` J_c > 0 each triangle of a body whose three edges are
springs becomes one LAMMPS angle, its atoms counter-clockwise at rest, with

    E = k A0 [J_c / J - 1 + ln(J / J_c)]  for J = A / A0 < J_c,  0 above,

zero and flat at J_c (so the small-strain moduli are the springs' alone) and
infinite as the area vanishes. k is the body's 2-D bulk modulus, B ka
(calibration/materials.json): the barrier's curvature at J_c is B / J_c^2
per unit area, as stiff against losing area as the lattice itself.

A0 is shared by angle types, not written per triangle: each triangle's
reference area is rounded to a grid of ``AREA_STEP`` in ln A, so the data
file holds one coefficient line per grid value a body uses (2,624 for both
bodies at 6,400 disk points) instead of one per triangle (36,968), and
J at rest is 1 within AREA_STEP / 2. That moves where the barrier starts by
at most 5e-4 of J_c and leaves every triangle at rest, far above J_c, at
zero energy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import Delaunay

from ground.checks import Range

from .network import edge_keys

# J_c: the share of its area at rest below which a triangle meets the barrier;
# 0, no barrier (no angles at all: the scene as before the option).
AREA_FLOOR = Range(0.0, 0.9, unit="the share of a triangle's area at rest below which the "
                   "barrier acts; 0: no barrier")  # fmt: skip
AREA_STEP = 1e-3  # the grid of ln A0 that the angle types share
ANGLE_STYLE = "area/barrier"


@dataclass
class Triangles:
    """A scene's angles: atoms (0-based, counter-clockwise at rest) and types,
    and each type's coefficients A0, k, J_c."""

    atoms: np.ndarray  # (t, 3)
    types: np.ndarray  # (t,) 1-based
    coefficients: np.ndarray  # (types, 3): A0 k J_c


def signed_areas(positions: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Each triangle's signed area, positive counter-clockwise."""
    a, b, c = (positions[triangles[:, i]] for i in range(3))
    u, v = b - a, c - a
    return 0.5 * (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])


def spring_triangles(positions: np.ndarray, springs: np.ndarray, members: np.ndarray) -> np.ndarray:
    """The triangles of the Delaunay triangulation of the points ``members``
    (indices into ``positions``) whose three edges are springs, counter-clockwise."""
    simplices = members[Delaunay(positions[members]).simplices]
    size = len(positions)
    known = np.sort(edge_keys(np.sort(springs, axis=1), size))
    keep = np.ones(len(simplices), bool)
    for i in range(3):
        edge = np.sort(simplices[:, [i, (i + 1) % 3]], axis=1)
        key = edge_keys(edge, size)
        at = np.clip(np.searchsorted(known, key), 0, len(known) - 1)
        keep &= known[at] == key
    triangles = simplices[keep]
    turned = signed_areas(positions, triangles) < 0.0
    triangles[turned] = triangles[turned][:, [0, 2, 1]]
    return triangles


def barrier_triangles(
    positions: np.ndarray, springs: np.ndarray, bodies: list[tuple[np.ndarray, float]], floor: float
) -> Triangles:
    """The angles of every body: ``bodies`` lists each one's atoms (indices)
    and stiffness k; ``floor`` is J_c."""
    atoms, types, rows = [], [], []
    for members, k in bodies:
        triangles = spring_triangles(positions, springs, members)
        grid = np.round(np.log(signed_areas(positions, triangles)) / AREA_STEP).astype(np.int64)
        values, index = np.unique(grid, return_inverse=True)
        atoms.append(triangles)
        types.append(index.ravel() + len(rows) + 1)
        rows.extend([np.exp(v * AREA_STEP), k, floor] for v in values.tolist())
    return Triangles(np.concatenate(atoms), np.concatenate(types), np.array(rows, float))
