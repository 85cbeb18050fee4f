"""result.json of one impact: what was run and what came out of it."""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path

from builder.scene import MODEL_READINGS

from .restitution import contact_window, energy_split, rebound_from_series, side_clearance, touches
from .series import read_energies, read_series

# The energy drift (change of the total energy over the initial kinetic
# energy) above which a run counts as inaccurate: its time step is too large
# for the scene. On the default scene at the default dt = 2e-3 the paper
# study's 6,400 drifts have a median of 9.4e-5, 99 % below 4.7e-3 and the
# largest 2.1e-2; dt = 0.02 drifts 0.13 (docs/benchmarks/time_vs_error.md).
MAX_DRIFT = 0.05
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


# REQUIRED's numbers: a result with one of them not finite is not a result.
FINITE = tuple(key for key in REQUIRED if key != "lattice")


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
    rebound = rebound_from_series(series, radius, tangential=spec["gamma_deg"] > 0.0)
    start, end = contact_window(series)
    result = {
        "lattice": spec["lattice"],
        "seed": spec["seed"],
        "gamma_deg": spec["gamma_deg"],
        "cot_gamma": rebound.cot_gamma,
        "vn": spec["vn"],
        "dt": run["options"]["dt"],
        "integrator": run["options"]["integrator"],
        # contact steps per step; before the respa of the contact's inner level
        # (2026-11) respa meant the springs' inner level, and nrespa its steps
        "nrespa": run["options"]["nrespa"] if run["options"]["integrator"] == "respa" else None,
        "contact": run["options"]["contact"],
        "e": rebound.e,
        "beta": rebound.beta,
        "omega": rebound.omega,
        "contact_time": end - start,
        "touches": touches(series),
        "steps": int(series["step"][-1]),
        "wall_seconds": run["wall_seconds"],
        "lammps_version": run["lammps_version"],
        "rule": run["options"]["rule"],
        "springs": run["options"]["springs"],
        "route": run["options"]["route"],
        "nprocs": run["options"]["nprocs"],
        "git_revision": run["git_revision"],
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
    }
    result.update(energy_split(series, energies, scene["disk_mass"]))
    # results written before the option existed were judged by the default
    result["max_drift"] = run["options"].get("max_drift", MAX_DRIFT)
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
    missing = [key for key in REQUIRED if key not in values]
    if missing:
        raise UnreadableResult(
            f"{path}: incomplete (no {', '.join(missing[:4])}{', ...' if len(missing) > 4 else ''})"
        )
    # a run that produced these cannot have been right (run_scene never writes them)
    wrong = [key for key in FINITE if not _finite(values[key])]
    if wrong:
        raise UnreadableResult(f"{path}: not a result ({', '.join(wrong)} not a finite number)")
    return values


def _finite(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def write_json_atomically(data: dict, path: Path | str) -> None:
    """Write JSON so that a reader sees either nothing or the whole file."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    with os.fdopen(fd, "w") as handle:
        json.dump(data, handle, indent=1, sort_keys=True)
        handle.write("\n")
    os.replace(tmp, path)
