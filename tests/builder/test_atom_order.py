"""The interiors' binned order beyond SAMPLE_ORDER_UP_TO disk points: a
permutation in LAMMPS's bin order that leaves the scene, and its impact,
the same body."""

from __future__ import annotations

import numpy as np
import pytest

import builder.assembly as assembly
from builder.assembly import binned_order, build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from runner.impact import run_scene
from runner.options import RunOptions
from tests.helpers import SMALL


def test_binned_order_is_a_permutation_in_bin_rows():
    rng = np.random.default_rng(3)
    points = rng.uniform(-1.0, 1.0, (500, 2))
    indices = rng.permutation(500)[:400]
    order = binned_order(points, indices, 0.3)
    assert sorted(order) == sorted(indices)
    cell = np.floor(points[order] / 0.3).astype(int)
    key = cell[:, 1] * 1000 + cell[:, 0]  # bin rows bottom to top, each left to right
    assert np.all(np.diff(key) >= 0)
    # within a bin the given order stays
    for k in np.unique(key):
        inside = order[key == k]
        assert list(inside) == [i for i in indices if i in set(inside)]


def as_sets(scene):
    """The atoms (position, type, molecule), springs (their two atoms' positions
    and constant) and the barrier's triangles, independent of the atoms' order."""
    atoms = {(*map(float, p), int(t), int(m)) for p, t, m in
             zip(scene.positions, scene.types, scene.molecule)}  # fmt: skip
    springs = {
        (frozenset(map(tuple, scene.positions[pair].tolist())), float(k))
        for pair, k in zip(scene.springs, scene.ka)
    }
    triangles = {
        frozenset(map(tuple, scene.positions[triple].tolist())) for triple in scene.angles.atoms
    }
    return atoms, springs, triangles


@pytest.fixture(scope="module")
def both_orders():
    spec = SceneSpec(**{**SMALL, "gamma_deg": 30.0, "roughness": 0.0, "area_floor": 0.5})
    sampled = build_scene(spec)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(assembly, "SAMPLE_ORDER_UP_TO", 0)
        binned = build_scene(spec)
    return sampled, binned


def test_the_binned_scene_is_the_same_body(both_orders):
    sampled, binned = both_orders
    assert not np.array_equal(sampled.positions, binned.positions)  # the order did change
    assert as_sets(sampled) == as_sets(binned)
    # the contact rows keep their place: the wall's surface row and the disk's
    # surface ring lead their bodies, in the same order
    n_row = sampled.info["wall_row_tags"][1]
    assert n_row > 0 and np.array_equal(sampled.positions[:n_row], binned.positions[:n_row])
    assert sampled.info.keys() == binned.info.keys()
    assert binned.info["disk_inertia"] == pytest.approx(sampled.info["disk_inertia"], rel=1e-14)


@pytest.mark.lammps
def test_the_binned_scene_rebounds_alike(tmp_path, both_orders):
    # A smooth contact: the sums' other order changes the last bits only, and
    # nothing chaotic amplifies them.
    results = [
        run_scene(write_scene(scene, tmp_path / name), RunOptions())
        for name, scene in zip(("sampled", "binned"), both_orders)
    ]
    for key in ("e", "beta", "omega"):
        assert results[1][key] == pytest.approx(results[0][key], rel=1e-9, abs=1e-12)
    assert results[1]["steps"] == results[0]["steps"]
