"""Defaults that follow the body (issue 46): a disk of any N with no options
hitting the wall is the same body refined, the "profile-floor" reading whose
limit exists; a binary scene keeps the paper's; the paper's scene stays the
named reading "paper", byte for byte; every N from 200 to 51,200 is a valid
scene with no option at every angle of the paper's grid."""

from __future__ import annotations

import argparse

import pytest

from builder.assembly import build_scene
from builder.cli import add_scene_arguments, spec_from_args
from builder.lammps_data import write_scene
from builder.scene import BODY, PAPER, SCENE, SceneSpec
from builder.study_names import LIMITS
from runner.impact import run_impact
from runner.options import RunOptions
from runner.study import study_angles
from runner.study.file import read_study_file
from tests.helpers import ROOT

FOUR = tuple(BODY)
# the paper's grid: 16 angles, cot gamma log-spaced from 10 to cot 80.5 degrees
PAPER_ANGLES = study_angles(16)
# 200 to 51,200 points, doubling (the resolution studies' levels)
LEVELS = [200 * 2**k for k in range(9)]


def four(spec: SceneSpec) -> dict:
    return {name: getattr(spec, name) for name in FOUR}


def test_the_default_at_the_wall_is_the_refined_body():
    assert four(SceneSpec()) == LIMITS["profile-floor"] == BODY
    assert four(SceneSpec(n_disk=12_800)) == BODY


def test_the_default_of_a_binary_scene_is_the_papers():
    assert four(SceneSpec(target="disk")) == LIMITS["paper"] == PAPER
    SceneSpec(target="disk").validate()
    # the paper's values given are the binary scene's own, not refused
    SceneSpec(target="disk", **PAPER).validate()


def test_the_command_line_with_no_option_is_the_default():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    assert spec_from_args(parser.parse_args([])) == SceneSpec()
    binary = spec_from_args(parser.parse_args(["--target", "disk"]))
    assert binary == SceneSpec(target="disk") and four(binary) == PAPER
    # a draw per point needs no profile: --roughness-length 0 alone is sampled
    assert spec_from_args(parser.parse_args(["--roughness-length", "0"])).roughness_profile == (
        "sampled"
    )


def test_help_says_the_default_and_why():
    parser = argparse.ArgumentParser()
    add_scene_arguments(parser)
    text = " ".join(parser.format_help().split())
    assert "(default: 0.2 with --target wall, 0 with --target disk)" in text
    assert "(default: physical with --target wall, spacing with --target disk)" in text
    assert "(default: 0.5 with --target wall, 0 with --target disk)" in text
    assert "whose limit as n_disk grows exists" in text and "the reading paper" in text


def test_made_by_spells_out_what_is_not_the_targets_default():
    paper = {"target": "wall", **PAPER}
    words = [SCENE[name].made_by_words(paper) for name in FOUR]
    assert words == [
        "--roughness-length 0",
        "--roughness-profile sampled",
        "--contact-scaling spacing",
        "--area-floor 0",
    ]
    assert [SCENE[name].made_by_words({"target": "wall", **BODY}) for name in FOUR] == [""] * 4
    assert [SCENE[name].made_by_words({"target": "disk", **PAPER}) for name in FOUR] == [""] * 4
    # a record from before the options existed was the paper's scene
    assert SCENE["area_floor"].made_by_words({"target": "wall"}) == "--area-floor 0"


def test_every_named_reading_gives_the_four_options():
    """Each named limit means what it meant whatever the default: it names all four."""
    for name, options in LIMITS.items():
        assert set(FOUR) <= set(options), name
    assert LIMITS["point-roughness"] == LIMITS["paper"] == PAPER


def test_the_paper_study_pins_the_papers_scene():
    for name in ("paper", "grazing", "speed"):
        study = read_study_file(ROOT / "studies" / f"{name}.toml").study
        assert {k: getattr(study, k) for k in FOUR} == PAPER, name


def test_the_papers_reading_is_the_old_default_scene_byte_for_byte(tmp_path):
    """The named reading against the four old defaults given one by one (and
    tests/builder/test_builder.py's pinned digest of the old default scene)."""
    named = SceneSpec(gamma_deg=30.0, seed=1, **LIMITS["paper"])
    explicit = SceneSpec(
        gamma_deg=30.0,
        seed=1,
        roughness_length=0.0,
        roughness_profile="sampled",
        contact_scaling="spacing",
        area_floor=0.0,
    )
    data = []
    for spec, folder in ((named, tmp_path / "named"), (explicit, tmp_path / "explicit")):
        write_scene(build_scene(spec), folder)
        data.append((folder / "scene.data").read_bytes())
    assert data[0] == data[1]
    default = tmp_path / "default"
    write_scene(build_scene(SceneSpec(gamma_deg=30.0, seed=1)), default)
    assert (default / "scene.data").read_bytes() != data[0]  # the default is the body now


@pytest.mark.parametrize("n_disk", LEVELS)
def test_every_resolution_is_a_scene_at_every_angle_of_the_papers_grid(n_disk):
    options = RunOptions()
    for gamma in PAPER_ANGLES:
        spec = SceneSpec(n_disk=n_disk, gamma_deg=gamma)
        spec.validate()
        assert options.scene_problem(spec) is None, (n_disk, gamma)
        assert options.for_scene(spec).dt > 0


@pytest.mark.slow
def test_the_default_body_runs_at_200_points(tmp_path):
    spec = SceneSpec(n_disk=200, gamma_deg=PAPER_ANGLES[-1])
    spec.validate()
    result = run_impact(spec, tmp_path / "impact", RunOptions())
    assert 0.0 < result["e"] < 1.5
    assert result["in_barrier_max"] is not None
    assert spec.area_floor == BODY["area_floor"]  # the barrier ran
