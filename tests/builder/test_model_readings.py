"""The readings of the model (docs/model.md section 8) change the scene as specified.

Each reading is an option of the builder, the impact and the study; here each
one is checked on the scene it builds: the contact's V0, the velocity's scale,
the surface displacements' direction and size, the surface row's positions,
and the springs of a regular disk's own surface. The default reading must
leave every scene as it was (test_builder's and test_data_file's checks).
"""

from __future__ import annotations

import numpy as np
import pytest

from builder import bodies
from builder.assembly import build_scene
from builder.cli import MODEL_OPTIONS
from builder.materials import square_ratio_for_poisson
from builder.scene import DISK, FIRST_READING, MODEL_READINGS, SceneSpec
from builder.study_names import LIMITS
from ground.errors import InputError
from runner.__main__ import main as runner_main
from runner.study import Study
from runner.study.studies import load_study

DELTA = 0.03


def disk(**readings) -> bodies.Body:
    lattice = readings.pop("lattice", "random")
    seed = readings.pop("seed", 7)
    roughness = readings.pop("roughness", DELTA)
    return bodies.make_disk(
        np.random.default_rng(seed), lattice, 800, roughness, 3.0 / 7.0, **readings
    )


def polar(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.hypot(points[:, 0], points[:, 1]), np.arctan2(points[:, 1], points[:, 0])


def test_every_reading_is_an_option_with_its_choices():
    assert (
        set(MODEL_OPTIONS)
        == set(MODEL_READINGS)
        == set(Study.__dataclass_fields__) & set(MODEL_READINGS)
    )
    for name, choices in MODEL_READINGS.items():
        assert getattr(SceneSpec, name) in choices
        assert FIRST_READING[name] == choices[0]  # what a record without it means
        with pytest.raises(InputError, match=f"^{name} must be one of"):
            SceneSpec(**{name: "nonsense"}).validate()


@pytest.mark.parametrize(("mass", "factor"), [("point", None), ("disk", "n_disk_points")])
def test_the_contact_energy_takes_one_point_or_the_disk(mass, factor):
    scene = build_scene(SceneSpec(seed=2, gamma_deg=30.0, contact_mass=mass))
    # the disk's mass: its points, counted from the atoms (every point has m = 1)
    points = 1 if factor is None else int((scene.molecule == DISK).sum())
    assert factor is None or points == scene.info[factor] > 700
    # V0 = a m c^2 R / 2 with a = 300 / R, m = c = R = 1
    assert scene.info["contact"]["V0"] == pytest.approx(150.0 * points, rel=1e-15)


@pytest.mark.parametrize("lattice", ["random", "triangular", "square"])
def test_the_speed_unit_is_c_or_the_springs_sound_speed(lattice):
    extra = {"k2_over_k1": square_ratio_for_poisson(0.3)} if lattice == "square" else {}
    spec = dict(lattice=lattice, seed=2, gamma_deg=30.0, vn=0.1, **extra)
    in_c = build_scene(SceneSpec(**spec))
    in_springs = build_scene(SceneSpec(**spec, speed_unit="spring"))
    # d sqrt(ka / m), d the disk's nominal spacing, m = 1: independently of the
    # calibration's c^2 = c2 ka d^2 / m, which makes it 1 / sqrt(c2) in units of c
    unit = in_springs.info["disk_spacing"] * np.sqrt(in_springs.info["ka_disk"])
    assert unit == pytest.approx(1.0 / np.sqrt(in_springs.info["disk_material"]["c2"]))
    assert in_springs.info["units"]["vn_unit"] == pytest.approx(unit, rel=1e-14)
    assert in_c.info["units"]["vn_unit"] == 1.0
    np.testing.assert_allclose(in_c.velocities[-1], [0.1 * np.tan(np.radians(30.0)), -0.1])
    np.testing.assert_allclose(in_springs.velocities[-1], unit * in_c.velocities[-1], rtol=1e-14)
    if lattice == "triangular":  # the theory's c is the springs' sound speed
        assert unit == pytest.approx(1.0, abs=1e-3)


def test_normal_roughness_moves_the_disk_surface_along_the_radius_only():
    body = disk()
    radius, angle = polar(body.points[body.surface])
    n = len(angle)
    even = 2.0 * np.pi * np.arange(n) / n
    np.testing.assert_allclose(np.mod(angle - even + np.pi, 2 * np.pi) - np.pi, 0.0, atol=1e-12)
    # sd of the radial displacement: delta within the chi-square spread of n draws
    assert np.std(radius - 1.0) == pytest.approx(DELTA, rel=4.0 / np.sqrt(2 * n))


def test_both_directions_move_the_disk_surface_along_the_circle_too():
    rows = [disk(seed=seed, roughness_direction="both") for seed in range(20)]
    plain = [disk(seed=seed) for seed in range(20)]
    radial, along = [], []
    for body, flat in zip(rows, plain, strict=True):
        radius, angle = polar(body.points[body.surface])
        assert np.all(np.diff(np.mod(angle, 2 * np.pi)) > 0)  # still a row in order of angle
        # the radial draws are the default's (a move along the circle adds s^2 / 2)
        np.testing.assert_allclose(
            np.sort(radius), np.sort(polar(flat.points[flat.surface])[0]), atol=0.01
        )
        n = len(angle)
        even = 2.0 * np.pi * np.arange(n) / n
        start = np.argmin(np.abs(np.mod(angle - even[0] + np.pi, 2 * np.pi) - np.pi))
        shift = np.mod(np.roll(angle, -start) - even + np.pi, 2 * np.pi) - np.pi
        radial.append(radius - 1.0)
        along.append(shift * radius)  # arc length, the displacement along the circle
    n = sum(len(r) for r in radial)
    for values in (np.concatenate(radial), np.concatenate(along)):
        # a swap of neighbours pairs a shift with the wrong even angle now and
        # then; the sd must still be delta, not 0 (normal) or twice it
        assert np.std(values) == pytest.approx(DELTA, rel=0.1)
    assert n > 1000


def test_the_wall_takes_both_directions_too():
    rng = np.random.default_rng
    normal = bodies.make_wall(rng(5), 4000, roughness=DELTA)
    both = bodies.make_wall(rng(5), 4000, roughness=DELTA, roughness_direction="both")
    top_n, top_b = normal.points[normal.surface], both.points[both.surface]
    spacing = normal.spacing
    # normal: the top row's x evenly spaced; both: moved along x by delta, in order
    np.testing.assert_allclose(np.diff(top_n[:, 0]), np.diff(top_n[:, 0])[0], rtol=1e-9)
    assert np.all(np.diff(top_b[:, 0]) >= 0.0)
    assert np.abs(top_b[:, 0]).max() <= 4.0
    moved = np.sort(top_b[1:-1, 0]) - top_n[1:-1, 0]
    assert 0.5 * DELTA < np.std(moved) < 1.5 * DELTA
    np.testing.assert_array_equal(np.sort(top_b[:, 1]), np.sort(top_n[:, 1]))  # y the same
    assert spacing == both.spacing


def test_a_random_surface_row_keeps_its_minimum_distance_and_count():
    counts = []
    for seed in range(12):
        body = disk(seed=seed, surface_row="random", roughness=0.0)
        radius, angle = polar(body.points[body.surface])
        np.testing.assert_allclose(radius, 1.0, atol=1e-12)  # on the circle
        gaps = np.diff(np.concatenate([np.sort(angle), [np.sort(angle)[0] + 2 * np.pi]]))
        assert gaps.min() >= bodies.ROW_MIN_DISTANCE * body.spacing * (1 - 1e-9)
        assert gaps.std() > 0.1 * gaps.mean()  # not evenly spaced
        counts.append(len(angle))
    even = len(disk(roughness=0.0).surface)
    assert abs(np.mean(counts) - even) < 3.0


@pytest.mark.parametrize("lattice", ["triangular", "square"])
def test_a_regular_disk_can_be_its_own_surface(lattice):
    smooth = disk(lattice=lattice, roughness=0.0, regular_surface="lattice")
    d = smooth.spacing
    lengths = np.linalg.norm(
        smooth.points[smooth.springs[:, 0]] - smooth.points[smooth.springs[:, 1]], axis=1
    )
    allowed = (d,) if lattice == "triangular" else (d, np.sqrt(2.0) * d)
    # every spring joins lattice neighbours: no band of joining springs
    assert np.all(np.min([np.abs(lengths - a) for a in allowed], axis=0) < 1e-9 * d)
    # the surface row: lattice points, a spacing apart, each missing a neighbour
    row = smooth.points[smooth.surface]
    np.testing.assert_allclose(np.linalg.norm(row - np.roll(row, -1, axis=0), axis=1), d)
    coordination = np.bincount(smooth.springs.ravel(), minlength=len(smooth.points))
    full = 6 if lattice == "triangular" else 8
    assert np.all(coordination[smooth.surface] < full)
    assert np.all(np.hypot(*smooth.points.T) <= 1.0 + 1e-9)
    # the band construction has springs of other lengths
    band = disk(lattice=lattice, roughness=0.0)
    band_lengths = np.linalg.norm(
        band.points[band.springs[:, 0]] - band.points[band.springs[:, 1]], axis=1
    )
    assert np.any(np.min([np.abs(band_lengths - a) for a in allowed], axis=0) > 0.01 * d)
    # roughened: the same springs, the row moved along the radius by delta
    rough = disk(lattice=lattice, regular_surface="lattice")
    np.testing.assert_array_equal(rough.springs, smooth.springs)
    moved = polar(rough.points[rough.surface])[0] - polar(row)[0]
    assert np.std(moved) == pytest.approx(DELTA, rel=4.0 / np.sqrt(2 * len(moved)))
    np.testing.assert_allclose(
        polar(rough.points[rough.surface])[1], polar(row)[1], atol=1e-12
    )  # along the radius only


def test_readings_that_do_not_apply_are_refused():
    with pytest.raises(InputError, match="regular_surface lattice applies to the triangular"):
        SceneSpec(regular_surface="lattice").validate()
    with pytest.raises(InputError, match="surface_row random places a surface row"):
        SceneSpec(
            lattice="square", regular_surface="lattice", surface_row="random", **LIMITS["paper"]
        ).validate()
    with pytest.raises(InputError, match="--regular-surface lattice applies to"):
        Study("x", lattices=("random",), regular_surface="lattice").validate()


def test_a_study_gives_each_lattice_the_readings_that_apply():
    study = Study(
        "x",
        lattices=("random", "triangular"),
        regular_surface="lattice",
        surface_row="random",
        contact_mass="disk",
    )
    random = study.spec({"lattice": "random", "seed": 1, "gamma": 30.0})
    triangular = study.spec({"lattice": "triangular", "seed": 1, "gamma": 30.0})
    assert (random.surface_row, random.regular_surface) == ("random", "band")
    assert (triangular.surface_row, triangular.regular_surface) == ("even", "lattice")
    assert random.contact_mass == triangular.contact_mass == "disk"
    # the paper study pins the paper's scene (the named reading "paper")
    assert load_study("paper").spec({"lattice": "random", "seed": 1, "gamma": 30.0}) == SceneSpec(
        seed=1, gamma_deg=30.0, **LIMITS["paper"]
    )


def test_the_command_line_takes_the_readings(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        runner_main(["impact", "--contact-mass", "planet", "--out", str(tmp_path / "x")])
    assert exit_.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--contact-mass" in err[0] and "'planet'" in err[0]
    assert not (tmp_path / "x").exists()
    status = runner_main(["impact", "--regular-surface", "lattice", "--out", str(tmp_path / "y")])
    assert status == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "python -m runner: error: --regular-surface lattice applies to the triangular and "
        "square disks, got lattice random"
    ]
    assert not (tmp_path / "y").exists()
