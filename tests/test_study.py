"""The study's sweep: resumable, crash-tolerant, the same on partitions."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import time

import pytest

from runner.pool import run_jobs
from runner.study import Study, job_groups

from tests.helpers import ROOT

TINY = ["--lattices", "random", "--angles", "3", "--samples", "2", "--n-disk", "200"]
COMPARED = ("study_lattice", "seed", "gamma_deg", "cot_gamma", "e", "beta", "omega", "steps",
            "contact_time")


def study(name: str, *extra: str, wait: bool = True):
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *TINY, *extra]
    if wait:
        return subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    return subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)


def table(name: str) -> list[tuple]:
    with (ROOT / "runs" / name / "impacts.csv").open() as handle:
        return [tuple(row[c] for c in COMPARED) for row in csv.DictReader(handle)]


@pytest.fixture(scope="module")
def uninterrupted():
    name = "test_study_whole"
    subprocess.run(["rm", "-rf", str(ROOT / "runs" / name)])
    proc = study(name)
    assert proc.returncode == 0, proc.stderr
    return table(name)


def test_a_killed_study_resumes_and_loses_nothing(uninterrupted):
    name = "test_study_killed"
    folder = ROOT / "runs" / name
    subprocess.run(["rm", "-rf", str(folder)])
    proc = study(name, wait=False)
    deadline = time.monotonic() + 300
    while not any(folder.glob("random/*/*/result.json")) and time.monotonic() < deadline:
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    finished = len(list(folder.glob("random/*/*/result.json")))
    assert 1 <= finished < 6                              # killed half-way
    resumed = study(name)
    assert resumed.returncode == 0, resumed.stderr
    assert f"{finished} already done" in resumed.stdout
    assert table(name) == uninterrupted


def test_two_partitions_give_the_serial_results(uninterrupted):
    name = "test_study_partitions"
    subprocess.run(["rm", "-rf", str(ROOT / "runs" / name)])
    proc = study(name, "--partitions", "2", "--batch-size", "1")   # 3 MPI jobs, built ahead
    assert proc.returncode == 0, proc.stderr
    assert table(name) == uninterrupted


def test_a_crashing_job_is_reported_and_the_others_finish():
    def job(x):
        if x == 3:
            os._exit(7)                                   # as LAMMPS does on an error
        if x == 5:
            raise ValueError("bad input")
        return x * x

    done, failed = {}, {}
    run_jobs(job, list(range(9)), [[0, 1, 2, 3, 4, 5], [6, 7, 8]], 2,
             on_done=done.__setitem__, on_failed=failed.__setitem__)
    assert done == {i: i * i for i in (0, 1, 2, 4, 6, 7, 8)}
    assert set(failed) == {3, 5}
    assert "exit status 7" in failed[3] and "ValueError: bad input" in failed[5]


def test_many_crashes_in_many_groups_lose_no_job():
    def job(x):
        if x % 7 == 3:
            os._exit(1)
        return -x

    jobs = list(range(60))
    groups = [jobs[i:i + 6] for i in range(0, 60, 6)]
    for _ in range(5):                                    # a lost result or a hang shows by chance
        done, failed = {}, {}
        run_jobs(job, jobs, groups, 2, on_done=done.__setitem__, on_failed=failed.__setitem__)
        assert set(failed) == {x for x in jobs if x % 7 == 3}
        assert done == {x: -x for x in jobs if x % 7 != 3}


@pytest.mark.parametrize("samples, lattices, angles, per_group", [
    (20, 2, 3, 6),         # whole samples: the wall is built once per seed
    (4, 4, 2, 2),          # few samples: a lattice of a sample each
    (1, 1, 3, 1),          # one lattice of one sample: single impacts
])
def test_job_groups_keep_every_worker_busy(samples, lattices, angles, per_group):
    names = ("random", "triangular", "square_nu0.1", "square_nu0.3")[:lattices]
    jobs = Study("groups", lattices=names, angles=angles, samples=samples).jobs()
    groups = job_groups(jobs, workers=2)
    assert sorted(i for g in groups for i in g) == list(range(len(jobs)))
    assert [len(g) for g in groups] == sorted((len(g) for g in groups), reverse=True)
    assert {len(g) for g in groups} == {per_group}
    for group in groups:
        assert len({jobs[i]["seed"] for i in group}) == 1
