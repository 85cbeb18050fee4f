"""e and beta from a LAMMPS dump through MDAnalysis: the route for notebooks.

The dump must hold x, y, z and vx, vy, vz (MDAnalysis wants all three even in
2-D). MDAnalysis shifts positions by the box's lower corner, which changes
from frame to frame in a shrink-wrapped box; only positions relative to the
disk's centre of mass are used here, which the shift does not change.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .restitution import Rebound, rebound

DISK_MOLECULE = 1


def open_run(folder: Path | str):
    """An MDAnalysis Universe of a run folder: scene.data and dump.lammpstrj.

    Parameters
    ----------
    folder : pathlib.Path or str
        A run folder that was run with ``dump_every`` > 0 (``RunOptions``).

    Returns
    -------
    MDAnalysis.Universe
        Topology from scene.data (``resid`` is the LAMMPS molecule: 1 the disk),
        trajectory from dump.lammpstrj.
    """
    import MDAnalysis as mda

    folder = Path(folder)
    return mda.Universe(
        str(folder / "scene.data"),
        str(folder / "dump.lammpstrj"),
        atom_style="id resid type x y z",
        format="LAMMPSDUMP",
    )


def rigid_motion(atoms) -> tuple[np.ndarray, float, float]:
    """Centre-of-mass velocity, angular momentum Lz and moment of inertia Izz.

    Parameters
    ----------
    atoms : MDAnalysis.AtomGroup
        The atoms of one body (e.g. the disk) at the current frame; needs masses,
        positions and velocities.

    Returns
    -------
    v_cm : numpy.ndarray
        Centre-of-mass velocity (x, y).
    lz : float
        Angular momentum about the centre of mass.
    izz : float
        Moment of inertia about the centre of mass.
    """
    masses = atoms.masses.astype(float)
    r = atoms.positions[:, :2].astype(float)
    v = atoms.velocities[:, :2].astype(float)
    mass = masses.sum()
    r = r - masses @ r / mass
    v_cm = masses @ v / mass
    v = v - v_cm
    lz = float(np.sum(masses * (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0])))
    izz = float(np.sum(masses * (r * r).sum(axis=1)))
    return v_cm, lz, izz


def rebound_from_dump(universe, radius: float = 1.0) -> Rebound:
    """Rebound from the first frame (before contact) and the last (after it).

    Parameters
    ----------
    universe : MDAnalysis.Universe
        A run's dump, as ``open_run`` gives it; its first frame before the
        contact and its last after it.
    radius : float
        The disk's radius R.

    Returns
    -------
    Rebound
        e, beta, cot gamma and the spin after the impact (``analysis.impact.restitution``).
    """
    disk = universe.select_atoms(f"resid {DISK_MOLECULE}")
    universe.trajectory[0]
    v_in, l_in, inertia = rigid_motion(disk)
    universe.trajectory[-1]
    v_out, l_out, _ = rigid_motion(disk)
    return rebound(v_in, v_out, l_in / inertia, l_out / inertia, radius)
