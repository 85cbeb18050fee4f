"""The study's sweep on Dask: resumable, crash-tolerant, stoppable."""

from __future__ import annotations

import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from runner.driver import job_groups
from runner.study import Study
from tests.helpers import ROOT, RUNS, SMALL, genuine_failures, run_crash_scenario, stop_by_pid

# SMALL's scene (tests/helpers.py): the 200-point disk on the 1,600-point wall, the paper's contact
TINY = ["--lattices", "random", "--angles", "3", "--samples", "2", "--n-disk", "200"]
TINY += ["--n-wall", "1600", "--contact-scaling", "fixed"]
COMPARED = (
    "study_lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "e",
    "beta",
    "omega",
    "steps",
    "contact_time",
)


def study(name: str, *extra: str, wait: bool = True):
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *TINY, *extra]
    if wait:
        return subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    return subprocess.Popen(
        command,
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )


def table(name: str) -> list[tuple]:
    with (RUNS / name / "impacts.csv").open() as handle:
        return [tuple(row[c] for c in COMPARED) for row in csv.DictReader(handle)]


@pytest.fixture(scope="module")
def uninterrupted():
    name = "test_study_whole"
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    proc = study(name)
    assert proc.returncode == 0, proc.stderr
    return table(name)


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


def test_a_lammps_error_costs_exactly_its_impact():
    """Each LAMMPS error ends its worker's process; exactly that impact is
    marked failed, with the error of its own log, and the others finish."""
    name = "test_study_crashes"
    proc = run_crash_scenario(name)
    assert proc.returncode == 1, proc.stderr
    genuine_failures(RUNS / name)
    assert proc.stdout.strip().splitlines()[-1].startswith("4 impacts, 4 failed")


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

    from runner.driver import run_study

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


def test_a_joined_cluster_that_gives_tasks_up_loses_no_impact(tmp_path):
    """--scheduler joins a running Dask cluster; where its scheduler gives a
    task up at the first worker it ends (allowed-failures 0), the driver
    submits it again and the impacts' folders decide: exactly the genuine
    failures."""
    scheduler_file = tmp_path / "scheduler.json"
    env = {**os.environ, "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0"}
    dask = [str(Path(sys.executable).parent / "dask")]
    daemons = [
        subprocess.Popen(
            [*dask, "scheduler", "--scheduler-file", str(scheduler_file), "--port", "0",
             "--no-dashboard"], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )
    ]  # fmt: skip
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        daemons.append(
            subprocess.Popen(
                [*dask, "worker", "--scheduler-file", str(scheduler_file), "--nworkers", "2",
                 "--nthreads", "1", "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )  # fmt: skip
        name = "test_study_joined"
        proc = run_crash_scenario(name, "--scheduler", str(scheduler_file))
        assert proc.returncode == 1, proc.stderr
        genuine_failures(RUNS / name)
    finally:
        stop_by_pid(daemons)


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
    failed.csv and study.json, with no run folder (docs/results/ for the paper)."""
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
        (["--dt", "0.001"], "'dt': 0.001"),
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


def test_a_missing_plugin_stops_the_study_before_any_impact(monkeypatch, capsys):
    """An environment fault is no impact's failure: one line naming the file
    and the make target, exit 1, no impact folder."""
    import runner.study
    from runner.__main__ import main

    monkeypatch.setitem(
        runner.study.STYLE_LIBRARIES, ("pair", "polyline/exp"), ("libmissing.so", "register")
    )
    name = "test_study_no_plugin"
    status = main(["study", "demo", "--name", name, *TINY])
    err = capsys.readouterr().err.strip()
    assert status == 1
    assert len(err.splitlines()) == 1 and "build/libmissing.so is missing: make setup" in err
    assert not (RUNS / name).exists()


def committed_tables_copy(folder: Path) -> Path:
    folder.mkdir(parents=True)
    for name in ("impacts.csv", "failed.csv", "study.json"):
        (folder / name).write_bytes((ROOT / "docs" / "results" / name).read_bytes())
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
