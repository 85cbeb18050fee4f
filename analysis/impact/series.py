"""The time series a run writes: the disk's rigid-body motion and the contact."""

from __future__ import annotations

from pathlib import Path

import numpy as np

COLUMNS = ("step", "time", "x", "y", "vx", "vy", "Lz", "Izz", "omega_z", "fx", "fy", "pe_contact")
# A binary scene's (decks/binary.lmp): the second disk's motion, prefixed t, too.
BINARY_COLUMNS = (
    *COLUMNS[:-1],
    *(f"t{name}" for name in ("x", "y", "vx", "vy", "Lz", "Izz", "omega_z", "fx", "fy")),
    "pe_contact",
)


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
    names = {len(COLUMNS): COLUMNS, len(BINARY_COLUMNS): BINARY_COLUMNS}.get(data.shape[1])
    if names is None:
        raise ValueError(
            f"{path}: expected {len(COLUMNS)} columns (or a binary scene's "
            f"{len(BINARY_COLUMNS)}), found {data.shape[1]}"
        )
    return np.rec.fromarrays(data.T, names=names)


def read_energies(path: Path | str) -> np.ndarray:
    """energy.dat: the first row at the start, the last one at the end of the run.

    Parameters
    ----------
    path : pathlib.Path or str
        A run's energy.dat.

    Returns
    -------
    numpy.recarray
        Records of time, ke_disk, pe_disk, ke_wall, pe_wall, pe_contact (a
        binary scene's: ke_target and pe_target for the wall's).
    """
    data = np.loadtxt(path, comments="#", ndmin=2)
    names = ("time", "ke_disk", "pe_disk", "ke_wall", "pe_wall", "pe_contact")
    header = Path(path).read_text().split("\n", 1)[0].split()
    if header[1:] and header[0] == "#" and len(header) - 1 == data.shape[1]:
        names = tuple(header[1:])  # a binary scene's: ke_target, pe_target
    return np.rec.fromarrays(data.T, names=names)
