"""An impact whose step is too long for the area barrier runs again at half
the step (runner.impact.run_scene, --barrier-halvings), with LAMMPS itself."""

from __future__ import annotations

import filecmp
import json
import shutil
import subprocess
import sys

import pytest

from builder.scene import SceneSpec
from builder.study_names import LIMITS
from ground.launch import LammpsError
from runner.impact import BARRIER_CROSSED, may_halve, run_impact
from runner.options import RunOptions
from tests.helpers import ROOT, RUNS

pytestmark = pytest.mark.lammps

# The paper's slope as one surface (L = 0.06 R) with the barrier, sliding at
# 80.5 degrees: at 1.5 times the 800-point disk's step a surface triangle
# turns over between two steps (at step 526); at the default step it does not.
CROSSING = SceneSpec(n_disk=800, gamma_deg=80.5, seed=1, **LIMITS["paper-slope-floor"])
LONG_STEP = 0.012


def test_a_step_too_long_for_the_barrier_stops_with_halvings_0(tmp_path):
    with pytest.raises(LammpsError, match=BARRIER_CROSSED):
        run_impact(CROSSING, tmp_path / "run", RunOptions(dt=LONG_STEP, barrier_halvings=0))
    assert not (tmp_path / "run" / "result.json").exists()


def test_the_impact_runs_again_at_half_the_step(tmp_path):
    """The retry is the impact at dt / 2, every output the same to the last
    bit as a run given dt / 2 from the start, and run.json says so."""
    halved = run_impact(CROSSING, tmp_path / "halved", RunOptions(dt=LONG_STEP))
    direct = run_impact(
        CROSSING, tmp_path / "direct", RunOptions(dt=LONG_STEP / 2, barrier_halvings=0)
    )
    record = json.loads((tmp_path / "halved" / "run.json").read_text())
    assert record["dt_halvings"] == 1 and record["options"]["dt"] == LONG_STEP / 2
    assert json.loads((tmp_path / "direct" / "run.json").read_text())["dt_halvings"] == 0
    for name in ("series.dat", "energy.dat"):
        assert filecmp.cmp(tmp_path / "halved" / name, tmp_path / "direct" / name, shallow=False)
    assert halved["e"] == direct["e"] and halved["beta"] == direct["beta"]
    assert 0.5 < halved["e"] < 1.0


def barrier_study(name: str, dt: str, fresh: bool = True) -> dict[str, dict]:
    """The crossing scene's reading as a two-angle study on one worker (the
    lammps module in-process, where LAMMPS's error ends the worker): each
    impact's run.json by its folder's name. ``fresh``: from an empty folder,
    else resumed."""
    if fresh:
        shutil.rmtree(RUNS / name, ignore_errors=True)
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name]
    command += ["--lattices", "random", "--cot-gamma", "0.167", "1.0", "--samples", "1"]
    command += ["--n-disk", "800", "--roughness-length", "0.06", "--roughness-profile"]
    command += ["continuous", "--contact-scaling", "physical", "--area-floor", "0.5"]
    proc = subprocess.run(
        [*command, "--dt", dt, "--workers", "1"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    assert "2 impacts, 0 failed" in proc.stdout
    return {p.parent.name: json.loads(p.read_text()) for p in (RUNS / name).rglob("run.json")}


@pytest.mark.slow
def test_a_study_runs_a_crossing_impact_again_at_half_the_step():
    """In a study the crossing ends the worker's process; the next start of
    the impact runs at half the step (started.json counts the halvings), and
    gives what a study at that step gives, to the last bit."""
    long = barrier_study("test_barrier_long_step", "0.016")
    half = barrier_study("test_barrier_half_step", "0.008")
    assert long["g80.5191"]["dt_halvings"] == 1 and long["g80.5191"]["options"]["dt"] == 0.008
    assert long["g45.0000"]["dt_halvings"] == 0 and long["g45.0000"]["options"]["dt"] == 0.016
    assert half["g80.5191"]["dt_halvings"] == 0
    rebound = {
        name: json.loads((RUNS / name / "random/s1/g80.5191/result.json").read_text())
        for name in ("test_barrier_long_step", "test_barrier_half_step")
    }
    first, second = rebound.values()
    assert (first["e"], first["beta"]) == (second["e"], second["beta"])
    # started again (after a stop, or to more seeds): the impact run at half
    # the step is the study's own, kept as done, not refused as another's
    again = barrier_study("test_barrier_long_step", "0.016", fresh=False)
    assert again == long


# Sliding at 87 degrees on the grazing wall (held at its sides and bottom,
# 32 R): at 1.9 c along the wall the spacing's step does not resolve the
# contact; seed 12's surface tears a wall segment past the contact's reach
# at dt 0.004 (step 1072) and rebounds at 0.002.
GRAZING = SceneSpec(
    n_disk=800,
    gamma_deg=87.0,
    seed=12,
    wall_fixed="sides+bottom",
    wall_width=32.0,
    n_wall=6400,
    **LIMITS["paper-slope-floor"],
)
TORN = (
    "ERROR on proc 0: Pair polyline/exp: segment 134-135 is 0.81 long, more than reach 0.29, "
    "at step 1072: the run went unstable, or reach is too small"
)
INSIDE = "ERROR on proc 0: Pair polyline/exp: atom 6468 is inside the wall at step 323"


def test_the_contacts_step_errors_halve_only_a_step_the_program_chose():
    options = RunOptions(dt=0.008)
    for error in (TORN, INSIDE):
        assert may_halve(error, 0, options, automatic=True)
        assert not may_halve(error, 0, options)  # the user's dt: the user's error
        assert not may_halve(error, 2, options, automatic=True)  # no halvings left
    assert may_halve(BARRIER_CROSSED, 0, options)
    slid = "ERROR: the disk slid off the end of the wall before it rebounded"
    assert not may_halve(slid, 0, options, automatic=True)  # the wall's, not the step's


@pytest.mark.slow
def test_an_automatic_step_too_long_for_the_contact_runs_again_at_half(tmp_path):
    """The user's dt 0.004 stops with the contact's error; dt auto (0.008 at
    800 points) is halved until the impact rebounds, and run.json says so."""
    with pytest.raises(LammpsError, match="the run went unstable"):
        run_impact(GRAZING, tmp_path / "given", RunOptions(dt=0.004))
    assert not (tmp_path / "given" / "result.json").exists()
    result = run_impact(GRAZING, tmp_path / "auto", RunOptions(dt="auto"))
    record = json.loads((tmp_path / "auto" / "run.json").read_text())
    assert record["dt_halvings"] == 2 and record["options"]["dt"] == 0.002
    assert result["dt"] == 0.002 and 0.5 < result["e"] < 1.2


@pytest.mark.slow
def test_the_command_says_the_step_it_halved(tmp_path):
    """`runner impact --dt` given a step too long for the barrier: the table's
    dt is the step the run was made at, and one line on stderr says it was
    halved (issue 56: it ran at half the step and said nothing)."""
    command = [sys.executable, "-m", "runner", "impact", "--out", str(tmp_path / "run")]
    command += ["--lattice", "random", "--seed", "1", "--gamma", "80.5", "--n-disk", "800"]
    for name, value in LIMITS["paper-slope-floor"].items():  # CROSSING's reading
        command += [f"--{name.replace('_', '-')}", str(value)]
    command += ["--dt", str(LONG_STEP)]
    proc = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    header, row = proc.stdout.strip().splitlines()[-2:]
    assert dict(zip(header.split(), row.split()))["dt"] == f"{LONG_STEP / 2:g}"
    (note,) = [line for line in proc.stderr.splitlines() if "note:" in line]
    assert f"ran at dt = {LONG_STEP / 2:g} R/c, the step given halved 1 time:" in note
