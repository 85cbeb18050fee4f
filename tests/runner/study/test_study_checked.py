"""Results checked against their study (issue 44), as the user runs it: a
finished impact made with other options is refused in one line naming the
option, also when study.json was deleted; a corrupted record is rerun, not
fatal; a corrupted study.json is one line naming it."""

from __future__ import annotations

import itertools
import json
import os
import shutil
import subprocess
import sys

import pytest

from tests.helpers import ROOT, RUNS

COPIES = itertools.count()
SMALL = '[grid]\nlattices = ["random"]\nangles = 2\nsamples = 1\n[scene]\nn_disk = 200\n'


def study(path, name: str, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "runner", "study", str(path), "--name", name, *extra],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "IMPACT_RUNS": str(RUNS)},
    )


def one_line(done: subprocess.CompletedProcess, says: str) -> None:
    errors = done.stderr.strip()
    assert done.returncode == 2, (done.stdout, errors)
    assert len(errors.splitlines()) == 1 and "Traceback" not in errors, errors
    assert says in errors, errors


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A small study, run once: its file and its folder's name."""
    file = tmp_path_factory.mktemp("checked") / "checked.toml"
    file.write_text(SMALL)
    done = study(file, "h44_checked", "--workers", "1")
    assert done.returncode == 0, done.stderr
    return file


@pytest.fixture
def copy(finished):
    """A fresh copy of the finished study's folder, under its own name."""
    name = f"h44_checked_{next(COPIES)}"
    shutil.rmtree(RUNS / name, ignore_errors=True)
    shutil.copytree(RUNS / "h44_checked", RUNS / name, symlinks=True)
    record = json.loads((RUNS / name / "study.json").read_text())
    for job in RUNS.joinpath(name).rglob("g*"):
        assert job.is_dir()
    (RUNS / name / "study.json").write_text(json.dumps({**record, "name": name}))
    for path in (RUNS / name).rglob("*.json"):  # the impacts' jobs name their folders
        text = path.read_text().replace("/h44_checked/", f"/{name}/")
        path.write_text(text)
    return name


def test_a_finished_impact_of_another_speed_is_refused_without_study_json(finished, copy):
    (RUNS / copy / "study.json").unlink()
    done = study(finished, copy, "--vn", "0.05", "--workers", "1")
    one_line(done, "was made with vn 0.1; the study asks 0.05: remove")
    # nothing recorded: study.json does not claim the other speed
    assert not (RUNS / copy / "study.json").exists()
    one_line(study(finished, copy, "--vn", "0.05", "--report-only"), "no study in")


def test_a_changed_run_option_is_named_alone(finished, copy):
    done = study(finished, copy, "--dt", "0.01", "--workers", "1")
    one_line(done, "options.dt 'auto' there, 0.01 asked;")
    (RUNS / copy / "study.json").unlink()
    one_line(study(finished, copy, "--dt", "0.01", "--workers", "1"), "was made with dt ")


@pytest.mark.parametrize("text", ["[]", "null", "{", "", '{"lattices": 3}'])
def test_a_corrupted_study_json_is_one_line(finished, copy, text):
    (RUNS / copy / "study.json").write_text(text)
    one_line(study(finished, copy, "--workers", "1"), f"{RUNS / copy / 'study.json'}: not a")


@pytest.mark.parametrize("name", ["scene.json", "run.json"])
def test_a_corrupted_finished_impact_runs_again(finished, copy, name):
    folder = next((RUNS / copy).rglob("g80.5000"))
    (folder / name).write_text("{")
    done = study(finished, copy, "--workers", "1")
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert f"{folder}: its scene.json or run.json cannot be read" in done.stderr
    assert "1 already done or failed, 1 to run" in done.stdout
    assert json.loads((folder / name).read_text())  # made again
    assert (folder / "result.json.corrupt").is_file()


def test_an_impact_that_took_more_halvings_than_the_study_allows_is_refused(finished, copy):
    """barrier_halvings is a budget (runner.study.folders.RUN_ANY_WAY): a done
    impact is checked at the step it took, and refused if it took more
    halvings than the study allows."""
    folder = next((RUNS / copy).rglob("g80.5000"))
    run = json.loads((folder / "run.json").read_text())
    (RUNS / copy / "study.json").unlink()
    run["dt_halvings"] = 3
    run["options"]["dt"] /= 8
    (folder / "run.json").write_text(json.dumps(run))
    one_line(study(finished, copy, "--workers", "1"), "ran at its step halved 3 times; the study")
