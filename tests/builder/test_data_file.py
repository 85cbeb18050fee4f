"""The data file read back by LAMMPS and by MDAnalysis gives the builder's scene."""

from __future__ import annotations

import numpy as np
import pytest

from tests.helpers import new_lammps


@pytest.fixture(scope="module")
def lammps_scene(small_scene_dir):
    lmp = new_lammps()
    for command in [
        "units lj",
        "dimension 2",
        "boundary s s p",
        "atom_style bond",
        "special_bonds lj/coul 1.0 1.0 1.0",
        "bond_style class2",
        f"read_data {small_scene_dir}/scene.data",
        "pair_style zero 0.1",
        "pair_coeff * *",
        "compute bonds all bond/local dist engpot",
        "compute ends all property/local batom1 batom2 btype",
        # local computes run only when something asks for them
        "compute bonds_sum all reduce sum c_bonds[2]",
        "compute ends_max all reduce max c_ends[1]",
        "thermo_style custom step c_bonds_sum c_ends_max",
        "run 0",
    ]:
        lmp.command(command)
    yield lmp
    lmp.close()


def by_id(values, ids):
    out = np.empty_like(values)
    out[ids - 1] = values
    return out


@pytest.mark.lammps
def test_lammps_reads_the_atoms(lammps_scene, small_scene):
    lmp = lammps_scene
    n = lmp.get_natoms()
    assert n == len(small_scene.positions)
    x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3)
    v = np.ctypeslib.as_array(lmp.gather_atoms("v", 1, 3)).reshape(n, 3)
    types = np.ctypeslib.as_array(lmp.gather_atoms("type", 0, 1))
    molecule = np.ctypeslib.as_array(lmp.gather_atoms("molecule", 0, 1))
    assert np.array_equal(x[:, :2], small_scene.positions)  # exact: shortest round-trip text
    assert np.array_equal(v[:, :2], small_scene.velocities)
    assert np.array_equal(types, small_scene.types)
    assert np.array_equal(molecule, small_scene.molecule)


@pytest.mark.lammps
def test_lammps_reads_the_springs_at_their_natural_lengths(lammps_scene, small_scene):
    from lammps import LMP_STYLE_LOCAL, LMP_TYPE_ARRAY

    lmp = lammps_scene
    m = len(small_scene.springs)
    ends = lmp.numpy.extract_compute("ends", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY)
    bonds = lmp.numpy.extract_compute("bonds", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY)
    assert len(ends) == m
    pairs = np.sort(ends[:, :2].astype(int) - 1, axis=1)
    order = ends[:, 2].astype(int) - 1  # bond type = spring index
    assert np.array_equal(pairs, small_scene.springs[order])
    # every spring starts at exactly its natural length: zero energy, zero force
    assert np.array_equal(bonds[:, 0], small_scene.natural_lengths[order])
    assert np.all(bonds[:, 1] == 0.0)


@pytest.mark.lammps
def test_stress_free_start(lammps_scene, small_scene):
    n = len(small_scene.positions)
    f = np.ctypeslib.as_array(lammps_scene.gather_atoms("f", 1, 3)).reshape(n, 3)
    assert np.all(f == 0.0)


def test_mdanalysis_reads_the_same(small_scene_dir, small_scene):
    import MDAnalysis as mda

    u = mda.Universe(str(small_scene_dir / "scene.data"), atom_style="id resid type x y z")
    assert len(u.atoms) == len(small_scene.positions)
    assert np.array_equal(u.atoms.types.astype(int), small_scene.types)
    assert np.array_equal(u.atoms.resids, small_scene.molecule)
    assert np.all(u.atoms.masses == 1.0)
    # MDAnalysis keeps positions in float32
    assert np.allclose(u.atoms.positions[:, :2], small_scene.positions, atol=1e-6)
    assert np.all(u.atoms.positions[:, 2] == 0.0)
    expected = dict(zip(map(tuple, small_scene.springs.tolist()), small_scene.natural_lengths))
    pairs = list(map(tuple, np.sort(u.bonds.indices, axis=1).tolist()))
    assert len(pairs) == len(expected) and set(pairs) == set(expected)
    # float32 positions of size ~4 carry ~5e-7 of rounding each
    assert np.allclose(u.bonds.values(), [expected[p] for p in pairs], rtol=0, atol=2e-6)


def test_reference_reader_takes_both_spring_styles(small_scene, tmp_path):
    """harmonic K r0 is class2 r0 K2 K3 K4 with K3 = K4 = 0 (the stop rule and
    the reference read either)."""
    from builder.lammps_data import read_data, write_scene

    quartic = read_data(write_scene(small_scene, tmp_path / "class2", "class2") / "scene.data")
    harmonic = read_data(write_scene(small_scene, tmp_path / "harmonic", "harmonic") / "scene.data")
    assert np.array_equal(harmonic.r0, quartic.r0) and np.array_equal(harmonic.k2, quartic.k2)
    assert np.array_equal(harmonic.bonds, quartic.bonds) and np.array_equal(harmonic.x, quartic.x)
    assert np.all(harmonic.k4 == 0) and np.all(quartic.k4 > 0)
