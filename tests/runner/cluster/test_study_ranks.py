"""A study whose impacts run on several MPI ranks each ([run] ranks, --ranks):
its rows are `runner impact --np`'s bit for bit, a LAMMPS error costs exactly
its impact, a killed worker leaves no LAMMPS behind, and ranks the workers'
cores cannot hold are refused before any work. Under Slurm: tests/runner/cluster/test_slurm.py.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest

from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.errors import InputError
from ground.launch import lammps_error
from runner.__main__ import main
from runner.cluster.tasks import STARTED, impact_task
from runner.options import DEFAULT_DT, RunOptions, on_ranks
from runner.study import Study
from runner.study.file import read_study_file, study_file_text
from tests.helpers import (
    RANKS_STUDY,
    ROOT,
    RUNS,
    SMALL,
    impact_rows_on_ranks,
    study_on_ranks,
    without_times,
)

CORES = os.cpu_count() or 1
two_cores = pytest.mark.skipif(CORES < 2, reason="two ranks need two cores")


@pytest.mark.lammps
@pytest.mark.mpi
@pytest.mark.slow
@two_cores
def test_a_study_on_two_ranks_gives_runner_impacts_rows_bit_for_bit(tmp_path):
    rows = study_on_ranks(tmp_path, "test_ranks_local")
    assert len(rows) == 2
    assert without_times(rows) == without_times(impact_rows_on_ranks(rows, tmp_path))
    # each impact on two ranks, by mpirun (the study's own run.json is its provenance)
    for run in (r.parent / "run.json" for r in (RUNS / "test_ranks_local").rglob("result.json")):
        record = json.loads(run.read_text())
        assert record["options"]["nprocs"] == 2
        assert record["launcher"] == "mpirun --bind-to none -np 2"


@pytest.mark.lammps
@pytest.mark.mpi
@two_cores
def test_a_lammps_error_on_two_ranks_fails_exactly_its_impact(tmp_path, monkeypatch):
    """lmp's ERROR ends lmp, not the worker: the task records the impact as
    failed with its log's ERROR line, as a worker's next start does today."""
    monkeypatch.setenv("IMPACT_RUNS", str(tmp_path))
    options = on_ranks(RunOptions(route="python", tmax=2.0), 2)  # leaves no time to rebound
    study = Study("ranks_error", lattices=("random",), angles=2, samples=1, options=options,
                  **SMALL)  # fmt: skip
    job = study.prepare()[0]
    outcome = impact_task(study, job)
    folder = Path(job["folder"])
    error = lammps_error(folder / "log.lammps", "no ERROR in the log")
    assert error.startswith("ERROR: the disk has not left the wall by tmax = 2")
    # a disk still on the wall at tmax is an outcome of its own, recorded as failed.json is
    assert outcome["state"] == "stuck" and outcome["error"] == error
    assert json.loads((folder / "failed.json").read_text())["error"] == error
    assert not (folder / STARTED).exists()


@pytest.mark.lammps
@pytest.mark.mpi
@two_cores
def test_a_killed_worker_leaves_no_lammps_running(tmp_path):
    """The process running lmp under mpirun is SIGKILLed, as a worker killed
    from outside is: mpirun and its ranks end too, rather than write into the
    folder the impact's next start uses (the run would take minutes)."""
    scene = write_scene(build_scene(SceneSpec(**SMALL)), tmp_path / "scene")
    variables = {"scene": str(scene), "out": str(scene), "early_stop": "no",
                 **RunOptions(dt=DEFAULT_DT, tmax=1000.0).deck_variables()}  # fmt: skip
    code = (
        "import sys, json; from pathlib import Path; from ground.launch import run_lmp; "
        "run_lmp(json.loads(sys.argv[1]), Path(sys.argv[2]), 2)"
    )
    parent = subprocess.Popen(
        [sys.executable, "-c", code, json.dumps(variables), str(scene / "log.lammps")], cwd=ROOT
    )
    children: list = []
    try:
        deadline, ranks = time.monotonic() + 60, []
        while len(ranks) < 2 and time.monotonic() < deadline:
            time.sleep(0.2)
            children = psutil.Process(parent.pid).children(recursive=True)
            ranks = [p for p in children if p.name() == "lmp"]
        assert len(ranks) == 2, "lmp did not start on two ranks"
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        _, alive = psutil.wait_procs(children, timeout=15)
        assert not alive, [p.name() for p in alive]
    finally:  # only what this test started
        if parent.poll() is None:
            parent.kill()
            parent.wait()
        for process in children:
            if process.is_running():
                process.kill()


def test_a_study_files_ranks_read_back_and_run_lmp(tmp_path):
    path = tmp_path / "ranks.toml"
    path.write_text(RANKS_STUDY)
    study = read_study_file(path).study
    assert (study.options.nprocs, study.options.route) == (2, "lmp")
    assert "ranks = 2" in study_file_text(read_study_file(path))
    again = tmp_path / "again.toml"
    again.write_text(study_file_text(read_study_file(path)))
    assert read_study_file(again).study.options == study.options
    one = tmp_path / "one.toml"
    one.write_text(RANKS_STUDY.replace("ranks = 2", "ranks = 1"))
    assert (read_study_file(one).study.options.nprocs, read_study_file(one).study.options.route) \
        == (1, "python")  # fmt: skip


@pytest.mark.parametrize("value", ["0", "-1", "2.5", "true", '"2"', "[1, 2]", "5000"])
def test_a_study_files_bad_ranks_are_refused(tmp_path, value):
    path = tmp_path / "bad.toml"
    path.write_text(RANKS_STUDY.replace("ranks = 2", f"ranks = {value}"))
    with pytest.raises(InputError, match=r"bad.toml: \[run\] ranks .* must be an integer in "):
        read_study_file(path)


def test_ranks_with_nprocs_is_refused(tmp_path):
    path = tmp_path / "both.toml"
    path.write_text(RANKS_STUDY + "nprocs = 2\n")
    with pytest.raises(InputError, match=r"\[run\] gives ranks and nprocs"):
        read_study_file(path)


@pytest.mark.parametrize(
    ("options", "refusal"),
    [
        (["--ranks", str(CORES + 1)], f"must be at most this machine's {CORES} cores"),
        (["--ranks", "2", "--workers", str(CORES)], "more than this machine's"),
        (["--ranks", "2", "--cluster", "slurm", "--cores-per-job", "3"],
         "--cores-per-job must be a multiple of it"),
        (["--ranks", "4", "--cluster", "slurm", "--cores-per-job", "2"],
         "--cores-per-job must be a multiple of it"),
    ],
)  # fmt: skip
def test_ranks_the_workers_cannot_hold_are_refused_before_any_work(
    options, refusal, capsys, monkeypatch
):
    """One line, exit 2, nothing written, no cluster made (Slurm not needed)."""
    started = []
    monkeypatch.setattr("runner.cluster.driver.dask_client", started.append)
    name = f"test_ranks_refused_{len(options)}_{options[-1]}"
    if "--workers" in options and CORES < 2:
        pytest.skip("two ranks need two cores")
    assert main(["study", "demo", "--name", name, *options]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and refusal in err and "ranks" in err, err
    assert not started and not (RUNS / name).exists()
