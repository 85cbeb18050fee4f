"""Angle style area/barrier and fix area/barrier (potentials/): the energy
is the formula, zero and flat at J_c; the forces are its gradient (finite
differences); a triangle driven into the barrier conserves energy, momentum
and angular momentum; one rank and two agree on a scene; bad coefficients
are refused."""

from __future__ import annotations

import ctypes
import subprocess

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.launch import mpi_environment, mpi_launcher
from tests.helpers import PAPER, ROOT, new_lammps

pytestmark = pytest.mark.lammps

LIBRARY = ROOT / "build" / "libarea_barrier.so"
SPRINGS = ROOT / "build" / "libharmonic_quartic.so"
DECK = ROOT / "tests" / "decks" / "barrier_forces.lmp"
A0, K, JC = 0.5, 2.0, 0.5


def formula(j: float, jc: float = JC) -> float:
    """E = k A0 [Jc / J - 1 + ln(J / Jc)] below Jc, 0 above."""
    return K * A0 * (jc / j - 1.0 + np.log(j / jc)) if j < jc else 0.0


def at(j: float) -> np.ndarray:
    """Three points, counter-clockwise, whose area is J A0: (0.2, q), (1, 0),
    (0.3, 1) have area (0.8 - 0.7 q) / 2, turned by 0.4 rad off the axes."""
    points = np.array([[0.2, (0.8 - j) / 0.7], [1.0, 0.0], [0.3, 1.0]])
    turn = np.array([[np.cos(0.4), -np.sin(0.4)], [np.sin(0.4), np.cos(0.4)]])
    return points @ turn.T + np.array([0.37, -0.11])


def triangle(points: np.ndarray, jc: float = JC, springs: bool = False):
    """A LAMMPS instance with one angle on three atoms at ``points`` (after
    run 0); with ``springs``, harmonic/quartic springs on its edges too."""
    lmp = new_lammps()
    ctypes.CDLL(str(LIBRARY)).area_barrier_register(lmp.lmp)
    ctypes.CDLL(str(SPRINGS)).harmonic_quartic_register(lmp.lmp)
    commands = [
        "dimension 2",
        "units lj",
        "atom_style angle",
        "boundary f f p",
        "region box block -10 10 -10 10 -1 1",
        "create_box 1 box bond/types 1 angle/types 1 extra/bond/per/atom 2 "
        "extra/angle/per/atom 1 extra/special/per/atom 4",
        "mass 1 1.0",
        *(f"create_atoms 1 single {x!r} {y!r} 0" for x, y in points.tolist()),
        "angle_style area/barrier",
        f"angle_coeff 1 {A0} {K} {jc}",
        "create_bonds single/angle 1 1 2 3",
        "bond_style harmonic/quartic",
        "bond_coeff 1 1.0 5.0 0.0",
        *(
            [f"create_bonds single/bond 1 {i} {j}" for i, j in ((1, 2), (2, 3), (3, 1))]
            if springs
            else []
        ),
        "special_bonds lj/coul 1.0 1.0 1.0",
        "pair_style zero 1.0",
        "pair_coeff * *",
        "compute e all pe angle",
        "fix b all area/barrier",
        "thermo_style custom step c_e f_b[1] f_b[2]",
        "thermo_modify norm no",
        "run 0",
    ]
    for command in commands:
        lmp.command(command)
    return lmp


def forces(lmp) -> np.ndarray:
    return np.ctypeslib.as_array(lmp.gather_atoms("f", 1, 3)).reshape(-1, 3)


@pytest.mark.parametrize("j", [0.05, 0.3, 0.499, 0.501, 0.7, 1.0])
def test_energy_is_the_formula_and_the_fix_counts_it(j):
    lmp = triangle(at(j))
    assert lmp.extract_compute("e", 0, 0) == pytest.approx(formula(j), rel=1e-12, abs=1e-15)
    assert lmp.extract_fix("b", 0, 1, 0) == (1.0 if j < JC else 0.0)  # the most inside at once
    assert lmp.extract_fix("b", 0, 1, 1) == pytest.approx(j, rel=1e-12)  # the smallest J
    if j >= JC:
        assert np.all(forces(lmp) == 0.0)
    lmp.close()


@pytest.mark.parametrize("j", [0.02, 0.1, 0.3, 0.45])
def test_forces_are_the_gradient_of_the_energy(j):
    """Central differences of the energy in every coordinate of every atom,
    and no net force: the forces are -dE/dx, and they sum to zero."""
    points = at(j)
    lmp = triangle(points)
    f = forces(lmp)
    lmp.close()
    step = 1e-6 * j
    numeric = np.zeros((3, 2))
    for atom in range(3):
        for axis in range(2):
            values = []
            for sign in (1.0, -1.0):
                shifted = points.copy()
                shifted[atom, axis] += sign * step
                other = triangle(shifted)
                values.append(other.extract_compute("e", 0, 0))
                other.close()
            numeric[atom, axis] = -(values[0] - values[1]) / (2.0 * step)
    assert np.abs(f[:, :2]).max() > 0.1
    assert np.allclose(f[:, :2], numeric, rtol=1e-6, atol=1e-8 * np.abs(numeric).max())
    assert np.all(f[:, 2] == 0.0)
    assert np.abs(f.sum(axis=0)).max() < 1e-12 * np.abs(f).max()


def test_force_vanishes_at_the_floor():
    """C1 at J_c: the force falls to zero as J rises to J_c, in proportion to J_c - J."""
    small = [np.abs(forces(triangle(at(JC - d))))[:, :2].max() for d in (1e-3, 1e-4)]
    assert small[0] > 0.0
    assert small[1] / small[0] == pytest.approx(0.1, rel=1e-2)


def test_a_triangle_driven_into_the_barrier_conserves_energy_and_momenta():
    """Springs on the edges and the barrier; the first atom thrown at the
    opposite edge fast enough to pass J_c without the barrier. Velocity
    Verlet at a small step: the total energy stays within 1e-6 of the kinetic
    energy given; momentum and angular momentum stay put to round-off."""
    lmp = triangle(at(1.0), springs=True)
    lmp.command("velocity all set 0 0 0")
    # the first atom towards the centroid, the others to cancel its momentum
    lmp.command("group one id 1")
    lmp.command("group rest id 2 3")
    lmp.command("velocity one set -0.8 2.6 0 units box")
    lmp.command("velocity rest set 0.4 -1.3 0 units box")
    lmp.command("compute ke all ke")
    lmp.command("compute pe all pe")
    lmp.command("variable etot equal c_ke+c_pe")
    lmp.command("variable px equal vcm(all,x)")
    lmp.command("variable py equal vcm(all,y)")
    lmp.command("variable lz equal angmom(all,z)")
    lmp.command("fix move all nve")
    lmp.command("timestep 1e-5")
    lmp.command("thermo_style custom step v_etot v_px v_py v_lz c_e f_b[1] f_b[2]")
    lmp.command("run 0")
    start = [lmp.extract_variable(v, None, 0) for v in ("etot", "px", "py", "lz")]
    ke = lmp.extract_compute("ke", 0, 0)
    lowest, largest_barrier, drift = 1.0, 0.0, 0.0
    for _ in range(40):
        lmp.command("run 2000 post no")
        now = [lmp.extract_variable(v, None, 0) for v in ("etot", "px", "py", "lz")]
        drift = max(drift, abs(now[0] - start[0]))
        assert now[1:] == pytest.approx(start[1:], abs=1e-12)
        largest_barrier = max(largest_barrier, lmp.extract_compute("e", 0, 0))
        lowest = min(lowest, lmp.extract_fix("b", 0, 1, 1))
    lmp.close()
    assert lowest < 0.2  # deep in the barrier (J_c = 0.5)
    assert largest_barrier > 0.1 * ke  # which held a good part of the energy
    assert drift < 1e-6 * ke


def barrier_scene(folder):
    """A scene with the barrier at J_c 0.9, so that barrier_state's displaced
    state puts hundreds of triangles inside it."""
    return write_scene(
        build_scene(SceneSpec(**{**PAPER, "gamma_deg": 30.0, "n_wall": 800, "area_floor": 0.9})),
        folder,
    )


def barrier_state(tmp_path, scene, nprocs=1, newton="on", command=None, env=None, extra=()):
    """tests/decks/barrier_forces.lmp: (angle energy, virial xx yy xy, the
    fix's most inside and smallest J), per atom (fx fy fz pe) by ID."""
    out = tmp_path / f"forces_{nprocs}_{newton}_{len(list(tmp_path.iterdir()))}.dump"
    args = ["-in", str(DECK), "-log", f"{out}.log", "-screen", "none", "-nocite"]
    args += ["-var", "scene", str(scene), "-var", "out", str(out)]
    args += ["-var", "newton", newton, "-var", "amp", "0.015", *extra]
    proc = subprocess.run(
        mpi_launcher(nprocs) + (command or ["lmp"]) + args,
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**mpi_environment(), **(env or {})},
    )
    assert proc.returncode == 0, proc.stdout[-2000:]
    glob = np.array((tmp_path / f"{out.name}.global").read_text().split(), float)
    return glob, np.loadtxt(out, skiprows=9)[:, 1:]


@pytest.mark.mpi
def test_two_ranks_give_the_forces_of_one(tmp_path):
    """The scene split over two ranks, newton_bond on and off: the same
    forces, energies, virial and counts. The barrier's virial is a
    pressure: xx = yy, xy = 0 (a shear keeps every area)."""
    scene = barrier_scene(tmp_path / "scene")
    one = barrier_state(tmp_path, scene)
    assert one[0][4] > 100 and 0.0 < one[0][5] < 0.9  # inside the barrier, none turned
    assert one[0][1] == pytest.approx(one[0][2], rel=1e-12)
    assert abs(one[0][3]) < 1e-12 * one[0][1]
    for newton in ("on", "off"):
        two = barrier_state(tmp_path, scene, 2, newton)
        assert np.allclose(two[1], one[1], rtol=0.0, atol=1e-12 * np.abs(one[1]).max())
        assert np.allclose(two[0], one[0], rtol=1e-12, atol=1e-12 * abs(one[0][1]))


@pytest.mark.parametrize(
    "coeff, message",
    [
        ("angle_coeff 1 0.5 2.0", r"expects N A0 k Jc, got 3 values"),
        ("angle_coeff 1 0.0 2.0 0.5", r"A0 must be > 0, got 0"),
        ("angle_coeff 1 0.5 -2.0 0.5", r"k must be >= 0, got -2"),
        ("angle_coeff 1 0.5 2.0 1.0", r"Jc must be in \[0, 1\), got 1"),
    ],
)
def test_bad_coefficients_are_refused(tmp_path, coeff, message):
    """A one-line error naming the coefficient (errors end the process: lmp, not the module)."""
    deck = tmp_path / "in.lmp"
    deck.write_text(
        "\n".join(
            [
                "variable area_barrier_lib index " + str(LIBRARY),
                "include decks/area_barrier.lmp",
                "units lj",
                "dimension 2",
                "atom_style angle",
                "region box block -1 1 -1 1 -0.5 0.5",
                "create_box 1 box angle/types 1 extra/angle/per/atom 1",
                "angle_style area/barrier",
                coeff,
                "",
            ]
        )
    )
    proc = subprocess.run(
        ["lmp", "-in", str(deck), "-log", "none", "-nocite"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=mpi_environment(),
    )
    errors = [line for line in proc.stdout.splitlines() if line.startswith("ERROR")]
    assert proc.returncode != 0 and len(errors) == 1
    assert __import__("re").search(message, errors[0]), errors[0]


@pytest.mark.mpi
def test_an_impact_with_the_barrier_flags_its_triangles_on_one_rank_and_two(tmp_path):
    """The rough impact of docs/rough_contact.md at 800 points with J_c 0.5:
    result.json counts the triangles that entered the barrier and the
    smallest J (fix area/barrier, every step); two ranks give the same run
    to round-off; without the barrier the result has neither field."""
    from dataclasses import replace

    from runner.impact import run_impact
    from runner.options import RunOptions

    rough = {"roughness_length": 0.2, "roughness_profile": "continuous"}
    spec = SceneSpec(area_floor=0.5, contact_scaling="physical", **rough)
    results = [
        run_impact(spec, tmp_path / f"np{n}", replace(RunOptions(), nprocs=n).for_scene(spec))
        for n in (1, 2)
    ]
    for result in results:
        assert result["in_barrier_max"] >= 1 and 0.0 < result["area_ratio_min"] < 0.5
    assert results[1]["e"] == pytest.approx(results[0]["e"], rel=1e-9)
    assert results[1]["in_barrier_max"] == results[0]["in_barrier_max"]
    assert abs(results[0]["energy_drift"]) < 1e-4  # the barrier's energy is in the balance
    plain = replace(spec, area_floor=0.0)
    result = run_impact(plain, tmp_path / "plain", RunOptions().for_scene(plain))
    assert "in_barrier_max" not in result and "area_ratio_min" not in result
