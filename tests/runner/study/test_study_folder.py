"""What a study does with the folder it finds, on copies of the tiny study's
folder: unreadable or NaN results, another grid, --extend, timings, disks that
stayed on the wall, tables from elsewhere; the page made again from the tables."""

from __future__ import annotations

import csv
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import ROOT, RUNS
from tests.runner.tiny_study import study, table

# reads the committed pages' bytes or times, which the pages made again
# rewrite: after them (Makefile)
pytestmark = pytest.mark.last


def test_an_unreadable_result_is_named_set_aside_and_run_again(uninterrupted):
    name = "test_study_corrupt"
    folder = RUNS / name
    subprocess.run(["rm", "-rf", str(folder)])
    shutil.copytree(RUNS / "test_study_whole", folder)
    results = sorted(folder.glob("random/*/*/result.json"))
    truncated, empty = results[1], results[4]
    truncated.write_text('{"e": 0.3, "bet')
    empty.write_text("{}")

    report = study(name, "--report-only")
    assert report.returncode == 0, report.stderr
    warnings = report.stderr.strip().splitlines()
    assert len(warnings) == 2 and all(line.startswith("warning: ") for line in warnings)
    assert str(truncated) in report.stderr and str(empty) in report.stderr
    assert len(table(name)) == 4  # the two left out
    assert truncated.read_text() == '{"e": 0.3, "bet'  # and left alone

    rerun = study(name)
    assert rerun.returncode == 0, rerun.stderr
    assert str(truncated) in rerun.stderr and str(empty) in rerun.stderr
    assert "4 already done" in rerun.stdout
    assert (truncated.parent / "result.json.corrupt").read_text() == '{"e": 0.3, "bet'
    assert (empty.parent / "result.json.corrupt").read_text() == "{}"
    assert table(name) == uninterrupted


def test_the_page_comes_back_from_the_tables_alone(uninterrupted, tmp_path):
    """report_from_tables remakes a study's page and means from impacts.csv,
    failed.csv and study.json, with no run folder (docs/studies/results/ for the paper)."""
    from pages.report import report_from_tables

    folder = RUNS / "test_study_whole"
    tables = tmp_path / "tables"
    tables.mkdir()
    for name in ("impacts.csv", "failed.csv", "study.json"):
        (tables / name).write_bytes((folder / name).read_bytes())
    page = tmp_path / "results.md"
    report_from_tables(tables, page, preset="demo")
    remade = page.read_text()
    where = re.search(r" \(in `[^`]*`, from which .*? without the runs\)", remade).group(0)
    assert remade.replace(where, "") == (folder / "results.md").read_text()
    assert (tables / "means.csv").read_text() == (folder / "means.csv").read_text()
    assert (tables / "fits.json").read_text() == (folder / "fits.json").read_text()


def docs_listing() -> dict[str, int]:
    return {str(p): p.stat().st_mtime_ns for p in (ROOT / "docs").rglob("*")}


def copy_of_whole(name: str) -> Path:
    folder = RUNS / name
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(RUNS / "test_study_whole", folder)
    return folder


def report_only(name: str, *options: str):
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *options]
    return subprocess.run(
        [*command, "--report-only"], cwd=ROOT, capture_output=True, text=True, timeout=600
    )


def test_report_only_takes_the_grid_from_study_json(uninterrupted):
    """The demo preset's grid is 16 angles x 4 samples; the study was made with
    3 x 2: a report without options keeps its 6 rows and writes nothing into docs/."""
    copy_of_whole("test_study_grid")
    before = docs_listing()
    proc = report_only("test_study_grid")
    assert proc.returncode == 0, proc.stderr
    assert table("test_study_grid") == uninterrupted
    assert docs_listing() == before


@pytest.mark.parametrize(
    "options, words",
    [
        (["--angles", "4"], "angles 3 there, 4 asked"),
        (["--samples", "3"], "samples 2 there, 3 asked; leave the option out"),
        (["--extend"], "--extend does not apply to --report-only"),
        (["--dt", "0.001"], "options.dt 'auto' there, 0.001 asked"),
    ],
)
def test_another_grid_for_a_study_is_refused(uninterrupted, options, words):
    folder = copy_of_whole("test_study_other_grid")
    record = (folder / "study.json").read_text()
    proc = report_only("test_study_other_grid", *options)
    assert proc.returncode == 2, proc.stdout
    assert len(proc.stderr.strip().splitlines()) == 1 and words in proc.stderr, proc.stderr
    assert (folder / "study.json").read_text() == record
    assert table("test_study_other_grid") == uninterrupted


def test_extend_adds_samples_and_never_removes(uninterrupted):
    copy_of_whole("test_study_extend")
    fewer = study("test_study_extend", "--samples", "1", "--extend")
    assert fewer.returncode == 2 and "samples 2 there, 1 asked" in fewer.stderr
    more = study("test_study_extend", "--samples", "3", "--extend")
    assert more.returncode == 0, more.stderr
    assert "6 already done" in more.stdout
    rows = table("test_study_extend")
    assert len(rows) == 9 and set(uninterrupted) < set(rows)
    assert (
        "0 of the study's 3 samples" not in (RUNS / "test_study_extend" / "results.md").read_text()
    )


def test_timings_stay_out_of_the_tables(uninterrupted):
    """impacts.csv has no wall-clock seconds: timings.csv has each impact's,
    study.json their sum; a report after impacts that took other times but
    gave the same numbers changes no byte of the tables."""
    folder = copy_of_whole("test_study_timings")
    tables = ("impacts.csv", "means.csv", "fits.json", "failed.csv")
    proc = report_only("test_study_timings")
    assert proc.returncode == 0, proc.stderr
    before = {name: (folder / name).read_bytes() for name in tables}
    with (folder / "timings.csv").open() as handle:
        timings = list(csv.DictReader(handle))
    assert "wall_seconds" not in before["impacts.csv"].decode().splitlines()[0].split(",")
    assert len(timings) == len(uninterrupted) and all(float(t["wall_seconds"]) > 0 for t in timings)
    lammps = json.loads((folder / "study.json").read_text())["lammps_seconds"]
    assert lammps == round(sum(float(t["wall_seconds"]) for t in timings), 1)
    for path in folder.rglob("result.json"):  # the same impacts, twice as slow
        result = json.loads(path.read_text())
        path.write_text(json.dumps({**result, "wall_seconds": 2 * result["wall_seconds"] + 1}))
    proc = report_only("test_study_timings")
    assert proc.returncode == 0, proc.stderr
    assert {name: (folder / name).read_bytes() for name in tables} == before
    assert json.loads((folder / "study.json").read_text())["lammps_seconds"] > lammps


@pytest.mark.parametrize(
    "error, status, said",
    [
        ("ERROR: the disk has not left the wall by tmax = 100.0", 0,
         "0 failed, in 1 the disk had not left the wall by tmax; results in"),
        ("ERROR: the disk slid off the end of the wall before it rebounded, at time 5.6", 1,
         "1 failed (1: the disk slid off the end of the wall before it rebounded)"),
    ],
)  # fmt: skip
def test_a_disk_that_stays_on_the_wall_is_an_outcome_not_a_failure(
    uninterrupted, error, status, said
):
    """An impact whose disk has not left the wall by tmax is recorded as its
    own state (failed.csv's state, its own section of the page) and the study
    has run as asked (exit 0); a failed run is a failure (exit 1)."""
    folder = copy_of_whole("test_study_stuck")
    result = sorted(folder.rglob("result.json"))[-1]
    job = json.loads(result.read_text())
    result.unlink()
    failure = {"lattice": "random", "seed": job["seed"], "gamma": job["gamma_deg"], "vn": 0.1}
    (result.parent / "failed.json").write_text(json.dumps({**failure, "error": error}))
    proc = report_only("test_study_stuck")
    assert proc.returncode == status, proc.stdout + proc.stderr
    last = proc.stdout.strip().splitlines()[-1]
    assert last.startswith(f"{len(uninterrupted) - 1} impacts") and said in last, last
    with (folder / "failed.csv").open() as handle:
        (row,) = list(csv.DictReader(handle))
    assert row["state"] == ("stuck" if status == 0 else "failed") and row["error"] == error
    page = (folder / "results.md").read_text()
    assert ("## Disks that stayed on the wall" in page) == (status == 0)
    assert ("## Failed impacts" in page) == (status == 1)


def test_a_result_with_nan_is_not_a_result(uninterrupted):
    folder = copy_of_whole("test_study_nan")
    result = sorted(folder.glob("random/*/*/result.json"))[2]
    values = json.loads(result.read_text())
    values["e"] = float("nan")
    result.write_text(json.dumps(values))  # json writes NaN
    proc = report_only("test_study_nan")
    assert proc.returncode == 0, proc.stderr
    assert str(result) in proc.stderr and "e not a finite number" in proc.stderr
    rows = table("test_study_nan")
    assert len(rows) == 5 and set(rows) < set(uninterrupted)
    for name in ("impacts.csv", "means.csv", "fits.json"):
        assert "nan" not in (folder / name).read_text().lower()


def committed_tables_copy(folder: Path) -> Path:
    folder.mkdir(parents=True)
    for name in ("impacts.csv", "failed.csv", "study.json"):
        (folder / name).write_bytes((ROOT / "docs" / "studies" / "results" / name).read_bytes())
    return folder


def test_tables_with_nan_make_no_page(tmp_path, capsys):
    from runner.__main__ import main

    tables = committed_tables_copy(tmp_path / "tables")
    text = (tables / "impacts.csv").read_text().splitlines()
    header, row = text[0].split(","), text[1].split(",")
    row[header.index("beta")] = "nan"
    (tables / "impacts.csv").write_text("\n".join([text[0], ",".join(row), *text[2:]]) + "\n")
    status = main(["study", "paper", "--from-tables", str(tables), "--name", "test_nan_tables"])
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1
    assert "line 2: beta not a finite number" in err
    assert not (RUNS / "test_nan_tables").exists()


def test_tables_never_replace_another_study(uninterrupted, tmp_path, capsys):
    from runner.__main__ import main

    folder = copy_of_whole("test_study_target")
    before = {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}
    tables = committed_tables_copy(tmp_path / "tables")
    status = main(["study", "paper", "--from-tables", str(tables), "--name", "test_study_target"])
    err = capsys.readouterr().err.strip()
    assert status == 2 and "holds a study" in err and len(err.splitlines()) == 1
    assert {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()} == before
