"""The readings of the scene by name (docs/model.md section 8), and the rows, table
and page frame that the readings studies share (studies/scene_readings.toml,
model_readings.toml, fact_sensitivity.toml; their pages: analysis.kinds).

A study file names a wall (``wall = "1600_10ka_sides"``: points, ka over the
random disk's, held) and a reading of the model (``model = "disk-mass"``:
the choices changed from the first reading) instead of spelling out their
options; a list of names is an axis like a list of values.
"""

from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field
from pathlib import Path

from builder.study_names import (  # noqa: F401 (the readings by name live there)
    LIMITS,
    MODEL_CHANGES,
    MODELS,
    N_WALL,
    NAMED,
    ONE_BODY,
    REFERENCES,
    ROUGHNESS_LENGTH,
    WALL_FIXED,
    WALL_KA,
    WALLS,
    wall_label,
)
from ground.gate import write_text

from ..impact.failures import failure_cause
from ..table import TIMINGS, write_csv

# Choices that depart from the paper's text, for the rules' tie-break: its
# sentence (800 points, one ka, the sides held), its c, its "displaced along
# the normal" and its triangular disk whose "surface is the random one's".
# "The mass of the particle" reads either way, as does the even row.
TEXT = {"n_wall": 800, "wall_ka": 1.0, "wall_fixed": "sides"}
DEPARTS = {"speed_unit": "spring", "roughness_direction": "both", "regular_surface": "lattice"}


def distance_from_text(wall: str, model: str = "first-read") -> int:
    """How many of a reading's choices depart from the paper's text."""
    return sum(WALLS[wall][k] != v for k, v in TEXT.items()) + sum(
        MODEL_CHANGES[model].get(k) == v for k, v in DEPARTS.items()
    )


def named_reading(options: dict) -> dict[str, str]:
    """The wall and model names whose options ``options`` has (those it has)."""
    out = {}
    for key, names in NAMED.items():
        for name, values in names.items():
            if all(options.get(k) == v for k, v in values.items()):
                out[key] = name
                break
    return out


@dataclass(frozen=True)
class Setup:
    """What a readings page is made from besides its rows: the study's grid
    (angles, samples, run options, as study.json records them), its
    combinations in the file's order (each option -> value or name), the
    named readings the file gives outside its axes, the re-run of the best,
    and the record of the run (command, machine, and what the kind keeps)."""

    study: dict
    choices: tuple[dict, ...]
    named: dict = field(default_factory=dict)
    rerun: dict = field(default_factory=dict)
    record: dict = field(default_factory=dict)
    figures: str = "."  # the figures' folder, relative to the page


def study_rows(study, name: str) -> list[dict]:
    """Rows of a study's impacts, finished (impacts.csv's) and failed (their
    cause), each marked as reading ``name``: what a readings table keeps."""
    from ..study_tables import read_failure
    from ..table import collect

    jobs = study.jobs()
    rows = collect([(j["lattice"], Path(j["folder"])) for j in jobs])
    for job in jobs:
        if (Path(job["folder"]) / "failed.json").exists():
            rows.append(
                {
                    "study_lattice": job["lattice"],
                    "lattice": job["lattice"],
                    "seed": job["seed"],
                    "gamma_deg": job["gamma"],
                    "error": failure_cause(read_failure(job)["error"]),
                }
            )
    for row in rows:
        row["reading"] = name
    return rows


# A readings study's tables in its folder (docs/studies/<page>/ for the committed one).
ROWS = "rows.csv"
RECORD = "run.json"


# timings.csv beside rows.csv: each finished impact's LAMMPS seconds, by its
# key; rows.csv keeps no time, so that a rerun that changes no number
# changes no byte of it (analysis.table.TIMING_COLUMNS, for a results study).
TIMING_KEY = ("reading", "study_lattice", "seed", "gamma_deg")


def read_rows(folder: Path) -> list[dict]:
    """A readings study's rows, each finished one with its wall_seconds from
    timings.csv (tables from before it have them in rows.csv)."""
    with (Path(folder) / ROWS).open() as handle:
        rows = list(csv.DictReader(handle))
    timings = Path(folder) / TIMINGS
    if timings.is_file():
        with timings.open() as handle:
            seconds = {
                tuple(t[k] for k in TIMING_KEY): t["wall_seconds"] for t in csv.DictReader(handle)
            }
        for row in rows:
            if (key := tuple(row[k] for k in TIMING_KEY)) in seconds:
                row["wall_seconds"] = seconds[key]
    return rows


def write_tables(rows: list[dict], folder: Path, columns: tuple[str, ...]) -> None:
    """rows.csv (``columns``) and timings.csv of a readings study's rows."""
    write_csv(rows, Path(folder) / ROWS, columns)
    timed = [r for r in rows if r.get("wall_seconds") not in (None, "")]
    if timed:  # tables made before runs recorded their time have none
        write_csv(timed, Path(folder) / TIMINGS, (*TIMING_KEY, "wall_seconds"))


def read_record(folder: Path) -> dict:
    """A readings study's record of its run: the command, the machine, ..."""
    return json.loads((Path(folder) / RECORD).read_text())


def write_record(record: dict, folder: Path) -> None:
    write_text(Path(folder) / RECORD, json.dumps(record, indent=1) + "\n")
