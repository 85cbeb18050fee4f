"""The study's sweep on Dask: resumable, crash-tolerant, stoppable."""

from __future__ import annotations

import csv
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from runner.cluster.driver import job_groups
from runner.study import Study
from tests.helpers import (
    CRASH_SCENARIO,
    ROOT,
    RUNS,
    SMALL,
    genuine_failures,
    run_crash_scenario,
    stop_by_pid,
)
from tests.runner.tiny_study import TINY, study, table


def test_a_whole_study_records_where_its_workers_time_went(uninterrupted):
    clock = json.loads((RUNS / "test_study_whole" / "study.json").read_text())["wall_clock"]
    spent = clock["worker_seconds"]
    assert set(spent) == {"build", "lammps", "rest"}
    # LAMMPS's share is the sum of the impacts' own records, not a guess
    runs = (RUNS / "test_study_whole").glob("random/*/*/run.json")
    lammps = sum(json.loads(path.read_text())["wall_seconds"] for path in runs)
    assert spent["lammps"] == pytest.approx(lammps, abs=0.1)
    assert spent["build"] > 0 and spent["rest"] >= 0
    # two workers cannot spend more than twice the study's wall-clock time
    assert sum(spent.values()) <= 2 * clock["seconds"] + 0.5


def test_a_killed_study_resumes_and_loses_nothing(uninterrupted):
    name = "test_study_killed"
    folder = RUNS / name
    subprocess.run(["rm", "-rf", str(folder)])
    proc = study(name, wait=False)
    deadline = time.monotonic() + 300
    while not any(folder.glob("random/*/*/result.json")) and time.monotonic() < deadline:
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    finished = len(list(folder.glob("random/*/*/result.json")))
    assert 1 <= finished < 6  # killed half-way
    resumed = study(name)
    assert resumed.returncode == 0, resumed.stderr
    assert f"{finished} already done" in resumed.stdout
    assert table(name) == uninterrupted


@pytest.mark.lammps
@pytest.mark.slow
def test_a_lammps_error_costs_exactly_its_impact():
    """Each LAMMPS error ends its worker's process; exactly that impact is
    marked failed, with the error of its own log, and the others finish."""
    name = "test_study_crashes"
    proc = run_crash_scenario(name)
    assert proc.returncode == 1, proc.stderr
    failed = genuine_failures(RUNS / name, proc)
    assert proc.stdout.strip().splitlines()[-1].startswith("4 impacts, 4 failed")
    # --retry-failed runs exactly the failed impacts again, each in LAMMPS anew
    logs = {f: (Path(f) / "log.lammps").stat().st_mtime_ns for f in failed}
    done = {p: p.stat().st_mtime_ns for p in (RUNS / name).rglob("result.json")}
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name]
    again = subprocess.run(
        [*command, *CRASH_SCENARIO, "--retry-failed"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert again.returncode == 1, again.stderr
    assert genuine_failures(RUNS / name) == failed
    for folder in failed:
        assert (Path(folder) / "log.lammps").stat().st_mtime_ns > logs[folder]
    assert {p: p.stat().st_mtime_ns for p in (RUNS / name).rglob("result.json")} == done


def worker_processes(pid: int) -> list[int]:
    """The Dask workers below the study's process ``pid`` that run LAMMPS: the
    processes with an Open MPI daemon (orted) of their own."""
    return [p for p in descendants(pid) if "orted" in {comm(c) for c in children(p)}]


def children(pid: int) -> set[int]:
    out = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout
    return {int(p) for p in out.split()}


def test_a_worker_killed_from_outside_fails_no_impact(uninterrupted):
    """SIGKILL to a worker in the middle of the study: its impacts run on
    another worker, none is marked failed, and the results are the same."""
    name = "test_study_worker_killed"
    folder = RUNS / name
    subprocess.run(["rm", "-rf", str(folder)])
    proc = study(name, "--samples", "20", wait=False)
    try:
        deadline = time.monotonic() + 120
        while not (workers := worker_processes(proc.pid)) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert workers, "no worker started LAMMPS"
        time.sleep(1.0)
        os.kill(workers[0], signal.SIGKILL)
        assert proc.wait(timeout=600) == 0
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert not list(folder.rglob("failed.json"))
    rows = table(name)
    assert len(rows) == 60 and set(uninterrupted) < set(rows)


def test_run_study_takes_a_notebooks_client(uninterrupted):
    """run_study(study, client=...) runs on a cluster the caller made, and
    gives the same e and beta as the command."""
    from distributed import Client, LocalCluster

    from runner.cluster.driver import run_study

    done = Study("test_study_client", lattices=("random",), angles=3, samples=1, **SMALL)
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=":0") as cluster:
        with Client(cluster) as client:
            counts = run_study(done, client=client)
    assert counts["done"] == 3 and counts["ran"] == 3 and counts["workers"] == 1
    command_results = sorted((RUNS / "test_study_whole" / "random" / "s1").glob("*/result.json"))
    assert len(command_results) == 3  # the same three angles, so the comparison is made
    for result in command_results:
        ours = json.loads((done.folder / "random" / "s1" / result.parent.name / "result.json")
                          .read_text())  # fmt: skip
        theirs = json.loads(result.read_text())
        assert (ours["e"], ours["beta"]) == (theirs["e"], theirs["beta"])


@pytest.mark.lammps
@pytest.mark.slow
def test_a_joined_cluster_that_gives_tasks_up_loses_no_impact(tmp_path):
    """--scheduler joins a running Dask cluster; where its scheduler gives a
    task up at the first worker it ends (allowed-failures 0), the driver
    submits it again and the impacts' folders decide: exactly the genuine
    failures."""
    scheduler_file = tmp_path / "scheduler.json"
    env = {**os.environ, "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0"}
    dask = [str(Path(sys.executable).parent / "dask")]
    said = (tmp_path / "daemons.log").open("w")  # shown if the scenario goes wrong
    daemons = [
        subprocess.Popen(
            [*dask, "scheduler", "--scheduler-file", str(scheduler_file), "--port", "0",
             "--no-dashboard"], env=env, stdout=said, stderr=subprocess.STDOUT,
        )
    ]  # fmt: skip
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        daemons.append(
            subprocess.Popen(
                [*dask, "worker", "--scheduler-file", str(scheduler_file), "--nworkers", "2",
                 "--nthreads", "1", "--no-dashboard"], env=env, stdout=said,
                stderr=subprocess.STDOUT,
            )
        )  # fmt: skip
        name = "test_study_joined"
        proc = run_crash_scenario(name, "--scheduler", str(scheduler_file))
        assert proc.returncode == 1, proc.stderr
        try:
            genuine_failures(RUNS / name, proc)
        except AssertionError as error:
            said.flush()
            raise AssertionError(f"{error}\n{(tmp_path / 'daemons.log').read_text()}") from None
        assert proc.stdout.strip().splitlines()[-1].startswith("4 impacts, 4 failed")
    finally:
        stop_by_pid(daemons)
        said.close()


@pytest.mark.parametrize(
    "samples, lattices, angles, per_group",
    [
        (20, 2, 3, 6),  # whole samples: the wall is built once per seed
        (4, 4, 2, 2),  # few samples: a lattice of a sample each
        (1, 1, 3, 1),  # one lattice of one sample: single impacts
    ],
)
def test_job_groups_keep_every_worker_busy(samples, lattices, angles, per_group):
    names = ("random", "triangular", "square_nu0.1", "square_nu0.3")[:lattices]
    jobs = Study("groups", lattices=names, angles=angles, samples=samples).jobs()
    groups = job_groups(jobs, workers=2)
    assert sorted(i for g in groups for i in g) == list(range(len(jobs)))
    assert [len(g) for g in groups] == sorted((len(g) for g in groups), reverse=True)
    assert {len(g) for g in groups} == {per_group}
    for group in groups:
        assert len({jobs[i]["seed"] for i in group}) == 1


def runs_listing() -> set[str]:
    """Everything under runs/ and beside it that a study could have written."""
    return {str(p.relative_to(RUNS)) for p in RUNS.glob("*")} | {
        p.name for p in ROOT.glob("escape*")
    }


@pytest.mark.parametrize("name", ["my study", "", "../escape", ".", "a/b"])
def test_a_bad_name_exits_2_and_writes_nothing(name):
    (RUNS).mkdir(exist_ok=True)
    before = runs_listing()
    proc = study(name)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "argument --name" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert proc.stdout == ""
    assert runs_listing() == before


@pytest.mark.lammps
@pytest.mark.slow
def test_a_failed_impact_exits_1_and_the_last_line_counts_by_cause():
    """On a 4 R wall (the first study's dense wall) the grazing impact slides
    off the end; the other finishes, and a tiny --max-drift flags it."""
    name = "test_study_failed"
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    command = [
        sys.executable,
        "-m",
        "runner",
        "study",
        "demo",
        "--name",
        name,
        "--lattices",
        "random",
        "--angles",
        "2",
        "--samples",
        "1",
        "--n-disk",
        "200",
        "--wall-width",
        "4",
        "--n-wall",
        "density",
        "--wall-ka",
        "same-c",
        "--wall-fixed",
        "sides",
        "--max-drift",
        "1e-9",
    ]
    proc = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 1, proc.stderr
    last = proc.stdout.strip().splitlines()[-1]
    assert re.match(
        r"1 impacts, 1 above --max-drift 1e-09, 1 failed \(1: the disk slid off the end "
        r"of the wall before it rebounded\); results in \S*/test_study_failed/results.md$",
        last,
    ), last
    page = (RUNS / name / "results.md").read_text()
    assert (
        "| the disk slid off the end of the wall before it rebounded | 1 "
        "| random 80.5 deg: seed 1 |" in page
    )
    assert "Made by `python -m runner study demo --name test_study_failed" in page
    assert "--max-drift 1e-09`" in page
    assert "1 of the 1 impacts have an energy drift" in page and "random 5.7106 deg: seed 1" in page
    with (RUNS / name / "impacts.csv").open() as handle:
        assert [row["drift_exceeded"] for row in csv.DictReader(handle)] == ["True"]
    # the report alone says the same and exits the same way
    again = subprocess.run(command + ["--report-only"], cwd=ROOT, capture_output=True, text=True)
    assert again.returncode == 1 and again.stdout.strip().splitlines()[-1] == last


def descendants(pid: int) -> set[int]:
    """Every process below ``pid``, from pgrep -P, recursively."""
    found: set[int] = set()
    todo = [pid]
    while todo:
        out = subprocess.run(
            ["pgrep", "-P", str(todo.pop())], capture_output=True, text=True
        ).stdout
        children = {int(p) for p in out.split()}
        todo += children - found
        found |= children
    return found


def comm(pid: int) -> str:
    """The process's command name, or '' if it is gone."""
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except FileNotFoundError:
        return ""


def alive(pid: int) -> bool:
    """Running, not a zombie waiting for whoever inherited it."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except FileNotFoundError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.lammps
@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_stops_the_study_and_every_process_below_it(signum):
    name = "test_study_signal"
    folder = RUNS / name
    subprocess.run(["rm", "-rf", str(folder)])
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *TINY,
               "--samples", "8"]  # fmt: skip
    # its own session, so that a failing test can still clean up the whole group
    proc = subprocess.Popen(
        command,
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        deadline = time.monotonic() + 120
        below: set[int] = set()
        while time.monotonic() < deadline:  # until the impacts are running
            below = descendants(proc.pid)
            names = [comm(p) for p in below if alive(p)]
            if names.count("orted") >= 2:  # two workers with LAMMPS (MPI singletons)
                break
            time.sleep(0.2)
        time.sleep(1.0)  # inside LAMMPS by now
        below = descendants(proc.pid) | below
        assert below, "the study started no process"
        os.kill(proc.pid, signum)  # the study's process only, as kill does
        out, err = proc.communicate(timeout=30)
        assert proc.returncode == 128 + signum, err
        assert "Traceback" not in err
        assert err.strip().splitlines() == [err.strip().splitlines()[-1]]
        assert f"stopped by {signal.Signals(signum).name}" in err
        time.sleep(5)
        assert not [p for p in below if alive(p)]
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()
        for pid in descendants(proc.pid):
            os.kill(pid, signal.SIGKILL)


def test_a_missing_plugin_stops_the_study_before_any_impact(monkeypatch, capsys):
    """An environment fault is no impact's failure: one line naming the file
    and the make target, exit 1, no impact folder."""
    import runner.cli.study_args
    from runner.__main__ import main

    monkeypatch.setitem(
        runner.cli.study_args.STYLE_LIBRARIES,
        ("pair", "polyline/exp"),
        ("libmissing.so", "register"),
    )
    name = "test_study_no_plugin"
    status = main(["study", "demo", "--name", name, *TINY])
    err = capsys.readouterr().err.strip()
    assert status == 1
    assert len(err.splitlines()) == 1 and "build/libmissing.so is missing: make setup" in err
    assert not (RUNS / name).exists()


@pytest.mark.lammps
@pytest.mark.slow
def test_a_study_on_a_larger_disk_is_the_same_study_scaled():
    """--radius scales every length and time: at R = 2 with twice the step, a
    smooth impact has the same e and beta, half the spin and twice the contact."""
    tables = {}
    for radius, dt in (("1", "0.002"), ("2", "0.004")):
        name = f"test_study_radius{radius}"
        subprocess.run(["rm", "-rf", str(RUNS / name)])
        command = ["--radius", radius, "--dt", dt, "--roughness", "0", "--angles", "2"]
        proc = subprocess.run(
            [sys.executable, "-m", "runner", "study", "demo", "--name", name, "--lattices",
             "random", "--samples", "1", "--n-disk", "200", *command],
            cwd=ROOT, capture_output=True, text=True, timeout=600,
        )  # fmt: skip
        assert proc.returncode == 0, proc.stderr
        with (RUNS / name / "impacts.csv").open() as handle:
            tables[radius] = list(csv.DictReader(handle))
        assert f"--radius {radius} " in (RUNS / name / "results.md").read_text()
    assert len(tables["1"]) == len(tables["2"]) == 2
    for one, two in zip(tables["1"], tables["2"], strict=True):
        assert float(two["e"]) == pytest.approx(float(one["e"]), abs=1e-6)
        assert float(two["beta"]) == pytest.approx(float(one["beta"]), abs=1e-6)
        assert float(two["omega"]) == pytest.approx(float(one["omega"]) / 2, abs=1e-7)
        # read off series.dat's rows, every 40 steps: 0.16 at R = 2
        assert float(two["contact_time"]) == pytest.approx(2 * float(one["contact_time"]), abs=0.17)


@pytest.mark.parametrize(
    "options, words",
    [
        (
            ["--partitions", "2"],
            "argument --partitions: is retired: studies run on Dask; use --cluster",
        ),
        (
            ["--batch-size", "16"],
            "argument --batch-size: is retired: studies run on Dask; use --cluster",
        ),
        (["--walltime", "01:00:00"], "--walltime applies to --cluster slurm only"),
        (["--jobs", "2"], "--jobs applies to --cluster slurm only"),
        (["--cluster", "slurm", "--workers", "2"], "--workers applies to --cluster local only"),
        (["--cluster", "local", "--scheduler", "tcp://a:8786"], "--scheduler joins a running"),
    ],
)
def test_a_cluster_option_that_does_not_apply_is_refused(options, words, capsys):
    from runner.__main__ import main

    name = "test_study_cluster_options"
    try:
        status = main(["study", "demo", "--name", name, *TINY, *options])
    except SystemExit as stop:
        status = stop.code
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1 and words in err, err
    assert not (RUNS / name).exists()
