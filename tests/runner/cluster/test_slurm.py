"""The cluster path under a real Slurm: a one-node Slurm on this host, started
for these tests (tests/local_slurm.py) and stopped by its daemons' pids.

Where it cannot be started (not root, Slurm not installed) the tests skip,
saying why; under CI (CI=true) they fail instead.
"""

from __future__ import annotations

import csv
import json
import os
import re
import subprocess
import sys
import time

import pytest

from tests.helpers import (
    ROOT,
    RUNS,
    genuine_failures,
    impact_rows_on_ranks,
    run_crash_scenario,
    study_on_ranks,
    without_times,
)
from tests.local_slurm import SlurmUnavailable, one_node_slurm, why_not

pytestmark = [pytest.mark.slurm, pytest.mark.lammps, pytest.mark.slow]

SMALL_STUDY = ["--lattices", "random", "--angles", "4", "--samples", "2", "--n-disk", "200"]
ON_SLURM = ["--cluster", "slurm", "--jobs", "1", "--cores-per-job", "2"]


@pytest.fixture(scope="module")
def slurm(tmp_path_factory):
    """The environment of Slurm's clients (SLURM_CONF) for this module's tests."""
    problem = why_not()
    if problem is None:
        try:
            with one_node_slurm(tmp_path_factory.mktemp("slurm")) as env:
                yield {**os.environ, **env}
            return
        except SlurmUnavailable as error:
            problem = str(error)
    if os.environ.get("CI") == "true":
        pytest.fail(f"Slurm could not be started under CI: {problem}")
    pytest.skip(f"no Slurm here: {problem}")


def study(name: str, *options: str, env: dict, wait: bool = True):
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *options]
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    if not wait:
        return subprocess.Popen(command, cwd=ROOT, env=env, stdout=subprocess.PIPE, text=True)
    return subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)


def rows(name: str) -> list[dict]:
    with (RUNS / name / "impacts.csv").open() as handle:
        return [
            {k: row[k] for k in ("seed", "gamma_deg", "e", "beta", "omega", "steps")}
            for row in csv.DictReader(handle)
        ]


def our_jobs(env: dict) -> list[str]:
    out = subprocess.run(["squeue", "-h", "-o", "%i"], env=env, capture_output=True, text=True)
    return out.stdout.split()


def test_a_study_on_slurm_gives_the_local_results_bit_for_bit(slurm):
    local = study("test_slurm_local", *SMALL_STUDY, env=slurm)
    assert local.returncode == 0, local.stderr
    on_slurm = study("test_slurm_jobs", *SMALL_STUDY, *ON_SLURM, env=slurm)
    assert on_slurm.returncode == 0, on_slurm.stderr
    assert len(rows("test_slurm_jobs")) == 8
    assert rows("test_slurm_jobs") == rows("test_slurm_local")
    assert list((RUNS / "test_slurm_jobs" / "slurm").glob("*.err"))  # the jobs' own output
    deadline = time.monotonic() + 30
    while our_jobs(slurm) and time.monotonic() < deadline:  # the jobs were cancelled
        time.sleep(0.5)
    assert not our_jobs(slurm)


def test_a_lammps_error_on_slurm_costs_exactly_its_impact(slurm):
    proc = run_crash_scenario("test_slurm_crashes", *ON_SLURM, env=slurm)
    assert proc.returncode == 1, proc.stderr
    genuine_failures(RUNS / "test_slurm_crashes", proc)


def test_a_slurm_job_that_ends_is_replaced_and_fails_no_impact(slurm):
    """scancel, as a walltime does, ends the workers' job in the middle of the
    study: a new job takes over and no impact counts as failed."""
    name = "test_slurm_job_ended"
    proc = study(name, "--lattices", "random", "--angles", "8", "--samples", "8", *ON_SLURM,
                 env=slurm, wait=False)  # fmt: skip
    try:
        deadline = time.monotonic() + 300
        while not any((RUNS / name).rglob("result.json")) and time.monotonic() < deadline:
            time.sleep(0.2)
        jobs = our_jobs(slurm)
        assert len(jobs) == 1, jobs
        subprocess.run(["scancel", jobs[0]], env=slurm, check=True)
        out, _ = proc.communicate(timeout=600)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0, out
    assert "1 batch job(s) ended; as many submitted again" in out
    assert not list((RUNS / name).rglob("failed.json"))
    assert len(list((RUNS / name).rglob("result.json"))) == 64


def test_the_documented_batch_script_runs_as_written(slurm, tmp_path):
    """docs/cluster/slurm_study.sh under sbatch, with a tiny study: the driver is a
    job, its workers another."""
    name = "test_slurm_script"
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    tiny = ["demo", "--name", name, "--lattices", "random", "--angles", "2", "--samples", "1",
            "--n-disk", "200", "--jobs", "1", "--cores-per-job", "1",
            "--walltime", "00:10:00"]  # fmt: skip
    proc = subprocess.run(
        ["sbatch", "--wait", f"--output={tmp_path}/driver-%j.out", f"--chdir={ROOT}",
         str(ROOT / "docs" / "cluster" / "slurm_study.sh"), *tiny],
        env=slurm, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    log = "".join(p.read_text() for p in tmp_path.glob("driver-*.out"))
    assert proc.returncode == 0, proc.stderr + log
    assert "2 impacts, 0 failed" in log, log
    assert len(list((RUNS / name).rglob("result.json"))) == 2


@pytest.mark.mpi
def test_one_impact_on_two_ranks_under_srun_gives_mpiruns_result(slurm, tmp_path):
    results = {}
    for launcher in ("", "srun --mpi=pmix"):
        env = {**slurm, "IMPACT_MPIRUN": launcher}
        out = tmp_path / (launcher.split()[0] if launcher else "mpirun")
        proc = subprocess.run(
            [sys.executable, "-m", "runner", "impact", "--n-disk", "200", "--gamma", "30",
             "--np", "2", "--out", str(out)],
            cwd=ROOT, env=env, capture_output=True, text=True, timeout=600,
        )  # fmt: skip
        assert proc.returncode == 0, proc.stderr
        result = json.loads((out / "result.json").read_text())
        results[launcher or "mpirun"] = (result["e"], result["beta"], result["steps"])
        assert " on 2 procs for " in (out / "log.lammps").read_text()  # two ranks, each way
    assert results["srun --mpi=pmix"] == results["mpirun"]


@pytest.mark.mpi
@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="two ranks need two cores")
def test_a_study_on_two_ranks_under_srun_gives_runner_impacts_rows(slurm, tmp_path):
    """[run] ranks = 2 on Slurm: each job's worker owns 2 cores and starts
    each impact as a step of them (srun --mpi=pmix); the rows are those of
    `runner impact --np 2` under mpirun, bit for bit."""
    name = "test_slurm_ranks"
    rows = study_on_ranks(tmp_path, name, *ON_SLURM, env=slurm)
    assert len(rows) == 2
    assert without_times(rows) == without_times(impact_rows_on_ranks(rows, tmp_path))
    # each impact's run.json (the study's own, beside its tables, has no launcher)
    for run in (r.parent / "run.json" for r in (RUNS / name).rglob("result.json")):
        assert json.loads(run.read_text())["launcher"] == "srun --mpi=pmix -n 2"
    worker = "".join(path.read_text() for path in (RUNS / name / "slurm").glob("*.err"))
    assert len(re.findall(r"Threads:\s+1\n", worker)) == 1  # one worker, an impact at a time
