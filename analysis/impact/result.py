"""result.json of one impact: what was run and what came out of it."""

from __future__ import annotations

import json
import math
from pathlib import Path

from builder.run_options import MAX_DRIFT
from builder.scene import MODEL_READINGS
from ground.gate import write_text

from .barrier import barrier_counts
from .binary import binary_energy_split, binary_normals, binary_rebound, momentum_change
from .restitution import contact_window, energy_split, rebound_from_series, side_clearance, touches
from .series import read_energies, read_series

# The energy drift (change of the total energy over the initial kinetic
# energy) above which a run counts as inaccurate: its time step is too large
# for the scene. On the default scene at the default dt = 2e-3 the paper
# study's 6,400 drifts have a median of 9.4e-5, 99 % below 4.7e-3 and the
# largest 2.1e-2; dt = 0.02 drifts 0.13 (docs/benchmarks/time_vs_error.md).
# MAX_DRIFT, builder.run_options's: the runs' default.
# What the study's tables read from every result.json.
REQUIRED = (
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "energy_drift",
    "side_clearance",
    "disk_inertia_ratio",
    "nu",
    "steps",
    "wall_seconds",
)


# A binary scene's (target disk): no wall, so no side to come near; the
# relative change of the total momenta instead.
BINARY_REQUIRED = (
    *(key for key in REQUIRED if key != "side_clearance"),
    "target",
    "momentum_change",
    "angular_momentum_change",
)


# REQUIRED's numbers: a result with one of them not finite is not a result.
FINITE = tuple(key for key in REQUIRED if key != "lattice")
BINARY_FINITE = tuple(key for key in BINARY_REQUIRED if key not in ("lattice", "target"))


class UnreadableResult(ValueError):
    """A result.json that is not a whole result (a truncated or foreign file)."""


def analyse_run(folder: Path | str) -> dict:
    """The result of the run in ``folder`` (scene.json, run.json and the outputs).

    Parameters
    ----------
    folder : pathlib.Path or str
        A finished run folder: scene.json, run.json, series.dat, energy.dat.

    Returns
    -------
    dict
        What result.json holds (README, "A run folder"): the scene, e, beta,
        omega, the contact window, the energy split, how it was run and its
        provenance.
    """
    folder = Path(folder)
    scene = json.loads((folder / "scene.json").read_text())
    run = json.loads((folder / "run.json").read_text())
    spec = scene["spec"]
    series = read_series(folder / "series.dat")
    energies = read_energies(folder / "energy.dat")
    radius = spec["radius"]
    if scene.get("target") == "disk":
        return binary_result(scene, run, series, energies)
    rebound = rebound_from_series(series, radius, tangential=spec["gamma_deg"] > 0.0)
    start, end = contact_window(series)
    result = {
        "lattice": spec["lattice"],
        "seed": spec["seed"],
        "gamma_deg": spec["gamma_deg"],
        "cot_gamma": rebound.cot_gamma,
        "vn": spec["vn"],
        "e": rebound.e,
        "beta": rebound.beta,
        "omega": rebound.omega,
        "contact_time": end - start,
        "touches": touches(series),
        "steps": int(series["step"][-1]),
        "contact_start": start,
        "contact_end": end,
        "time_end": float(series["time"][-1]),
        "side_clearance": side_clearance(series, spec["wall_width"], radius),
        "wall_width": spec["wall_width"],
        "n_wall": spec["n_wall"],
        "wall_ka": spec["wall_ka"],
        "wall_fixed": spec["wall_fixed"],
        # the readings of the model; scenes from before they were options had the first
        **{name: spec.get(name, choices[0]) for name, choices in MODEL_READINGS.items()},
        "vn_in_c": spec["vn"] * scene["units"].get("vn_unit", 1.0),
        "wall_spacing": scene["wall_spacing"],
        "ka_wall_over_disk": scene["ka_wall"] / scene["ka_disk"],
        "ka_wall": scene["ka_wall"],
        "disk_inertia_ratio": scene["disk_inertia_ratio"],
        "n_disk_points": scene["n_disk_points"],
        "n_wall_points": scene["n_wall_points"],
        "c_source": scene["units"]["c_source"],
        "nu": scene["disk_material"]["nu"],
        "stop_rule": run["options"].get("stop_rule", "clearance"),
        "vx_in": rebound.vx_in,
        "vy_in": rebound.vy_in,
        "vx_out": rebound.vx_out,
        "vy_out": rebound.vy_out,
        **run_provenance(run),
    }
    result.update(energy_split(series, energies, scene["disk_mass"]))
    result.update(barrier_counts(folder))  # with --area-floor only
    result["drift_exceeded"] = bool(abs(result["energy_drift"]) > result["max_drift"])
    return result


def run_provenance(run: dict) -> dict:
    """How a run was made: what every result records of run.json."""
    options = run["options"]
    return {
        "dt": options["dt"],
        "integrator": options["integrator"],
        # contact steps per step; before the respa of the contact's inner level
        # (2026-11) respa meant the springs' inner level, and nrespa its steps
        "nrespa": options["nrespa"] if options["integrator"] == "respa" else None,
        "contact": options["contact"],
        "rule": options["rule"],
        "springs": options["springs"],
        "route": options["route"],
        "nprocs": options["nprocs"],
        "wall_seconds": run["wall_seconds"],
        "lammps_version": run["lammps_version"],
        "git_revision": run["git_revision"],
        # results written before the option existed were judged by the default
        "max_drift": options.get("max_drift", MAX_DRIFT),
    }


def binary_result(scene: dict, run: dict, series, energies) -> dict:
    """The result of a binary run (builder/binary.py): e and beta at the
    apse's normal (analysis.impact.binary), the momenta's change, the energy split.
    ``vibration_wall`` is the second disk's, so that a binary study's tables
    have the columns of a wall study's (what the disk hit)."""
    spec = scene["spec"]
    # a held target (partner image-held) moves as an infinite mass would
    masses = (scene["disk_mass"], math.inf if scene.get("target_held") else scene["target_mass"])
    rebound, where = binary_rebound(series, spec["radius"])
    start, end = contact_window(series)
    result = {
        "target": "disk",
        "lattice": spec["lattice"],
        "partner_lattice": spec.get("partner_lattice") or spec["lattice"],
        "seed": spec["seed"],
        "partner_seed": spec.get("partner_seed"),
        "partner": spec.get("partner", "independent"),
        "target_held": bool(scene.get("target_held", False)),
        "gamma_deg": spec["gamma_deg"],
        "cot_gamma": rebound.cot_gamma,
        "cot_gamma_nominal": scene["cot_gamma"],
        "vn": spec["vn"],
        "vn_in_c": spec["vn"] * scene["units"].get("vn_unit", 1.0),
        "e": rebound.e,
        "beta": rebound.beta,
        "omega": rebound.omega,
        **where,
        "contact_time": end - start,
        "contact_start": start,
        "contact_end": end,
        "touches": touches(series),
        "steps": int(series["step"][-1]),
        "time_end": float(series["time"][-1]),
        **{name: spec.get(name, choices[0]) for name, choices in MODEL_READINGS.items()},
        "disk_inertia_ratio": scene["disk_inertia_ratio"],
        "target_inertia_ratio": scene["target_inertia_ratio"],
        "n_disk_points": scene["n_disk_points"],
        "n_target_points": scene["n_target_points"],
        "c_source": scene["units"]["c_source"],
        "nu": scene["disk_material"]["nu"],
        "vx_in": rebound.vx_in,
        "vy_in": rebound.vy_in,
        "vx_out": rebound.vx_out,
        "vy_out": rebound.vy_out,
        **run_provenance(run),
    }
    aim = scene.get("aim", {})  # scenes built before the aim by the contact have none
    result.update(binary_normals(series, masses, spec["radius"], aim.get("first_touch_time")))
    result["aim_offset"] = aim.get("offset")
    result["aim_incidence_deg"] = aim.get("first_touch_incidence_deg")
    result["aim_turn_deg"] = aim.get("turn_deg")
    result.update(momentum_change(series, masses, spec["radius"]))
    result.update(binary_energy_split(series, energies, masses))
    result["vibration_wall"] = result["vibration_target"]
    result["drift_exceeded"] = bool(abs(result["energy_drift"]) > result["max_drift"])
    return result


def read_result(path: Path | str) -> dict:
    """A result.json, or UnreadableResult naming the file and what is wrong."""
    path = Path(path)
    try:
        values = json.loads(path.read_text())
    except (ValueError, OSError) as error:  # JSONDecodeError and UnicodeDecodeError are ValueErrors
        raise UnreadableResult(f"{path}: unreadable ({error})") from None
    if not isinstance(values, dict):
        raise UnreadableResult(f"{path}: not a JSON object")
    binary = values.get("target") == "disk"
    missing = [key for key in (BINARY_REQUIRED if binary else REQUIRED) if key not in values]
    if missing:
        raise UnreadableResult(
            f"{path}: incomplete (no {', '.join(missing[:4])}{', ...' if len(missing) > 4 else ''})"
        )
    # a run that produced these cannot have been right (run_scene never writes them)
    wrong = [key for key in (BINARY_FINITE if binary else FINITE) if not _finite(values[key])]
    if wrong:
        raise UnreadableResult(f"{path}: not a result ({', '.join(wrong)} not a finite number)")
    return values


def _finite(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def write_json_atomically(data: dict, path: Path | str) -> None:
    """Write JSON so that a reader sees either nothing or the whole file
    (ground.gate.write_text, the one gate and atomic write of every file);
    every digit kept: a result is a measurement, not a page's number."""
    write_text(path, json.dumps(data, indent=1, sort_keys=True) + "\n")
