"""A study's tables hold physics only: the run's provenance (git revisions,
wall clock, LAMMPS seconds) goes to run.json beside them (issue 47), so that
tables made again from themselves, or by a rerun that reproduces every
impact, are byte for byte the committed ones."""

from __future__ import annotations

import csv
import json
import shutil

from analysis.study_tables import PROVENANCE, RUN_RECORD, tidy_tables, write_records
from tests.helpers import ROOT

SPEED = ROOT / "docs" / "studies" / "speed"


def old_format(folder, revisions=("abc123", "def456")):
    """The speed study's tables as they were before run.json: each row's git
    revision a column of impacts.csv, the wall clock in study.json."""
    run = json.loads((folder / RUN_RECORD).read_text())
    (folder / RUN_RECORD).unlink()
    with (folder / "impacts.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    columns = [*rows[0].keys(), "git_revision"]
    for i, row in enumerate(rows):
        row["git_revision"] = revisions[i % len(revisions)]
    with (folder / "impacts.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns)
        writer.writeheader()
        writer.writerows(rows)
    info = json.loads((folder / "study.json").read_text())
    info.update({k: run[k] for k in ("wall_clock", "lammps_seconds")})
    (folder / "study.json").write_text(json.dumps(info, indent=1))
    return run


def test_tidy_tables_move_the_provenance_to_run_json(tmp_path):
    folder = tmp_path / "speed"
    shutil.copytree(SPEED, folder)
    committed = {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}
    run = old_format(folder)
    tidy_tables(folder)
    with (folder / "impacts.csv").open() as handle:
        assert "git_revision" not in next(csv.reader(handle))
    assert not set(PROVENANCE) & set(json.loads((folder / "study.json").read_text()))
    moved = json.loads((folder / RUN_RECORD).read_text())
    assert moved["git_revisions"] == ["abc123", "def456"]
    assert moved["wall_clock"] == run["wall_clock"]
    # the physics as committed, byte for byte; made again, the same
    for name in ("impacts.csv", "study.json", "failed.csv"):
        assert (folder / name).read_bytes() == committed[name], name
    before = {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}
    tidy_tables(folder)
    assert {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()} == before


def test_a_rerun_that_reproduces_keeps_the_run_record(tmp_path):
    info = {"name": "s", "wall_clock": {"seconds": 1.0}, "lammps_seconds": 2.0}
    rows = [{"git_revision": "new"}]
    (tmp_path / RUN_RECORD).write_text("the committed run")
    write_records(info, rows, tmp_path, keep_run=True)
    assert (tmp_path / RUN_RECORD).read_text() == "the committed run"
    assert json.loads((tmp_path / "study.json").read_text()) == {"name": "s"}
    write_records(info, rows, tmp_path)
    assert json.loads((tmp_path / RUN_RECORD).read_text()) == {
        "git_revisions": ["new"],
        "wall_clock": {"seconds": 1.0},
        "lammps_seconds": 2.0,
    }
