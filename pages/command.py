"""The command that runs a study again, every option spelled out, from its
study.json (the "Made by" line of a results or speed page)."""

from __future__ import annotations

from analysis.result import MAX_DRIFT
from builder.scene import MODEL_READINGS


def angle_options(study: dict) -> str:
    """--cot-gamma's values if the study gave them, else --angles."""
    if study.get("cot_gamma"):
        return "--cot-gamma " + " ".join(f"{c:g}" for c in study["cot_gamma"])
    return f"--angles {study['angles']}"


def wall_options(study: dict) -> str:
    """The study's reading of the wall as options (studies from before the
    readings had the disk's density, springs for its c, the sides held), or
    a binary study's target (it has no wall)."""
    if study.get("target") == "disk":
        partner = study.get("partner_lattice")
        image = " --partner image" if study.get("partner") == "image" else ""
        return "--target disk" + (f" --partner-lattice {partner}" if partner else "") + image
    n_wall = study.get("n_wall", "density")
    wall_ka = study.get("wall_ka", "same-c")
    # n_wall None: twice the disk's points, what leaving out --n-wall gives
    points = "" if n_wall is None else f"--n-wall {n_wall} "
    return (
        f"{points}--wall-ka {wall_ka if isinstance(wall_ka, str) else f'{wall_ka:g}'} "
        f"--wall-fixed {study.get('wall_fixed', 'sides')}"
    )


def model_options(study: dict) -> str:
    """The readings of the model as runner study's options (studies from before
    they were options had the first choices)."""
    return " ".join(
        f"--{name.replace('_', '-')} {study.get(name, choices[0])}"
        for name, choices in MODEL_READINGS.items()
    )


def speed_options(study: dict) -> str:
    """--speeds if the study has a speed axis, else --vn."""
    if study.get("speeds"):
        return "--speeds " + " ".join(f"{v:g}" for v in study["speeds"])
    return f"--vn {study.get('vn', 0.1):g}"


def step(dt) -> str:
    """A study's dt as --dt takes it: a number, or "auto"."""
    return dt if isinstance(dt, str) else f"{dt:g}"


def resolution_options(study: dict) -> str:
    """How the study carries the model to its resolution, where it departs
    from the defaults (studies from before these options have them)."""
    words = ""
    if study.get("roughness_length"):
        words += f"--roughness-length {study['roughness_length']:g} "
    if study.get("contact_scaling", "spacing") != "spacing":
        words += f"--contact-scaling {study['contact_scaling']} "
    return words


def made_by(study: dict, preset: str) -> str:
    """The command that runs the study again, every option spelled out."""
    # a binary study has no wall (wall_options gives its target instead)
    width = (
        "" if study.get("target") == "disk" else f"--wall-width {study.get('wall_width', 8.0):g} "
    )
    return (
        f"python -m runner study {preset} --name {study['name']} --lattices "
        f"{' '.join(study['lattices'])} {angle_options(study)} --samples {study['samples']} "
        f"{speed_options(study)} --roughness {study.get('roughness', 0.03):g} "
        f"--n-disk {study['n_disk']} --radius {study.get('radius', 1.0):g} "
        f"{width}--contact-a {study.get('contact_a', 300.0):g} {wall_options(study)} "
        f"{model_options(study)} {resolution_options(study)}"
        f"--dt {step(study['options']['dt'])} "
        f"--max-drift {study['options'].get('max_drift', MAX_DRIFT):g}"
    )
