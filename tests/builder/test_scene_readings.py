"""The readings of the wall (docs/model.md section 8): options, what each builds, the default."""

from __future__ import annotations

import csv
import subprocess
import sys

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.bodies import triangular_spacing
from builder.materials import calibrated
from builder.scene import DISK, WALL_HELD, SceneSpec
from tests.helpers import ROOT, RUNS, SMALL

WALL_AREA = 8.0 * 2.0


@pytest.mark.parametrize("n_wall", [800, 1600, "density"])
@pytest.mark.parametrize("wall_ka", [1.0, 10.0, "same-c"])
def test_each_reading_builds_as_asked(n_wall, wall_ka):
    scene = build_scene(
        SceneSpec(**{**SMALL, "gamma_deg": 30.0, "n_wall": n_wall, "wall_ka": wall_ka})
    )
    info = scene.info
    target = n_wall if n_wall != "density" else SMALL["n_disk"] / np.pi * WALL_AREA
    # the rim rows and the Poisson-disk fill land within a few percent of the target
    assert abs(info["n_wall_points"] - target) < 0.05 * target
    assert info["wall_spacing"] == pytest.approx(triangular_spacing(target / WALL_AREA), rel=1e-3)
    assert info["contact"]["cutoff"] == info["wall_spacing"]
    wall = scene.molecule != DISK
    wall_springs = wall[scene.springs[:, 0]]
    assert np.all(wall[scene.springs[:, 1]] == wall_springs)  # no spring joins the bodies
    assert np.allclose(scene.ka[wall_springs], info["ka_wall"])
    assert np.allclose(scene.ka[~wall_springs], info["ka_disk"])
    if wall_ka == "same-c":
        # c^2 = factor ka d^2 / m: the wall's springs give it the disk's c = 1
        c2 = calibrated("random")["c2"] * info["ka_wall"] * info["wall_spacing"] ** 2
        assert c2 == pytest.approx(1.0, rel=1e-12)
    else:
        # in units of the random disk's ka, which is this (random) disk's
        assert info["ka_wall"] == pytest.approx(wall_ka * info["ka_wall_reference"], rel=1e-12)
        assert info["ka_wall_reference"] == info["ka_disk"]


@pytest.mark.parametrize(
    "wall_fixed, rows",
    [("sides", ("left", "right")), ("sides+bottom", ("left", "right", "bottom"))],
)
def test_held_points_are_the_reading_s(wall_fixed, rows):
    scene = build_scene(SceneSpec(gamma_deg=30.0, wall_fixed=wall_fixed, **SMALL))
    held = scene.positions[scene.molecule == WALL_HELD]
    wall = scene.positions[scene.molecule != DISK]
    half, low = wall[:, 0].max(), wall[:, 1].min()
    on_side = np.isclose(np.abs(held[:, 0]), half)
    on_bottom = np.isclose(held[:, 1], low)
    assert np.all(on_side | on_bottom)
    assert on_side.sum() >= 2 * 13  # both sides, top corners included
    assert (on_bottom & ~on_side).any() == ("bottom" in rows)  # bottom corners are the sides'

    # every point of the held rows is held, and no other wall point
    rim = np.isclose(np.abs(wall[:, 0]), half) | (
        np.isclose(wall[:, 1], low) if "bottom" in rows else False
    )
    assert rim.sum() == len(held)


# Results studies that run another wall on purpose, and why.
OTHER_WALL_ON_PURPOSE = {
    "sliding_branch": "the wall that holds the slide past 80.5 degrees without changing with "
    "its width (docs/studies/grazing_wall/grazing_wall.md)",
    "sliding_branch_1600": "the same wall as sliding_branch, its next level",
    "sliding_branch_3200": "the same wall as sliding_branch, its third level",
    "sliding_branch_6400": "the same wall as sliding_branch, its fourth level",
    "sliding_branch_12800": "the same wall as sliding_branch, its fifth level",
    "sliding_branch_slope03": "the same wall as sliding_branch, at the surface slope 0.3",
    "sliding_branch_slope015": "the same wall as sliding_branch, at the surface slope 0.15",
    "sliding_branch_triangular": "the same wall as sliding_branch, the triangular disk",
}


def test_the_default_scene_is_the_chosen_reading():
    """The rule's pick of docs/model.md section 8 (docs/studies/model_readings/model_readings.md,
    docs/model.md): 1600 wall points, ten times the random disk's ka, the sides
    held, V0 from the disk's mass; every study of a results page and the command
    line run it (the readings studies run the others on purpose)."""
    spec = SceneSpec()
    chosen = (1600, 10.0, "sides", "disk")
    assert (spec.n_wall, spec.wall_ka, spec.wall_fixed, spec.contact_mass) == chosen
    from runner.study.studies import all_studies

    for name, described in all_studies().items():
        study = described.study
        if described.kind != "results" or name in OTHER_WALL_ON_PURPOSE:
            continue
        n_wall = (
            2 * study.n_disk if study.n_wall is None else study.n_wall
        )  # None: twice the disk's
        assert (n_wall, study.wall_ka, study.wall_fixed, study.contact_mass) == chosen
    scene = build_scene(SceneSpec(gamma_deg=30.0))
    info = scene.info
    assert abs(info["n_wall_points"] - 1600) < 0.05 * 1600
    assert info["ka_wall"] == pytest.approx(10.0 * info["ka_disk"], rel=1e-12)
    held = scene.positions[scene.molecule == WALL_HELD]
    assert np.isclose(np.abs(held[:, 0]), spec.wall_width / 2).all()  # the sides only
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "impact", "--help-all"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    help_text = " ".join(proc.stdout.split())
    for default in (
        "(default: twice --n-disk, the paper's 1600 for 800)",
        "(default: 10)",
        "(default: sides)",
        "(default: disk)",
    ):
        assert default in help_text


@pytest.mark.parametrize(
    "field, value, words",
    [
        ("n_wall", 12, "n_wall must be an integer in [50, 400000] or 'density'"),
        ("n_wall", "dense", "n_wall must be an integer in [50, 400000] or 'density'"),
        ("wall_ka", 0.0, "wall_ka must be a number in [0.01, 1000]"),
        ("wall_ka", "hard", "wall_ka must be a number in [0.01, 1000]"),
    ],
)
def test_bad_reading_in_a_spec(field, value, words):
    from ground.errors import InputError

    with pytest.raises(InputError, match=words.replace("[", r"\[")):
        build_scene(SceneSpec(**{**SMALL, field: value}))


@pytest.mark.parametrize(
    "command, args, words",
    [
        (
            ["builder", "scene"],
            ["--n-wall", "12"],
            "argument --n-wall: must be an integer in [50, 400000] or 'density'",
        ),
        (
            ["builder", "scene"],
            ["--n-wall", "dense"],
            "argument --n-wall: must be an integer in [50, 400000]",
        ),
        (
            ["builder", "scene"],
            ["--wall-ka", "0"],
            "argument --wall-ka: must be a number in [0.01, 1000]",
        ),
        (["runner", "impact"], ["--wall-ka", "hard"], "argument --wall-ka: must be a number"),
        (["runner", "impact"], ["--wall-fixed", "top"], "argument --wall-fixed: invalid choice"),
        (
            ["runner", "study", "demo"],
            ["--wall-ka", "5000"],
            "argument --wall-ka: must be a number",
        ),
        (["runner", "study", "demo"], ["--n-wall", "x"], "argument --n-wall: must be an integer"),
    ],
)
def test_bad_reading_on_the_command_line(tmp_path, command, args, words):
    out = tmp_path / "scene"
    where = ["--out", str(out)] if command[-1] != "demo" else ["--name", "test_bad_reading"]
    proc = subprocess.run(
        [sys.executable, "-m", *command, *args, *where], cwd=ROOT, capture_output=True, text=True
    )
    assert proc.returncode == 2
    assert words in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists() and not (RUNS / "test_bad_reading").exists()


@pytest.mark.lammps
@pytest.mark.slow
def test_a_study_records_its_reading_in_every_row():
    name = "test_study_reading"
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    options = (
        "--lattices random --angles 2 --samples 1 --n-disk 200 "
        "--n-wall 600 --wall-ka 2 --wall-fixed sides+bottom"
    ).split()
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "study", "demo", "--name", name, *options],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    with (RUNS / name / "impacts.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 2
    for row in rows:
        assert (row["n_wall"], row["wall_ka"], row["wall_fixed"]) == ("600", "2.0", "sides+bottom")
        assert float(row["ka_wall_over_disk"]) == pytest.approx(2.0)
        assert abs(int(row["n_wall_points"]) - 600) < 30
    page = (RUNS / name / "results.md").read_text()
    assert "--n-wall 600 --wall-ka 2 --wall-fixed sides+bottom" in page
