"""The command that runs a study again, every option spelled out, from its
study.json (the "Made by" line of a results or speed page)."""

from __future__ import annotations

from builder.run_options import RUN_OPTIONS
from builder.scene import SCENE_OPTIONS


def angle_options(study: dict) -> str:
    """--cot-gamma's values if the study gave them, else --angles."""
    if study.get("cot_gamma"):
        return "--cot-gamma " + " ".join(f"{c:g}" for c in study["cot_gamma"])
    return f"--angles {study['angles']}"


def speed_options(study: dict) -> str:
    """--speeds if the study has a speed axis, else --vn."""
    if study.get("speeds"):
        return "--speeds " + " ".join(f"{v:g}" for v in study["speeds"])
    return f"--vn {study.get('vn', 0.1):g}"


def made_by(study: dict, preset: str) -> str:
    """The command that runs the study again, every option spelled out: the
    grid, then each scene and run option the way its declaration says
    (builder.declared.Option.made_by_words; a binary study has no wall, a
    wall study no partner)."""
    grid = (
        f"python -m runner study {preset} --name {study['name']} --lattices "
        f"{' '.join(study['lattices'])} {angle_options(study)} --samples {study['samples']} "
        f"{speed_options(study)}"
    )
    scene = [option.made_by_words(study) for option in SCENE_OPTIONS if option.study]
    run = [option.made_by_words(study["options"]) for option in RUN_OPTIONS]
    return " ".join(word for word in (grid, *scene, *run) if word)
