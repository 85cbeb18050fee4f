"""The time series a run writes: the disk's rigid-body motion and the contact."""

from __future__ import annotations

from pathlib import Path

import numpy as np

COLUMNS = ("step", "time", "x", "y", "vx", "vy", "Lz", "Izz", "omega_z", "fx", "fy", "pe_contact")


def read_series(path: Path | str) -> np.ndarray:
    """series.dat as a structured array with the names in ``COLUMNS``.

    Parameters
    ----------
    path : pathlib.Path or str
        A run's series.dat.

    Returns
    -------
    numpy.recarray
        One record per row: step, time, x, y, vx, vy, Lz, Izz, omega_z, fx, fy,
        pe_contact.

    Raises
    ------
    ValueError
        If the file has not those columns.
    """
    data = np.loadtxt(path, comments="#", ndmin=2)
    if data.shape[1] != len(COLUMNS):
        raise ValueError(f"{path}: expected {len(COLUMNS)} columns, found {data.shape[1]}")
    return np.rec.fromarrays(data.T, names=COLUMNS)


def read_energies(path: Path | str) -> np.ndarray:
    """energy.dat: the first row at the start, the last one at the end of the run.

    Parameters
    ----------
    path : pathlib.Path or str
        A run's energy.dat.

    Returns
    -------
    numpy.recarray
        Records of time, ke_disk, pe_disk, ke_wall, pe_wall, pe_contact.
    """
    data = np.loadtxt(path, comments="#", ndmin=2)
    names = ("time", "ke_disk", "pe_disk", "ke_wall", "pe_wall", "pe_contact")
    return np.rec.fromarrays(data.T, names=names)
