"""The impact deck's 2-D styles (potentials/): compute motion/2d against
LAMMPS's group functions, fix nve/2d against fix nve bit for bit."""

from __future__ import annotations

import filecmp
import subprocess

import numpy as np
import pytest

from ground.launch import mpi_environment, run_lmp
from tests.helpers import ROOT, new_lammps

pytestmark = pytest.mark.lammps


def spinning_scene(scene_dir, nve_style="nve"):
    """The scene in LAMMPS with the disk spinning and springs acting, before
    any run."""
    from ground.launch import register_styles

    lmp = new_lammps()
    register_styles(lmp)
    for command in [
        "units lj",
        "dimension 2",
        "boundary s s p",
        "atom_style bond",
        "special_bonds lj/coul 1.0 1.0 1.0",
        "bond_style class2",  # small_scene_dir's springs
        f"read_data {scene_dir}/scene.data",
        "group disk molecule 1",
        "pair_style zero 0.1",
        "pair_coeff * *",
        "comm_modify cutoff 1.0",
        "velocity disk create 0.01 4928 loop geom",
        "variable spin_x atom vx-0.05*(y-xcm(disk,y))",
        "variable spin_y atom vy+0.05*(x-xcm(disk,x))",
        "velocity disk set v_spin_x v_spin_y NULL",
        f"fix move all {nve_style}",
        "timestep 0.008",
    ]:
        lmp.command(command)
    return lmp


def motion_instance(scene_dir):
    """The spinning scene after 50 steps, group functions and compute
    motion/2d side by side."""
    lmp = spinning_scene(scene_dir)
    lmp.command("compute motion disk motion/2d")
    lmp.command("run 50")
    return lmp


def test_motion_2d_is_the_group_functions(small_scene_dir):
    lmp = motion_instance(small_scene_dir)
    motion = [lmp.numpy.extract_compute("motion", 0, 1)[k] for k in range(9)]
    functions = [
        "xcm(disk,x)",
        "xcm(disk,y)",
        "vcm(disk,x)",
        "vcm(disk,y)",
        "angmom(disk,z)",
        "inertia(disk,zz)",
        "omega(disk,z)",
        "fcm(disk,x)",
        "fcm(disk,y)",
    ]
    for k, function in enumerate(functions):
        lmp.command(f"variable f{k} equal {function}")
    expected = [lmp.extract_variable(f"f{k}") for k in range(len(functions))]
    lmp.close()
    # the same sums in the same order: equal but for omega (LAMMPS inverts the
    # 3-D inertia tensor, Lz / Izz here) and the force, which LAMMPS sums in
    # one pass with the positions
    assert motion[:6] == expected[:6]
    assert motion[6] == pytest.approx(expected[6], rel=1e-12)
    assert np.allclose(motion[7:], expected[7:], rtol=0, atol=1e-12)
    assert abs(motion[4]) > 1.0 and abs(motion[6]) > 1e-3  # it does spin


@pytest.mark.parametrize("integrator", ["verlet", "respa"])
def test_nve_2d_is_fix_nve_bit_for_bit(small_scene_dir, tmp_path, integrator):
    """The same impact with LAMMPS's fix nve and with fix nve/2d: every row of
    the series and the energies, to the last bit."""
    outputs = []
    for style in ("nve", "nve/2d"):
        out = tmp_path / style.replace("/", "")
        out.mkdir()
        variables = {"scene": str(small_scene_dir), "out": str(out), "nve_style": style}
        variables.update({"springs": "class2", "integrator": integrator, "tmax": "20"})
        run_lmp(variables, out / "log.lammps")
        outputs.append(out)
    for name in ("series.dat", "energy.dat"):
        assert filecmp.cmp(outputs[0] / name, outputs[1] / name, shallow=False)
    assert len((outputs[0] / "series.dat").read_text().splitlines()) > 100  # it ran


def state_after(scene_dir, nve_style, commands):
    """Positions, velocities and the step after the commands."""
    lmp = spinning_scene(scene_dir, nve_style)
    for command in commands:
        lmp.command(command)
    state = (
        lmp.numpy.extract_atom("x").copy(),
        lmp.numpy.extract_atom("v").copy(),
        lmp.extract_global("ntimestep"),
    )
    lmp.close()
    return state


@pytest.mark.parametrize(
    "commands",
    [
        ["run 37"],  # no end-of-step fix: every closing kick but the last deferred
        ["run 13", "run 24 pre no post no"],  # a run ends, the next one starts
        ["fix out all print 7 '$(vcm(disk,x))' screen no", "thermo 5", "run 37"],
    ],
)
def test_deferred_kick_is_fix_nve_bit_for_bit(small_scene_dir, commands):
    """fix nve/2d defers the closing half kick of a step that nothing reads
    to the next step's opening pass: x and v equal fix nve's to the last bit
    at the end of any run, whatever reads the atoms in between."""
    x, v, steps = state_after(small_scene_dir, "nve/2d", commands)
    x_nve, v_nve, _ = state_after(small_scene_dir, "nve", commands)
    assert steps == 37
    assert np.array_equal(x, x_nve) and np.array_equal(v, v_nve)
    assert np.abs(v).max() > 1e-3  # it moves


def test_a_run_cut_short_leaves_no_kick_undone(small_scene_dir):
    """A run that a timeout ends after a deferred kick: fix nve/2d does the
    kick when the run ends (post_run), so the state is fix nve's after as
    many steps."""
    cut = ["timer timeout 00:00:01 every 1", "run 100000000"]
    x, v, steps = state_after(small_scene_dir, "nve/2d", cut)
    assert 0 < steps < 100000000
    x_nve, v_nve, _ = state_after(small_scene_dir, "nve", [f"run {steps}"])
    assert np.array_equal(x, x_nve) and np.array_equal(v, v_nve)


@pytest.mark.parametrize(
    ("command", "message"),
    [
        ("compute motion all motion/2d", "Compute motion/2d requires dimension 2"),
        ("fix move all nve/2d", "Fix nve/2d requires dimension 2"),
    ],
)
def test_a_2d_style_refuses_3d(tmp_path, command, message):
    """One line naming what it needs, a non-zero exit (lmp in a child: Debian's
    LAMMPS has no C++ exceptions)."""
    deck = tmp_path / "in.3d"
    deck.write_text(
        "units lj\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n"
        f"include decks/impact_2d.lmp\n{command}\nrun 0\n"
    )
    proc = subprocess.run(
        ["lmp", "-in", str(deck), "-log", "none"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=mpi_environment(),
    )
    assert proc.returncode != 0
    assert f"ERROR: {message}" in proc.stdout


def test_the_barrier_leaves_the_kick_deferred_and_the_impact_bit_for_bit(tmp_path):
    """The default body's 800-point impact (its area barrier, whose fix acts
    every step but reads no atom, so that fix nve/2d still defers its closing
    kicks): every row of the series and the energies, and the barrier's
    counts, as with LAMMPS's fix nve to the last bit."""
    from builder.assembly import build_scene
    from builder.lammps_data import write_scene
    from builder.scene import SceneSpec
    from runner.impact import run_scene
    from runner.options import RunOptions

    spec = SceneSpec(gamma_deg=30.0, seed=2)
    assert spec.area_floor > 0  # the default body carries the barrier
    results = []
    for style in ("nve", "nve/2d"):
        folder = write_scene(build_scene(spec), tmp_path / style.replace("/", ""))
        results.append(
            (folder, run_scene(folder, RunOptions().for_scene(spec), {"nve_style": style}))
        )
    (plain, first), (ours, second) = results
    for name in ("series.dat", "energy.dat"):
        assert filecmp.cmp(plain / name, ours / name, shallow=False)
    assert first["e"] == second["e"] and first["in_barrier_max"] == second["in_barrier_max"]
