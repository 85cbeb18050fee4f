"""What a worker's task decides from an impact's folder (runner.cluster.tasks): the
impact that ended a worker with a LAMMPS error fails with that error, one
killed from outside runs again, a settled one is not run again."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from runner.cluster.tasks import MAX_ATTEMPTS, STARTED, impact_task
from runner.study import Study

ERROR = "ERROR: the disk slid off the end of the wall before it rebounded, at time 5.6"


@pytest.fixture
def job(tmp_path, monkeypatch):
    monkeypatch.setenv("IMPACT_RUNS", str(tmp_path))
    study = Study("tasks", lattices=("random",), angles=2, samples=1, n_disk=200)
    study.prepare()
    return study, study.jobs()[0]


def listing(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir()}


@pytest.mark.parametrize("settled", ["result.json", "failed.json"])
def test_a_settled_impact_is_not_run_again(job, settled):
    study, one = job
    folder = Path(one["folder"])
    folder.mkdir(parents=True)
    (folder / settled).write_text("{}")
    (folder / STARTED).write_text(json.dumps({"attempts": 1}))
    before = listing(folder)
    assert impact_task(study, one) == {"folder": one["folder"], "state": "settled"}
    assert listing(folder) == before


def test_a_start_that_ended_with_a_lammps_error_fails_with_it(job):
    study, one = job
    folder = Path(one["folder"])
    folder.mkdir(parents=True)
    (folder / STARTED).write_text(json.dumps({"attempts": 1}))
    (folder / "log.lammps").write_text(f"LAMMPS (29 Sep 2021)\nrun 100\n{ERROR} (src/x.cpp:12)\n")
    outcome = impact_task(study, one)
    assert outcome["state"] == "failed" and outcome["error"] == ERROR
    assert json.loads((folder / "failed.json").read_text())["error"] == ERROR
    assert not (folder / STARTED).exists() and not (folder / "result.json").exists()


def test_an_impact_that_keeps_ending_its_worker_without_an_error_fails(job):
    study, one = job
    folder = Path(one["folder"])
    folder.mkdir(parents=True)
    (folder / STARTED).write_text(json.dumps({"attempts": MAX_ATTEMPTS}))
    (folder / "log.lammps").write_text("LAMMPS (29 Sep 2021)\nrun 100\n")
    outcome = impact_task(study, one)
    assert outcome["state"] == "failed"
    assert f"ended its worker {MAX_ATTEMPTS} times without a LAMMPS error" in outcome["error"]


@pytest.mark.lammps
def test_an_impact_killed_from_outside_runs_again(job):
    """A start without a result and without an ERROR (SIGKILL, a walltime):
    the impact runs, here, with LAMMPS, and its marker goes."""
    study, one = job
    folder = Path(one["folder"])
    folder.mkdir(parents=True)
    (folder / STARTED).write_text(json.dumps({"attempts": 1}))
    (folder / "log.lammps").write_text("LAMMPS (29 Sep 2021)\nrun 100\n")
    outcome = impact_task(study, one)
    assert outcome["state"] == "done", outcome
    result = json.loads((folder / "result.json").read_text())
    assert (outcome["e"], outcome["beta"]) == (result["e"], result["beta"])
    assert not (folder / STARTED).exists() and not (folder / "log.lammps").exists()
