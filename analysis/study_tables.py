"""A study's tables: impacts.csv, failed.csv and study.json written from its
runs' folders and read back (a page made again from them reads them here;
pages.report makes the page), and run.json, the run's provenance.

The tables hold physics only: what was asked (study.json) and what came out
(impacts.csv, failed.csv, means.csv, fits.json). Where, with which revision
and how long the run ran is run.json's; a rerun that reproduces every
impact byte for byte leaves the committed run.json as it was, so that it
leaves ``git status`` clean."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

from ground.errors import InputError
from ground.gate import gate, write_json, write_text

from . import speed
from .impact.failures import impact_state, state_of
from .impact.result import BINARY_FINITE, FINITE
from .table import (
    MEAN_COLUMNS,
    TIMING_COLUMNS,
    TIMINGS,
    rounded,
    table_columns,
    with_model_readings,
    write_csv,
)


def read_failure(job: dict) -> dict:
    """A failed impact's failed.json, with its state (failed, or stuck: its
    disk stayed on the wall); a damaged one is a failure of its own cause."""
    path = Path(job["folder"]) / "failed.json"
    try:
        failure = json.loads(path.read_text())
        failure["state"] = failure.get("state") or impact_state(failure["error"])
        return failure
    except (ValueError, TypeError, KeyError) as error:
        return {
            **job,
            "state": "failed",
            "error": f"unreadable failed.json ({type(error).__name__})",
        }


# failed.csv: the impacts without a result; state: failed (the run did not go
# as asked) or stuck (the disk had not left the wall by tmax: analysis.impact.failures)
FAILED_COLUMNS = ("lattice", "seed", "gamma", "vn", "state", "error")


def record_timings(study, rows: list[dict]) -> dict:
    """timings.csv in the study's folder (each finished impact's LAMMPS
    seconds), and their sum in its study.json (lammps_seconds, which the page
    states and which the tables' copy of study.json keeps); returns study.json."""
    write_csv(rows, study.folder / TIMINGS, TIMING_COLUMNS)
    path = study.folder / "study.json"
    info = json.loads(path.read_text())
    info["lammps_seconds"] = round(sum(float(r["wall_seconds"] or 0.0) for r in rows), 1)
    write_text(path, json.dumps(info, indent=1))
    return info


# What a study's record says about its run rather than its physics: the
# revisions of the code that ran its impacts (each result.json's), the whole
# run's wall clock and CPU (runner.study.provenance) and its LAMMPS seconds.
PROVENANCE = ("git_revisions", "wall_clock", "lammps_seconds")
RUN_RECORD = "run.json"


def public_record(info: dict) -> str:
    """study.json as a study's tables keep it: without the grid its study file
    gave (runs' own record, runner.study.Study.source) and without the run's
    provenance (``run_record``)."""
    return json.dumps(
        {k: v for k, v in info.items() if k != "source" and k not in PROVENANCE}, indent=1
    )


def run_record(info: dict, rows: list[dict]) -> str:
    """run.json of a study's tables: the git revisions its impacts were run
    at (from the rows where they have them, else the record's), the whole
    run's wall clock and its LAMMPS seconds."""
    revisions = sorted({str(r["git_revision"]) for r in rows if r.get("git_revision")})
    record = {"git_revisions": revisions or list(info.get("git_revisions", []))}
    record.update({k: info[k] for k in PROVENANCE[1:] if k in info})
    return json.dumps(record, indent=1)


def write_records(info: dict, rows: list[dict], folder: Path, keep_run: bool = False) -> None:
    """study.json and run.json of a study's tables into ``folder``; with
    ``keep_run`` an existing run.json stays as it is (a rerun that
    reproduced the committed impacts)."""
    write_text(folder / "study.json", public_record(info))
    if not (keep_run and (folder / RUN_RECORD).is_file()):
        write_text(folder / RUN_RECORD, run_record(info, rows))


def read_tables(tables: Path) -> tuple[dict, list[dict], list[dict]]:
    """study.json, impacts.csv's rows and failed.csv's of a study's tables.

    Tables from elsewhere are checked as result.json files are: a number that
    is missing or not finite stops the page, before anything is written.

    Raises
    ------
    ground.errors.InputError
        If the folder holds no study's tables, or a row lacks a number.
    """

    def read(name: str) -> list[dict]:
        with (tables / name).open() as handle:
            return list(csv.DictReader(handle))

    try:
        info = json.loads((tables / "study.json").read_text(encoding="utf-8"))
        if not isinstance(info, dict):
            raise ValueError(f"study.json is a JSON {type(info).__name__}, not a study's record")
        if (tables / RUN_RECORD).is_file():  # the run's provenance, beside the physics
            run = json.loads((tables / RUN_RECORD).read_text(encoding="utf-8"))
            info = {**{k: run[k] for k in PROVENANCE if k in run}, **info}
        rows, failed = read("impacts.csv"), read("failed.csv")
        if not rows and not failed:  # a garbage or empty table: no page of nan
            raise ValueError("impacts.csv and failed.csv hold no impact")
        rows = [with_model_readings(row) for row in rows]
        for failure in failed:  # failed.csv from before its state column
            failure["state"] = state_of(failure)
        if "lammps_seconds" not in info:  # tables whose rows had their seconds
            info["lammps_seconds"] = round(sum(float(r.get("wall_seconds") or 0) for r in rows), 1)
        for line, row in enumerate(rows, start=2):
            finite = BINARY_FINITE if row.get("target") == "disk" else FINITE
            # a table's row has no time (timings.csv, study.json's lammps_seconds)
            finite = [k for k in finite if k != "wall_seconds"]
            bad = [k for k in finite if not math.isfinite(float(row.get(k) or "nan"))]
            if bad:
                raise ValueError(f"line {line}: {', '.join(bad)} not a finite number")
    except (OSError, ValueError, KeyError, TypeError, AttributeError, csv.Error) as error:
        raise InputError(f"--from-tables: {tables} holds no study's tables ({error})") from None
    return info, rows, failed


def tidy_tables(tables: Path) -> None:
    """A study's tables in this version's format, from themselves alone (no
    run, nothing recomputed): impacts.csv without wall-clock seconds (their
    sum into run.json's lammps_seconds) or git revisions (run.json's),
    study.json without the run's provenance (run.json), failed.csv with each impact's
    state, the numbers of means.csv, fits.json and speed.json to
    ``TABLE_DIGITS``. Tables already so are left byte for byte."""
    info, rows, failed = read_tables(tables)
    gate(tables)  # the one gate of every write (ground.gate)
    write_csv(rows, tables / "impacts.csv", table_columns(rows))
    write_csv(failed, tables / "failed.csv", FAILED_COLUMNS)
    write_records(info, rows, tables)
    if (tables / "fits.json").is_file():
        fits = rounded(json.loads((tables / "fits.json").read_text()))
        write_json(tables / "fits.json", fits)
    if (tables / "speed.json").is_file():
        numbers = rounded(json.loads((tables / "speed.json").read_text()))
        speed.write_json(numbers, tables / "speed.json")
    if (tables / "means.csv").is_file():
        with (tables / "means.csv").open() as handle:
            means = [{k: number_text(v) for k, v in r.items()} for r in csv.DictReader(handle)]
        write_csv(means, tables / "means.csv", MEAN_COLUMNS)


def number_text(text: str) -> str:
    """A table's cell with its number (a float's: with a point or an exponent)
    to ``TABLE_DIGITS``; integers and words as they are."""
    try:
        value = float(text)
    except ValueError:
        return text
    return str(rounded(value)) if any(c in text for c in ".eE") else text


def write_study_tables(rows: list[dict], failed: list[dict], out: Path) -> list[dict]:
    """impacts.csv (its rows in the tables' order: lattice, v_n, angle, seed)
    and failed.csv into ``out``; returns the rows in that order."""
    rows = sorted(
        rows,
        key=lambda r: (
            r["study_lattice"],
            float(r["vn"]),
            float(r["gamma_deg"]),
            float(r["seed"]),
        ),
    )
    write_csv(rows, out / "impacts.csv", table_columns(rows))
    write_csv(failed, out / "failed.csv", FAILED_COLUMNS)
    return rows
