"""The lattices and scenes the builder makes (MODEL.md section 1)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial import cKDTree

from builder import bodies
from builder.bodies import FIXED, SURFACE
from builder.errors import InputError
from builder.geometry import distance_to_polyline
from builder.scene import DISK, SceneSpec, build_scene

from tests.helpers import ROOT, SMALL


def make(lattice: str, seed: int = 3, n: int = 800):
    rng = np.random.default_rng(seed)
    return bodies.make_disk(rng, lattice, n)


def crossing_pairs(points: np.ndarray, springs: np.ndarray) -> list[tuple[int, int]]:
    """Pairs of springs that cross (sharing no end point)."""
    a, b = points[springs[:, 0]], points[springs[:, 1]]
    longest = np.linalg.norm(b - a, axis=1).max()
    pairs = np.array(sorted(cKDTree((a + b) / 2).query_pairs(longest)))
    i, j = pairs[:, 0], pairs[:, 1]
    shared = (springs[i][:, :, None] == springs[j][:, None, :]).any(axis=(1, 2))
    i, j = i[~shared], j[~shared]

    def side(p, q, r):
        return np.sign((q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]))

    cross = ((side(a[i], b[i], a[j]) * side(a[i], b[i], b[j]) < 0)
             & (side(a[j], b[j], a[i]) * side(a[j], b[j], b[i]) < 0))
    return list(zip(i[cross].tolist(), j[cross].tolist()))


@pytest.mark.parametrize("lattice", bodies.LATTICES)
def test_disk_network(lattice):
    disk = make(lattice)
    points, springs = disk.points, disk.springs
    nearest = cKDTree(points).query(points, 2)[0][:, 1]
    assert nearest.min() >= 0.7 * disk.spacing                      # no near-coincident points
    lengths = np.linalg.norm(points[springs[:, 0]] - points[springs[:, 1]], axis=1)
    at_surface = (disk.role[springs] == SURFACE).any(axis=1)
    assert lengths[~at_surface].max() <= 2.25 * disk.spacing
    assert lengths.max() <= bodies.MAX_SPRING * disk.spacing
    assert np.array_equal(np.unique(springs), np.arange(len(points)))  # every point bonded
    assert abs(len(points) - 800) < 0.05 * 800
    crossings = crossing_pairs(points, springs)
    if lattice == "square":
        # only the two diagonals of a complete cell cross: both k2, same midpoint
        assert crossings
        for i, j in crossings:
            assert disk.stiffness[i] < 1 and disk.stiffness[j] < 1
            assert np.allclose(points[springs[i]].mean(axis=0), points[springs[j]].mean(axis=0))
    else:
        assert crossings == []


def test_regular_interiors_are_the_lattices():
    triangular = make("triangular")
    interior = triangular.role != SURFACE
    both = interior[triangular.springs].all(axis=1)
    lengths = np.linalg.norm(np.diff(triangular.points[triangular.springs[both]], axis=1)[:, 0], axis=1)
    assert np.allclose(lengths[lengths < 1.01 * triangular.spacing], triangular.spacing)
    # six neighbours for points away from the band
    far = np.linalg.norm(triangular.points, axis=1) < 0.7
    degree = np.bincount(triangular.springs.ravel(), minlength=len(triangular.points))
    assert (degree[far & interior] == 6).all()

    square = make("square")
    degree = np.bincount(square.springs.ravel(), minlength=len(square.points))
    far = np.linalg.norm(square.points, axis=1) < 0.7
    assert (degree[far] == 8).all()                                 # 4 nearest + 4 diagonal
    k2 = square.stiffness < 1
    diagonal = np.linalg.norm(np.diff(square.points[square.springs[k2]], axis=1)[:, 0], axis=1)
    assert np.allclose(diagonal, np.sqrt(2) * square.spacing)


def test_surface_roughness_is_gaussian_along_the_normal():
    radii = np.concatenate([np.linalg.norm(make("random", seed=s).points[:90], axis=1)
                            for s in range(20)])
    # 20 disks x ~90 surface points: the sample std is within 5 percent of 0.03
    assert np.std(radii - 1.0) == pytest.approx(0.03, rel=0.05)
    assert abs(np.mean(radii - 1.0)) < 0.003


@pytest.mark.parametrize("fixed", ["sides", "sides+bottom", "all"])
def test_wall_fixed_points(fixed):
    wall = bodies.make_wall(np.random.default_rng(1), 1000, fixed=fixed)
    x, y = wall.points[:, 0], wall.points[:, 1]
    on_side = np.isclose(np.abs(x), 4.0)
    on_bottom = np.isclose(y, -2.0)
    assert wall.held[on_side].all()
    assert wall.held[on_bottom].all() == (fixed != "sides")
    assert wall.held.all() == (fixed == "all")
    if fixed == "sides":
        assert np.array_equal(wall.held, on_side)
    # the contact row keeps its role even when held
    assert (wall.role[wall.surface[1:-1]] == SURFACE).all()
    assert (wall.role[on_side] == FIXED).all()


def test_scene_placement(small_scene):
    info = small_scene.info
    disk = small_scene.molecule == DISK
    surface = small_scene.types == 1
    row = small_scene.positions[:info["wall_row_tags"][1]]
    gap = distance_to_polyline(small_scene.positions[surface], row).min()
    cutoff = info["contact"]["cutoff"]
    assert cutoff < gap <= cutoff * (1 + small_scene.spec.start_gap) * (1 + 1e-6)
    v = small_scene.velocities
    vn, gamma = small_scene.spec.vn, np.radians(small_scene.spec.gamma_deg)
    assert np.all(v[disk] == [vn * np.tan(gamma), -vn])
    assert np.all(v[~disk] == 0.0)
    # natural lengths are those of the written positions: a stress-free start
    assert np.all(small_scene.natural_lengths > 0)


def test_same_seed_same_files(tmp_path):
    def build(folder, seed):
        subprocess.run([sys.executable, "-m", "builder", "scene", "--n-disk", "200", "--seed", str(seed),
                        "--gamma", "30", "--out", str(folder)], cwd=ROOT, check=True, capture_output=True)
        return {name: (folder / name).read_bytes() for name in ("scene.data", "scene.lmp", "scene.json")}

    first = build(tmp_path / "a", 7)
    again = build(tmp_path / "b", 7)
    other = build(tmp_path / "c", 8)
    assert first == again
    assert first["scene.data"] != other["scene.data"]


@pytest.mark.parametrize("field, value, words", [
    ("radius", -1.0, "radius must be > 0"),
    ("n_disk", -5, "n_disk must be an integer >= 50"),
    ("gamma_deg", 90.0, "gamma_deg must be in [0, 90)"),
    ("lattice", "hexagonal", "lattice must be one of random, triangular, square"),
    ("vn", 1.5, "vn must be in (0, 1)"),
    ("wall_fixed", "top", "wall_fixed must be one of"),
    ("contact_a", 50.0, "contact_a must be >= "),
])
def test_bad_spec(field, value, words):
    with pytest.raises(InputError, match=words.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
        build_scene(SceneSpec(**{**SMALL, field: value}))


@pytest.mark.parametrize("args, words", [
    (["--radius", "-1"], "argument --radius: must be > 0"),
    (["--n-disk", "-5"], "argument --n-disk: must be an integer >= 50"),
    (["--gamma", "0"], "argument --gamma: must be in (0, 90) degrees"),
    (["--gamma", "95"], "argument --gamma: must be in (0, 90) degrees"),
    (["--lattice", "hexagonal"], "argument --lattice: invalid choice"),
    (["--n-disk", "200", "--contact-a", "50"], "contact_a must be >= "),
])
def test_builder_cli_rejects_bad_input(tmp_path, args, words):
    out = tmp_path / "scene"
    proc = subprocess.run([sys.executable, "-m", "builder", "scene", *args, "--out", str(out)],
                          cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 2
    assert words in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists()
