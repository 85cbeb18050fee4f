"""Forces of the whole model: class2 springs and the contact (disk and wall, or two disks)."""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field

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
    incidence: sparse.csr_matrix = field(init=False, repr=False)

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
        """Total force, spring energy, contact energy."""
        springs, e_springs = self.spring_forces(x)
        contact, e_contact = self.contact_forces(x)
        return springs + contact, e_springs, e_contact
