"""The study's tables: one row per impact, and means per lattice and angle."""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import numpy as np

from builder.scene import MODEL_READINGS
from ground.digits import TABLE_DIGITS, rounded  # noqa: F401 (the tables' digits, here since before ground.digits)
from ground.gate import atomic

from .impact.result import MAX_DRIFT, UnreadableResult, read_result

# The columns of impacts.csv, in order; every result.json has them. Physics
# and provenance only: how long an impact took (result.json's wall_seconds)
# goes into timings.csv (TIMING_COLUMNS), so that a rerun that changes no
# number changes no byte of the tables.
COLUMNS = (
    "study_lattice",
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "vn",
    "e",
    "beta",
    "omega",
    "contact_time",
    "touches",
    "vibration_disk",
    "vibration_wall",
    "energy_drift",
    "drift_exceeded",
    "side_clearance",
    "wall_width",
    "n_wall",
    "wall_ka",
    "wall_fixed",
    "contact_mass",
    "speed_unit",
    "roughness_direction",
    "surface_row",
    "regular_surface",
    "vn_in_c",
    "n_wall_points",
    "ka_wall_over_disk",
    "ka_wall",
    "disk_inertia_ratio",
    "nu",
    "steps",
    "time_end",
    "dt",
    "integrator",
    "contact",
    "stop_rule",
    "lammps_version",
)
# A binary study's impacts.csv has these too (analysis.impact.binary); its
# vibration_wall is the second disk's, and side_clearance is empty (no wall).
BINARY_COLUMNS = (
    *COLUMNS,
    "target",
    "partner_lattice",
    "cot_gamma_nominal",
    "apse_angle_deg",
    "momentum_change",
    "angular_momentum_change",
    "n_target_points",
    "target_inertia_ratio",
    # with the three before: each pair's two-body K (analysis.statistics.estimates)
    "n_disk_points",
    # the other two normals (analysis.impact.binary; e, beta, cot_gamma are the apse's)
    "e_first_touch",
    "beta_first_touch",
    "cot_gamma_first_touch",
    "normal_angle_deg_first_touch",
    "e_impulse",
    "beta_impulse",
    "cot_gamma_impulse",
    "normal_angle_deg_impulse",
    "impulse_tilt_deg",
    # the aim by the contact (builder/binary.py): the line's offset, the
    # first touch's incidence the rings give, and the pair's turn (degrees)
    "aim_offset",
    "aim_incidence_deg",
    "aim_turn_deg",
)
# A held second disk (partner image-held): the rows say so
# (analysis.statistics.estimates.two_body_k).
HELD_COLUMNS = (*BINARY_COLUMNS, "target_held")


# timings.csv: an impact's key and its LAMMPS seconds (runs/<name>/, and a
# readings study's tables); a results study's tables keep their sum in
# study.json (lammps_seconds), which its page states.
TIMING_COLUMNS = ("study_lattice", "seed", "gamma_deg", "vn", "wall_seconds", "steps")
TIMINGS = "timings.csv"


def held(values: dict) -> bool:
    """Whether a row's second disk was held (partner image-held)."""
    return str(values.get("target_held", "")).lower() == "true"


def table_columns(rows: list[dict]) -> tuple[str, ...]:
    """impacts.csv's columns for these rows: a binary study's has its own too,
    and one whose second disk was held says so."""
    if any(held(r) for r in rows):
        return HELD_COLUMNS
    return BINARY_COLUMNS if any(r.get("target") == "disk" for r in rows) else COLUMNS


# The columns of means.csv. "*_seed_sd": the error of the mean, the standard
# deviation over resamples of whole seeds (analysis.statistics.seeds).
# The quantities of impacts.csv averaged per lattice and angle (means.csv, and
# the seed bootstrap's, analysis/statistics/seeds.py, which adds side_clearance).
AVERAGED = (
    "cot_gamma",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "disk_inertia_ratio",
)
MEAN_COLUMNS = (
    "study_lattice",
    "gamma_deg",
    "cot_gamma",
    "samples",
    "e",
    "e_seed_sd",
    "beta",
    "beta_seed_sd",
    "omega",
    "omega_seed_sd",
    "contact_time",
    "contact_time_seed_sd",
    "vibration_disk",
    "vibration_disk_seed_sd",
    "vibration_wall",
    "vibration_wall_seed_sd",
    "disk_inertia_ratio",
    "near_side",
)
# A contact whose disk centre came within a radius of a fixed side of the wall
# felt the wall's end (docs/model.md); means.csv counts them, and an angle
# where more than a tenth of a lattice's contacts did is left out of the fits
# that must not see the ends.
NEAR_SIDE = 1.0
NEAR_SIDE_SHARE = 0.1


def near_the_ends(mean: dict) -> bool:
    """Whether too many contacts at this lattice and angle felt the wall's ends.

    Parameters
    ----------
    mean : dict
        One row of ``mean_rows`` (needs ``near_side`` and ``samples``).

    Returns
    -------
    bool
        True if more than ``NEAR_SIDE_SHARE`` of the contacts came within
        ``NEAR_SIDE`` of a fixed side.
    """
    return mean["near_side"] > NEAR_SIDE_SHARE * mean["samples"]


def with_model_readings(values: dict) -> dict:
    """``values`` (a result or a table's row) with the readings of the model
    filled in where it predates them: those were the first choices."""
    for name, choices in MODEL_READINGS.items():
        if values.get(name) in (None, ""):
            values[name] = choices[0]
    if values.get("vn_in_c") in (None, ""):  # before it, vn was in units of c
        values["vn_in_c"] = values.get("vn", "")
    return values


def row(result: dict, study_lattice: str) -> dict:
    """The table's row for one result.json."""
    values = dict(result, study_lattice=study_lattice)
    columns = BINARY_COLUMNS if values.get("target") == "disk" else COLUMNS
    columns = HELD_COLUMNS if held(values) else columns
    out = {name: "" if values.get(name) is None else values[name] for name in columns}
    out["wall_seconds"] = values.get("wall_seconds", "")  # for timings.csv, not a column
    out["git_revision"] = values.get("git_revision", "")  # for run.json, not a column
    return out


def write_csv(rows: list[dict], path: Path | str, columns=COLUMNS) -> None:
    # the one gate of every write, whole or not at all (ground.gate)
    with atomic(path) as temporary, temporary.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(columns), extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def collect(folders: list[tuple[str, Path]]) -> list[dict]:
    """Rows of every finished impact: (study lattice name, run folder) pairs.

    An unreadable result.json is named on stderr and left out (a study that
    runs again moves it aside and reruns its impact).

    Parameters
    ----------
    folders : list of tuple of (str, pathlib.Path)
        The study's name for the lattice (e.g. ``square_nu0.3``) and the run
        folder of each impact.

    Returns
    -------
    list of dict
        One impacts.csv row (``COLUMNS``) per folder that holds a readable
        result.json; unfinished or failed impacts are left out.
    """
    rows = []
    for lattice, folder in folders:
        result = Path(folder) / "result.json"
        if result.exists():
            try:
                values = read_result(result)
            except UnreadableResult as error:
                print(
                    f"warning: {error}; left out of the tables (running the study again reruns it)",
                    file=sys.stderr,
                )
                continue
            scene_file = Path(folder) / "scene.json"
            if values.get("target") == "disk":  # binary: no wall to fill in
                scene_file = Path(folder) / "no wall"
            if "n_wall" not in values and scene_file.exists():  # results from before the readings
                scene = json.loads(scene_file.read_text())
                spec = scene["spec"]
                values.setdefault("wall_width", spec["wall_width"])
                # the scenes before the readings: the disk's density, springs for its c
                values["n_wall"] = spec.get("n_wall") or "density"
                values["wall_ka"] = spec.get("wall_ka", "same-c")
                values["wall_fixed"] = spec["wall_fixed"]
                values["ka_wall_over_disk"] = scene["ka_wall"] / scene["ka_disk"]
            if "ka_wall" not in values and scene_file.exists():  # nor this one
                values["ka_wall"] = json.loads(scene_file.read_text())["ka_wall"]
            if "drift_exceeded" not in values:  # nor this one
                values["drift_exceeded"] = abs(values["energy_drift"]) > MAX_DRIFT
            rows.append(row(with_model_readings(values), lattice))
    return rows


def mean_rows(rows: list[dict], errors: dict | None = None) -> list[dict]:
    """Means per study lattice and angle, with their errors where given.

    Parameters
    ----------
    rows : list of dict
        One row per impact (``collect``).
    errors : dict, optional
        (lattice, gamma_deg) -> {"e_seed_sd": ..., ...}: the errors of the
        means (``analysis.statistics.estimates.study_estimates``), merged into the rows.

    Returns
    -------
    list of dict
        The rows of means.csv, sorted by lattice and angle: the means of e,
        beta, omega, ..., the number of samples, ``near_side`` and the errors.
    """
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r["study_lattice"], float(r["gamma_deg"])), []).append(r)
    out = []
    for (lattice, gamma), group in sorted(groups.items()):
        mean = {"study_lattice": lattice, "gamma_deg": gamma, "samples": len(group)}
        for name in AVERAGED:
            mean[name] = float(np.mean([float(r[name]) for r in group]))
        mean["near_side"] = sum(
            r["side_clearance"] != "" and float(r["side_clearance"]) < NEAR_SIDE for r in group
        )
        mean.update((errors or {}).get((lattice, gamma), {}))
        out.append(mean)
    return out
