"""Forces of the whole model: class2 springs, the area barrier on the bodies'
triangles (--area-floor) and the contact (disk and wall, or two disks)."""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import scipy.sparse as sparse

from builder.lammps_data import System
from ground.paths import BUILD

from .contact import polyline_contact, two_ring_contact

LIBRARY = BUILD / "libreference_springs.so"


def compiled_springs():
    """The C loop of reference/springs.c (make setup builds it), or None."""
    if not LIBRARY.exists():
        return None
    function = ctypes.CDLL(str(LIBRARY)).spring_forces
    # raw pointers: the arrays are checked once, when the model is built
    function.argtypes = [ctypes.c_int] + [ctypes.c_void_p] * 6 + [ctypes.c_int, ctypes.c_void_p]
    function.restype = ctypes.c_double
    return function


class TurnedOver(RuntimeError):
    """A triangle of the barrier was found turned over (J <= 0 with J_c > 0):
    it crossed the barrier within one step."""


class Barrier(NamedTuple):
    """What ``area_barrier`` finds at one configuration."""

    force: np.ndarray  # (n, 2) on the atoms
    energy: float
    each: np.ndarray  # (t,) each triangle's energy
    ratio: np.ndarray  # (t,) each triangle's J = A / A0


def area_barrier(
    x: np.ndarray, triangles: np.ndarray, a0: np.ndarray, k: np.ndarray, jc: np.ndarray
) -> Barrier:
    """The area barrier's forces and energy (docs/model.md, ``--area-floor``).

    Each triangle (p, q, r) has the signed area A = (q - p) x (r - p) / 2,
    positive counter-clockwise, and J = A / A0. Below J_c its energy is
    k A0 [J_c / J - 1 + ln(J / J_c)], zero above; so dE/dA = k (J - J_c) / J^2,
    and dA/dp = z x (r - q) / 2 (each vertex: the opposite edge, turned a
    quarter to the left, halved), so that the force on p is -dE/dA dA/dp.

    Parameters
    ----------
    x : numpy.ndarray
        (n, 2) positions.
    triangles : numpy.ndarray
        (t, 3) atom indices, counter-clockwise at rest.
    a0, k, jc : numpy.ndarray
        (t,) each triangle's area at rest, stiffness and J_c.

    Returns
    -------
    Barrier
        The forces, the energy, each triangle's energy and its J.

    Raises
    ------
    TurnedOver
        If a triangle with J_c > 0 has J <= 0.
    """
    force = np.zeros_like(x)
    each = np.zeros(len(triangles))
    if len(triangles) == 0:
        return Barrier(force, 0.0, each, np.zeros(0))
    p, q, r = (x[triangles[:, i]] for i in range(3))
    u, w = q - p, r - p
    j = 0.5 * (u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]) / a0
    inside = np.flatnonzero((j < jc) & (jc > 0.0))
    if inside.size == 0:
        return Barrier(force, 0.0, each, j)
    j_in, jc_in, k_in, a0_in = j[inside], jc[inside], k[inside], a0[inside]
    if (j_in <= 0.0).any():
        worst = inside[np.argmin(j_in)]
        raise TurnedOver(
            f"triangle of atoms {' '.join(str(i + 1) for i in triangles[worst])} turned over "
            f"(J = {j[worst]:.6g}): it crossed the barrier within one step"
        )
    each[inside] = k_in * a0_in * (jc_in / j_in - 1.0 + np.log(j_in / jc_in))
    de_da = k_in * (j_in - jc_in) / (j_in * j_in)
    corners = triangles[inside]
    n = len(x)
    for vertex in range(3):
        # the edge opposite the vertex, from the next vertex to the one after
        edge = x[corners[:, (vertex + 2) % 3]] - x[corners[:, (vertex + 1) % 3]]
        # -dE/dA times z x edge / 2, z x (ex, ey) = (-ey, ex)
        fx = 0.5 * de_da * edge[:, 1]
        fy = -0.5 * de_da * edge[:, 0]
        force[:, 0] += np.bincount(corners[:, vertex], fx, minlength=n)
        force[:, 1] += np.bincount(corners[:, vertex], fy, minlength=n)
    return Barrier(force, float(each.sum()), each, j)


@dataclass
class Model:
    """The interactions of a scene, ready to evaluate."""

    system: System
    a: float
    v0: float
    cutoff: float
    disk_surface: np.ndarray  # indices of the disk's surface points
    wall_row: np.ndarray  # indices of the wall's surface polyline, in order
    contact: str = "segment"  # segment or pair
    rule: str = "lever"
    # a binary scene's: the disk's surface ring, which wall_row (the second
    # disk's ring) repels and which repels it (reference.contact.two_ring_contact)
    partner_ring: np.ndarray | None = None
    compiled: bool = True  # springs by the C loop when it is built
    barrier: bool = True  # the area barrier, when the data file has its angles
    incidence: sparse.csr_matrix = field(init=False, repr=False)
    # what the barrier saw over the evaluations since the model was made, as
    # fix area/barrier counts it: the most triangles inside at once (J < J_c)
    # and the smallest J
    in_barrier_max: int = field(init=False, default=0)
    area_ratio_min: float = field(init=False, default=np.inf)

    def __post_init__(self) -> None:
        # bond vectors x_j - x_i = B x, forces on atoms = -B^T (tension along bond)
        s = self.system
        m, n = len(s.bonds), len(s.x)
        rows = np.concatenate([np.arange(m), np.arange(m)])
        cols = np.concatenate([s.bonds[:, 1], s.bonds[:, 0]])
        signs = np.concatenate([np.ones(m), -np.ones(m)])
        self.incidence = sparse.csr_matrix((signs, (rows, cols)), shape=(m, n))
        self.incidence_t = self.incidence.T.tocsr()
        self._loop = compiled_springs() if self.compiled else None
        if self._loop is not None:
            self._ends = np.ascontiguousarray(s.bonds, dtype=np.intc)
            self._arrays = [np.ascontiguousarray(a, dtype=float) for a in (s.r0, s.k2, s.k3, s.k4)]
            self._pointers = [self._ends.ctypes.data] + [a.ctypes.data for a in self._arrays]

    def spring_forces(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        s = self.system
        if self._loop is not None:
            x = np.ascontiguousarray(x, dtype=float)
            force = np.empty_like(x)
            energy = self._loop(
                len(s.bonds), *self._pointers, x.ctypes.data, len(x), force.ctypes.data
            )
            return force, energy
        d = self.incidence @ x
        r = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
        dr = r - s.r0
        energy = float(np.sum(dr * dr * (s.k2 + dr * (s.k3 + dr * s.k4))))
        # dE/dr along the bond, pulling its ends together when stretched
        tension = (dr * (2.0 * s.k2 + dr * (3.0 * s.k3 + dr * 4.0 * s.k4))) / r
        return -(self.incidence_t @ (tension[:, None] * d)), energy

    @property
    def has_barrier(self) -> bool:
        """Whether the barrier acts: the data file has its angles and ``barrier`` is on."""
        return self.barrier and len(self.system.angles) > 0

    def barrier_forces(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        """The area barrier's forces and energy (``area_barrier``); zero
        without it (``has_barrier``)."""
        s = self.system
        if not self.has_barrier:
            return np.zeros_like(x), 0.0
        found = area_barrier(x, s.angles, s.a0, s.k_area, s.jc)
        self.in_barrier_max = max(self.in_barrier_max, int(np.sum(found.ratio < s.jc)))
        self.area_ratio_min = min(self.area_ratio_min, float(found.ratio.min()))
        return found.force, found.energy

    def internal_forces(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        """The bodies' own forces, springs and barrier, and their energy."""
        springs, e_springs = self.spring_forces(x)
        if not self.has_barrier:  # the paper's scenes: no array of zeros to add
            return springs, e_springs
        barrier, e_barrier = self.barrier_forces(x)
        return springs + barrier, e_springs + e_barrier

    def contact_forces(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        force = np.zeros_like(x)
        if self.partner_ring is not None:
            return self._ring_forces(x, force)
        points, row = x[self.disk_surface], x[self.wall_row]
        # only disk points in range of the wall, and the part of the wall under
        # them: the parity test needs only segments that straddle a point's x
        near = points[:, 1] < row[:, 1].max() + self.cutoff
        if not near.any():
            return force, 0.0
        lo = points[near, 0].min() - self.cutoff
        hi = points[near, 0].max() + self.cutoff
        inside_x = (row[:, 0] >= lo) & (row[:, 0] <= hi)
        window = np.flatnonzero(inside_x)
        if window.size == 0:
            return force, 0.0
        first, last = max(window[0] - 1, 0), min(window[-1] + 2, len(row))
        disk_points = self.disk_surface[near]
        wall_points = self.wall_row[first:last]
        if self.contact == "segment":
            result = polyline_contact(
                x[disk_points], x[wall_points], self.a, self.v0, self.cutoff, self.rule
            )
            force[disk_points] = result.on_points
            force[wall_points] = result.on_vertices
            return force, result.energy
        return self._pair_forces(x[disk_points], x[wall_points], disk_points, wall_points, force)

    def _ring_forces(self, x: np.ndarray, force: np.ndarray) -> tuple[np.ndarray, float]:
        """Two disks: both rings whole, every point against the other's ring."""
        ring_a, ring_b = self.partner_ring, self.wall_row
        if self.contact == "pair":
            return self._pair_forces(x[ring_a], x[ring_b], ring_a, ring_b, force)
        result = two_ring_contact(x[ring_a], x[ring_b], self.a, self.v0, self.cutoff, self.rule)
        force[ring_a] = result.on_points
        force[ring_b] = result.on_vertices
        return force, result.energy

    def _pair_forces(self, points, row, disk_points, wall_points, force):
        """The pair variant: the same exponential between points."""
        d = points[:, None, :] - row[None, :, :]
        r = np.linalg.norm(d, axis=-1)
        near = r < self.cutoff
        energy = np.where(near, self.v0 * np.exp(-self.a * r), 0.0)
        f = (self.a * energy / np.where(near, r, 1.0))[..., None] * d
        force[disk_points] = f.sum(axis=1)
        force[wall_points] = -f.sum(axis=0)
        return force, float(energy.sum())

    def forces(self, x: np.ndarray) -> tuple[np.ndarray, float, float]:
        """Total force, the bodies' own energy (springs and barrier), contact energy."""
        internal, e_internal = self.internal_forces(x)
        contact, e_contact = self.contact_forces(x)
        return internal + contact, e_internal, e_contact
