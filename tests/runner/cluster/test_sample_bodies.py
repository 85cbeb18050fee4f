"""A sample's bodies, written once and placed by the deck, against the placed
scene.data of each impact."""

from __future__ import annotations

import filecmp

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.lammps_data import data_file_text, write_bodies, write_scene
from builder.placement import placement_quantum
from builder.scene import DISK, SceneSpec
from ground.errors import InputError
from ground.launch import data_to_restart
from runner.impact import run_scene
from runner.options import RunOptions
from runner.study.sample_bodies import BODIES_FOLDER, SampleBodies
from tests.helpers import SMALL, SMALL_DISK


@pytest.mark.parametrize("radius", [1.0, 0.3, 7.0])
def test_the_disk_is_placed_exactly(radius):
    """Frame points and the centre lie on one binary grid: placing and
    unplacing are exact, so every spring has one length in both frames."""
    scene = build_scene(SceneSpec(gamma_deg=60.0, radius=radius, **SMALL))
    quantum = placement_quantum(radius)
    disk = scene.molecule == DISK
    frame = scene.frame_positions
    assert np.array_equal(np.round(frame[disk] / quantum) * quantum, frame[disk])
    assert np.array_equal(frame[disk] + scene.disk_centre, scene.positions[disk])
    assert np.array_equal(frame[~disk], scene.positions[~disk])
    d = frame[scene.springs[:, 0]] - frame[scene.springs[:, 1]]
    assert np.array_equal(np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2), scene.natural_lengths)


def test_one_sample_has_one_bodies_file():
    """Angles and speeds change only the placement: the bodies' text is the same."""
    texts = {
        data_file_text(build_scene(SceneSpec(gamma_deg=g, vn=vn, **SMALL)), placed=False)
        for g, vn in ((10.0, 0.1), (45.0, 0.1), (80.0, 0.05))
    }
    assert len(texts) == 1
    other_seed = build_scene(SceneSpec(gamma_deg=10.0, seed=2, **SMALL))
    assert data_file_text(other_seed, placed=False) not in texts


@pytest.mark.lammps
@pytest.mark.parametrize(
    ("lattice", "gamma", "target"),
    [
        ("random", 20.0, "wall"),
        ("triangular", 60.0, "wall"),
        ("square", 75.0, "wall"),
        ("random", 45.0, "disk"),
    ],
)
def test_bodies_and_placed_scene_run_bit_for_bit(tmp_path, lattice, gamma, target):
    """The deck placing the sample's bodies, read from their data file or its
    binary restart, runs the same impact, bit for bit, as the impact's own
    placed data file: series.dat, energy.dat, e, beta; for two disks too (the
    deck sets the second disk's velocity)."""
    small = SMALL if target == "wall" else SMALL_DISK
    scene = build_scene(SceneSpec(lattice=lattice, gamma_deg=gamma, target=target, **small))
    placed = write_scene(scene, tmp_path / "placed")
    bodies = write_bodies(scene, tmp_path / "bodies.data")
    restart = data_to_restart(bodies, tmp_path / "bodies.restart", "harmonic/quartic")
    shared = write_scene(scene, tmp_path / "shared", bodies=bodies)
    from_restart = write_scene(scene, tmp_path / "restart", bodies=restart, restart=True)
    assert not (shared / "scene.data").exists()
    options = RunOptions(route="python")
    first = run_scene(placed, options)
    for other in (shared, from_restart):
        second = run_scene(other, options)
        assert (first["e"], first["beta"]) == (second["e"], second["beta"])
        for name in ("series.dat", "energy.dat"):
            assert filecmp.cmp(placed / name, other / name, shallow=False)


@pytest.mark.lammps
def test_a_process_writes_a_sample_once(tmp_path):
    cache = SampleBodies()
    log = tmp_path / "log.lammps"
    scenes = [build_scene(SceneSpec(gamma_deg=g, **SMALL)) for g in (15.0, 70.0)]
    first, second = (cache.path(s, "harmonic/quartic", tmp_path, log) for s in scenes)
    assert first == second and first.is_file() and first.parent.parent == tmp_path / BODIES_FOLDER
    other = build_scene(SceneSpec(gamma_deg=15.0, seed=2, **SMALL))
    assert cache.path(other, "harmonic/quartic", tmp_path, log) != first
    assert cache.path(scenes[0], "class2", tmp_path, log) != first  # another bond style
    assert "write_restart" in log.read_text()  # LAMMPS's log of the conversion
    first.unlink()  # a study's run ended and removed it: written again
    assert cache.path(scenes[0], "harmonic/quartic", tmp_path, log).is_file()


def test_a_folder_lammps_cannot_read_is_refused_before_lammps_runs(tmp_path):
    scene = build_scene(SceneSpec(gamma_deg=15.0, **SMALL))
    with pytest.raises(InputError, match="whitespace|space"):
        SampleBodies().path(scene, "harmonic/quartic", tmp_path / "a b", tmp_path / "log")


@pytest.mark.lammps
def test_the_driver_removes_the_workers_bodies(tmp_path, monkeypatch):
    """A study's run ends with no .bodies folder, whatever its workers left."""
    from runner.cluster.driver import run_study
    from runner.study import Study

    monkeypatch.setenv("IMPACT_RUNS", str(tmp_path))
    study = Study("bodies_probe", lattices=("random",), cot_gamma=(3.0, 1.0), angles=2,
                  samples=1, n_disk=200)  # fmt: skip
    (study.folder / BODIES_FOLDER / "elsewhere-1").mkdir(parents=True)  # a crashed worker's
    counts = run_study(study, workers=1)
    assert counts["done"] == 2 and not (study.folder / BODIES_FOLDER).exists()
