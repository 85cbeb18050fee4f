"""The Poisson-disk cache gives the same bodies, byte for byte, as drawing them."""

from __future__ import annotations

import numpy as np
import pytest

from builder import assembly, bodies, sample
from builder.lammps_data import write_scene
from builder.sample_cache import cache_folder
from builder.scene import SceneSpec

SPEC = SceneSpec(seed=5, gamma_deg=30.0, n_disk=200)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "poisson"
    monkeypatch.setenv("IMPACT_POISSON_CACHE", str(folder))
    return folder


def scene_bytes(folder) -> bytes:
    # the bodies of a process's last samples are kept in memory too: draw them here
    sample._disk.cache_clear()
    sample._wall.cache_clear()
    write_scene(assembly.build_scene(SPEC), folder, "harmonic/quartic")
    return (folder / "scene.data").read_bytes()


def test_a_scene_is_the_same_drawn_cached_or_uncached(cache, tmp_path, monkeypatch):
    cold = scene_bytes(tmp_path / "cold")
    assert len(list(cache.glob("*.npz"))) == 2  # the disk's interior and the wall's
    stamps = {p: p.stat().st_mtime_ns for p in cache.glob("*.npz")}
    warm = scene_bytes(tmp_path / "warm")
    assert {p: p.stat().st_mtime_ns for p in cache.glob("*.npz")} == stamps  # read, not drawn
    monkeypatch.setenv("IMPACT_POISSON_CACHE", "off")
    assert cache_folder() is None
    drawn = scene_bytes(tmp_path / "drawn")
    assert cold == warm == drawn


def test_a_cached_draw_leaves_the_generator_where_the_draw_would(cache):
    def after(rng):
        points = bodies.poisson_points(rng, 0.2, [-1.0, -1.0], [1.0, 1.0])
        return points, rng.standard_normal(4)

    first = after(np.random.default_rng(11))
    again = after(np.random.default_rng(11))  # from the cache
    assert len(list(cache.glob("*.npz"))) == 1
    np.testing.assert_array_equal(first[0], again[0])
    np.testing.assert_array_equal(first[1], again[1])
    other = after(np.random.default_rng(12))  # another state: another sample
    assert len(list(cache.glob("*.npz"))) == 2
    assert len(other[0]) != len(first[0]) or not np.array_equal(other[0], first[0])


def test_an_unreadable_cache_file_is_drawn_again(cache):
    points = bodies.poisson_points(np.random.default_rng(3), 0.2, [0.0, 0.0], [1.0, 1.0])
    (path,) = cache.glob("*.npz")
    path.write_bytes(b"not a numpy file")
    again = bodies.poisson_points(np.random.default_rng(3), 0.2, [0.0, 0.0], [1.0, 1.0])
    np.testing.assert_array_equal(points, again)
    with np.load(path) as stored:  # replaced by a good one
        np.testing.assert_array_equal(stored["points"], points)
