"""The reference's area barrier (reference.forces.area_barrier), written apart
from the LAMMPS style (potentials/angle_area_barrier.cpp): the data file's
triangles are the builder's; the energy is docs/model.md's formula, zero at
and above J_c; the forces are minus its gradient (finite differences); LAMMPS
gives the same forces and energies on a squeezed scene; and on the default
body, where triangles enter the barrier, LAMMPS and the reference's velocity
Verlet at the same step give the same impact, where the reference without
the barrier does not."""

from __future__ import annotations

import ctypes
from dataclasses import replace

import numpy as np
import pytest

from bench.validation import compare
from builder.assembly import build_scene
from builder.lammps_data import read_data, write_scene
from builder.scene import SceneSpec
from reference.forces import TurnedOver, area_barrier
from reference.run import DISK, Observer, ReferenceOptions, load_model
from reference.validate import body_scenes, reference_run
from runner.options import RunOptions
from tests.helpers import ROOT, new_lammps

K, A0, JC = 2.0, 0.5, 0.5
BARRIER_LIBRARY = ROOT / "build" / "libarea_barrier.so"
SPRINGS_LIBRARY = ROOT / "build" / "libharmonic_quartic.so"
# The default body (builder.scene.BODY) at 200 points: the middle angle for
# the static checks, the grazing one for the impact, where two triangles
# enter the barrier (fix area/barrier's count) at the default speed.
STATIC = SceneSpec(n_disk=200, gamma_deg=45.0)
IMPACT = "body_random_g80.4"


def formula(j: float, jc: float = JC) -> float:
    """docs/model.md: E = k A0 [J_c / J - 1 + ln(J / J_c)] below J_c, 0 above."""
    return K * A0 * (jc / j - 1.0 + np.log(j / jc)) if j < jc else 0.0


def at(j: float) -> np.ndarray:
    """Three points, counter-clockwise, whose area is J A0: (0.2, q), (1, 0),
    (0.3, 1) have area (0.8 - 0.7 q) / 2, turned by 0.4 rad and moved."""
    points = np.array([[0.2, (0.8 - j) / 0.7], [1.0, 0.0], [0.3, 1.0]])
    turn = np.array([[np.cos(0.4), -np.sin(0.4)], [np.sin(0.4), np.cos(0.4)]])
    return points @ turn.T + np.array([0.37, -0.11])


def one(points: np.ndarray, order=(0, 1, 2), jc: float = JC):
    return area_barrier(points, np.array([order]), np.array([A0]), np.array([K]), np.array([jc]))


@pytest.fixture(scope="module")
def body(tmp_path_factory):
    """The default body's scene folder and its System."""
    folder = write_scene(build_scene(STATIC), tmp_path_factory.mktemp("body"))
    return folder, read_data(folder / "scene.data")


def squeezed(system, factor: float = 0.42, noise: float = 0.004, seed: int = 3) -> np.ndarray:
    """Every point's y times ``factor`` (each triangle's J too), then moved
    by up to ``noise`` R: every triangle of both bodies inside the barrier,
    at J from about 0.3 to 0.55."""
    rng = np.random.default_rng(seed)
    return system.x * np.array([1.0, factor]) + noise * (2.0 * rng.random(system.x.shape) - 1.0)


def test_the_data_file_holds_the_builders_triangles(body, tmp_path):
    """read_data gives each angle's atoms as builder.triangles made them and
    its type's A0, k, J_c; a scene without the barrier has none."""
    folder, system = body
    scene = build_scene(STATIC)
    angles = scene.angles
    assert len(angles.atoms) > 1000
    assert np.array_equal(system.angles, angles.atoms)
    for column, name in enumerate(("a0", "k_area", "jc")):
        assert np.array_equal(getattr(system, name), angles.coefficients[angles.types - 1, column])
    assert np.all(system.jc == 0.5)
    plain = write_scene(build_scene(replace(STATIC, area_floor=0.0)), tmp_path / "plain")
    assert read_data(plain / "scene.data").angles.shape == (0, 3)


@pytest.mark.parametrize("j", [0.05, 0.3, 0.499, 0.501, 0.7, 1.0])
def test_energy_is_the_formula(j):
    found = one(at(j))
    assert found.ratio[0] == pytest.approx(j, rel=1e-12)
    assert found.energy == pytest.approx(formula(j), rel=1e-12, abs=1e-15)
    if j >= JC:
        assert np.all(found.force == 0.0)


def test_energy_at_half_the_floor_in_closed_form():
    """J = J_c / 2: k A0 (2 - 1 + ln(1/2)) = k A0 (1 - ln 2)."""
    assert one(at(JC / 2)).energy == pytest.approx(K * A0 * (1.0 - np.log(2.0)), rel=1e-12)


def test_the_area_is_signed_counter_clockwise():
    """The builder lists a triangle counter-clockwise at rest (J = +1); listed
    clockwise it is turned over, which stops a run with J_c > 0 and counts
    nothing with J_c = 0 (as the LAMMPS style does)."""
    assert one(at(1.0)).ratio[0] == pytest.approx(1.0)
    with pytest.raises(TurnedOver, match=r"turned over \(J = -1"):
        one(at(1.0), order=(0, 2, 1))
    flat = one(at(1.0), order=(0, 2, 1), jc=0.0)
    assert flat.energy == 0.0 and np.all(flat.force == 0.0)


def test_the_force_vanishes_at_the_floor():
    """C1 at J_c: the force falls to zero in proportion to J_c - J."""
    small = [np.abs(one(at(JC - d)).force).max() for d in (1e-3, 1e-4)]
    assert small[0] > 0.0
    assert small[1] / small[0] == pytest.approx(0.1, rel=1e-2)


def test_forces_are_minus_the_gradient_of_the_energy(body):
    """Central differences of the whole barrier's energy in both coordinates
    of the atoms with the largest forces and of others at random; no net
    force and no torque."""
    _, s = body
    x = squeezed(s)
    found = area_barrier(x, s.angles, s.a0, s.k_area, s.jc)
    assert found.ratio.min() > 0.25 and np.all(found.ratio < s.jc)  # all inside, none turned
    size = np.linalg.norm(found.force, axis=1)
    atoms = np.concatenate([np.argsort(size)[-8:], np.random.default_rng(0).choice(len(x), 8)])
    step = 1e-7
    for atom in atoms:
        # only the atom's own triangles change: their sum, for less round-off
        own = np.any(s.angles == atom, axis=1)
        for axis in range(2):
            energies = []
            for sign in (1.0, -1.0):
                moved = x.copy()
                moved[atom, axis] += sign * step
                each = area_barrier(moved, s.angles, s.a0, s.k_area, s.jc).each
                energies.append(each[own].sum())
            numeric = -(energies[0] - energies[1]) / (2.0 * step)
            assert found.force[atom, axis] == pytest.approx(numeric, rel=1e-6, abs=1e-9)
    assert size.max() > 0.1
    scale = size.max() * np.abs(x).max()
    assert np.abs(found.force.sum(axis=0)).max() < 1e-12 * size.max() * len(x)
    centre = x - x.mean(axis=0)
    torque = np.sum(centre[:, 0] * found.force[:, 1] - centre[:, 1] * found.force[:, 0])
    assert abs(torque) < 1e-12 * scale * len(x)


def lammps_state(folder, x: np.ndarray):
    """LAMMPS on the scene's data file (springs and angles, as decks/setup.lmp
    reads it) at positions ``x``: per-atom forces, the angles' energy, and
    the potential energy (bonds and angles) of the disk and of the wall."""
    lmp = new_lammps()
    ctypes.CDLL(str(BARRIER_LIBRARY)).area_barrier_register(lmp.lmp)
    ctypes.CDLL(str(SPRINGS_LIBRARY)).harmonic_quartic_register(lmp.lmp)
    for command in [
        "units lj",
        "dimension 2",
        "boundary s s p",
        "atom_style angle",
        "special_bonds lj/coul 1.0 1.0 1.0",
        "bond_style harmonic/quartic",
        "angle_style area/barrier",
        "pair_style zero 1.0",
        f"read_data {folder}/scene.data",
        "pair_coeff * *",
        "group disk molecule 1",
        "group wall molecule 2 3",
        "compute angles all pe angle",
        "compute pe_atom all pe/atom bond angle",
        "compute pe_disk disk reduce sum c_pe_atom",
        "compute pe_wall wall reduce sum c_pe_atom",
        "thermo_style custom step c_angles c_pe_disk c_pe_wall",
        "thermo_modify norm no",
    ]:
        lmp.command(command)
    n = len(x)
    flat = np.column_stack([x, np.zeros(n)]).ravel()
    lmp.scatter_atoms("x", 1, 3, (ctypes.c_double * (3 * n))(*flat))
    lmp.command("run 0")
    forces = np.ctypeslib.as_array(lmp.gather_atoms("f", 1, 3)).reshape(-1, 3)[:, :2].copy()
    energies = [lmp.extract_compute(name, 0, 0) for name in ("angles", "pe_disk", "pe_wall")]
    lmp.close()
    return forces, *energies


@pytest.mark.lammps
def test_lammps_gives_the_references_forces_and_energies(body):
    """Every triangle of both bodies inside the barrier: LAMMPS's forces
    (springs and angles) equal the reference's to 1e-12 of the largest, the
    angles' energy to 1e-12, and each body's potential energy (energy.dat's
    pe_disk, pe_wall) too."""
    folder, _ = body
    model = load_model(folder, ReferenceOptions())
    s = model.system
    x = squeezed(s)
    forces, e_angles, pe_disk, pe_wall = lammps_state(folder, x)
    ours, _ = model.internal_forces(x)
    barrier, e_barrier = model.barrier_forces(x)
    assert model.in_barrier_max == len(s.angles)  # every triangle inside
    assert np.abs(barrier).max() > 1e-3 * np.abs(ours).max()  # the barrier's share counts
    assert np.abs(forces - ours).max() < 1e-12 * np.abs(ours).max()
    assert e_barrier == pytest.approx(e_angles, rel=1e-12)
    row = Observer(model).energies(0.0, x, np.zeros_like(x), 0.0).split()
    assert float(row[2]) == pytest.approx(pe_disk, rel=1e-12)
    assert float(row[4]) == pytest.approx(pe_wall, rel=1e-12)
    in_disk = s.molecule[s.angles[:, 0]] == DISK
    assert 0 < in_disk.sum() < len(in_disk)  # both bodies have triangles


@pytest.mark.lammps
@pytest.mark.slow
def test_lammps_and_reference_verlet_agree_on_the_default_body(tmp_path):
    """The default body at 200 points sliding at 80.4 degrees (make
    validate's body_random_g80.4, smaller): LAMMPS at its default step and
    the reference's velocity Verlet at the same step agree on e, beta, the
    disk's motion during contact and the barrier's counts to round-off
    grown by the contact (1e-10); the reference without the barrier
    misses e or beta by far more."""
    spec = body_scenes(n_disk=200)[IMPACT]
    options = RunOptions().for_scene(spec)
    twin = ReferenceOptions(
        integrator="verlet", dt=options.dt, every=options.every_steps, check=options.check_steps
    )
    reference = reference_run(spec, tmp_path / "reference_verlet", twin)
    row = compare(
        spec, tmp_path / "lammps", options, reference, tmp_path / "reference_verlet", True
    )
    assert row["dt"] == options.dt  # no halving: the twin ran at LAMMPS's step
    assert row["in_barrier_max"] > 0  # fix area/barrier: triangles entered the barrier
    assert abs(row["de"]) < 1e-10 and abs(row["dbeta"]) < 1e-10
    for key in ("position", "velocity", "omega"):
        assert row[key] < 1e-10, key
    assert row["in_barrier_max_ref"] == row["in_barrier_max"]
    assert row["area_ratio_min_ref"] == pytest.approx(row["area_ratio_min"], rel=1e-10)
    assert row["area_ratio_min"] < 0.5
    assert reference["energy_drift"] == pytest.approx(row["energy_drift"], abs=1e-10)
    without = reference_run(spec, tmp_path / "no_barrier", replace(twin, barrier=False))
    assert max(abs(without["e"] - row["e"]), abs(without["beta"] - row["beta"])) > 1e-6
