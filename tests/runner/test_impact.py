"""Impacts run by LAMMPS: invariants, physics limits, routes, and failures."""

from __future__ import annotations

import dataclasses
import json
import re
import subprocess
import sys

import numpy as np
import pytest

from analysis.impact.dump import open_run, rebound_from_dump
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.errors import InputError
from ground.launch import LammpsError, lammps_error
from runner.impact import run_impact, run_scene
from runner.options import DEFAULT_DT, RESPA_DT, RESPA_NRESPA, RunOptions
from tests.helpers import PAPER, PAPER_ARGS, ROOT, SMALL, new_lammps


def free_flight(scene_dir, dt: float, time: float = 5.0) -> tuple[np.ndarray, np.ndarray]:
    """The disk alone, spinning and vibrating: (P_x, P_y, L_z, E) before and after."""
    lmp = new_lammps()
    for command in [
        "units lj",
        "dimension 2",
        "boundary s s p",
        "atom_style bond",
        "special_bonds lj/coul 1.0 1.0 1.0",
        "bond_style class2",
        f"read_data {scene_dir}/scene.data",
        "group wall molecule 2 3",
        "delete_atoms group wall bond yes",
        "pair_style zero 0.1",
        "pair_coeff * *",
        "comm_modify cutoff 1.0",
        "velocity all create 0.002 4928 loop geom",  # internal vibration
        "variable vx0 atom vx",
        "variable vy0 atom vy",  # plus a rigid spin
        "variable spin_x atom v_vx0-0.05*(y-xcm(all,y))",
        "variable spin_y atom v_vy0+0.05*(x-xcm(all,x))",
        "velocity all set v_spin_x v_spin_y NULL",
        "fix move all nve",
        f"timestep {dt}",
        "compute pe_bonds all pe bond",
        "compute ke all ke",
        "variable p_x equal vcm(all,x)*mass(all)",
        "variable p_y equal vcm(all,y)*mass(all)",
        "variable l_z equal angmom(all,z)",
        "variable etotal equal c_ke+c_pe_bonds",
        "thermo_style custom step v_etotal",
        "run 0",
    ]:
        lmp.command(command)

    def state():
        return np.array(
            [lmp.extract_variable(name, None, 0) for name in ("p_x", "p_y", "l_z", "etotal")]
        )

    before = state()
    lmp.command(f"run {round(time / dt)}")
    after = state()
    lmp.close()
    return before, after


@pytest.mark.lammps
def test_free_flight_conserves_momentum_and_angular_momentum(small_scene_dir):
    before, after = free_flight(small_scene_dir, 0.001)
    scale = abs(before[2]) + 1.0
    assert abs(before[2]) > 1.0  # it does spin
    assert np.all(np.abs(after[:3] - before[:3]) < 1e-12 * scale)


@pytest.mark.lammps
def test_free_flight_energy_error_is_small_and_second_order(small_scene_dir):
    errors = [
        abs(after[3] - before[3]) / before[3]
        for before, after in (free_flight(small_scene_dir, dt) for dt in (0.002, 0.001))
    ]
    assert errors[1] < 1e-4
    assert 3.0 < errors[0] / errors[1] < 5.0  # velocity Verlet: dt^2


@pytest.fixture(scope="module")
def head_on(tmp_path_factory):
    """e of smooth triangular disks hitting a rigid wall head-on, by speed.

    Smooth: at 0.03 c the indentation is comparable to a roughness of 0.03 R,
    and a rough disk lands on asperities and spins (docs/validation.md). The
    rigid wall's surface has the disk's spacing (``n_wall="density"``), so the
    contact's cutoff is the disk's spacing too. V0 from one point's mass: at
    that cutoff (20 decay lengths) V0 from the disk's mass, 800 times larger,
    leaves an energy step of 2.7e-4 where a point crosses it, which drifts the
    slow impact by 1.3e-5 (measured 2026-11-24; on the default wall, 32 decay
    lengths, the step is 1.5e-9).
    """
    results = {}
    for vn in (0.03, 0.1, 0.2):
        spec = SceneSpec(
            lattice="triangular",
            gamma_deg=0.0,
            vn=vn,
            roughness=0.0,
            **PAPER,
            wall_fixed="all",
            n_wall="density",
            contact_mass="point",
        )
        results[vn] = run_impact(
            spec, tmp_path_factory.mktemp(f"head_on_{vn}"), RunOptions(tmax=300.0)
        )
    return results


@pytest.mark.lammps
def test_slow_head_on_impact_on_a_rigid_wall_is_nearly_elastic(head_on):
    assert head_on[0.03]["e"] > 0.98
    assert head_on[0.03]["beta"] is None  # no tangential motion
    assert abs(head_on[0.03]["energy_drift"]) < 1e-6


@pytest.mark.lammps
def test_restitution_falls_as_the_speed_rises(head_on):
    assert head_on[0.03]["e"] > head_on[0.1]["e"] > head_on[0.2]["e"]


@pytest.fixture(scope="module")
def oblique(tmp_path_factory):
    folder = tmp_path_factory.mktemp("oblique")
    result = run_impact(SceneSpec(gamma_deg=40.0, **SMALL), folder, RunOptions(dump_every=50))
    return folder, result


@pytest.mark.lammps
def test_result_json(oblique):
    folder, result = oblique
    saved = json.loads((folder / "result.json").read_text())
    assert saved == result
    for key in (
        "lattice",
        "seed",
        "gamma_deg",
        "cot_gamma",
        "vn",
        "dt",
        "integrator",
        "contact",
        "e",
        "beta",
        "omega",
        "contact_time",
        "steps",
        "wall_seconds",
        "lammps_version",
    ):
        assert key in saved
    assert saved["lammps_version"].startswith("29 Sep 2021")
    assert saved["cot_gamma"] == pytest.approx(1.0 / np.tan(np.radians(40.0)))
    assert 0.0 < saved["e"] < 1.0 and -1.0 < saved["beta"] < 1.0
    # energy: what the disk lost went into vibrations, up to the integration error
    assert abs(saved["energy_drift"]) < 1e-3


@pytest.mark.lammps
def test_series_and_dump_agree(oblique):
    folder, result = oblique
    from_dump = rebound_from_dump(open_run(folder))
    # the dump route reads float32 velocities
    assert from_dump.e == pytest.approx(result["e"], rel=1e-6)
    assert from_dump.beta == pytest.approx(result["beta"], rel=1e-6)
    # float32 positions up to 8 R from the box's corner: 5e-7 R, so omega
    # (~1e-2 c/R, from sums over the disk) is good to about 1e-7 c/R
    assert from_dump.omega == pytest.approx(result["omega"], rel=1e-6, abs=1e-7)


@pytest.mark.lammps
def test_lmp_and_python_routes_agree(tmp_path, small_scene):
    results = {}
    for route in ("lmp", "python"):
        folder = write_scene(small_scene, tmp_path / route)
        results[route] = run_scene(folder, RunOptions(route=route))
    for key in ("e", "beta", "omega", "contact_time", "steps"):
        assert results["lmp"][key] == results["python"][key]


def runner_cli(*args, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "runner", *args], cwd=cwd, capture_output=True, text=True
    )


@pytest.mark.parametrize(
    "args, words",
    [
        (["impact", "--radius", "-1"], "argument --radius: must be a number in [0.1, 10]"),
        (["impact", "--n-disk", "0"], "argument --n-disk: must be an integer in [50, 100000]"),
        (["impact", "--gamma", "90"], "argument --gamma: must be a number in (0, 90)"),
        (["impact", "--lattice", "hexagonal"], "argument --lattice: invalid choice"),
        (["impact", "--dt", "-0.001"], "argument --dt: must be a number in [1e-05, 0.05]"),
    ],
)
def test_runner_cli_rejects_bad_input(tmp_path, args, words):
    out = tmp_path / "run"
    proc = runner_cli(*args, "--out", str(out))
    assert proc.returncode == 2
    assert words in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_missing_data_file(tmp_path):
    proc = runner_cli("run", str(tmp_path / "nowhere"))
    assert proc.returncode == 2
    assert "argument scene: must be an existing folder" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "nowhere").exists()


@pytest.mark.lammps
def test_unstable_run_stops_without_a_result(small_scene_dir, tmp_path):
    folder = write_scene(build_scene(SceneSpec(gamma_deg=30.0, **SMALL)), tmp_path / "unstable")
    with pytest.raises(LammpsError, match="unstable|inside the wall"):
        run_scene(folder, RunOptions(dt=0.05, check=20))
    assert not (folder / "result.json").exists()
    # from the command line checks farther apart than a contact lasts
    # are refused before the run
    proc = runner_cli("run", str(folder), "--dt", "0.05", "--check", "100")
    assert proc.returncode == 2 and "check * dt must be at most 2 R/c" in proc.stderr
    assert "give a smaller check" in proc.stderr
    assert not (folder / "result.json").exists()


@pytest.mark.lammps
def test_pair_variant_lets_the_disk_into_the_wall(tmp_path):
    """At 0.1 c disk points slip between the wall's surface points (docs/contact.md)."""
    folder = write_scene(build_scene(SceneSpec(gamma_deg=30.0, **SMALL)), tmp_path / "pair")
    with pytest.raises(LammpsError, match="inside the wall"):
        run_scene(folder, RunOptions(contact="pair"))
    assert not (folder / "result.json").exists()


@pytest.mark.lammps
def test_disk_that_slides_off_the_wall_stops_without_a_result(tmp_path):
    """On the shortest wall at the most grazing angle the disk reaches the
    wall's end while still pressing into it; the run must say so at once
    rather than wait for tmax, and record nothing."""
    # the dense wall of the first study, held at its sides only: on stiffer
    # walls the disk leaves before it reaches the 4 R wall's end
    spec = SceneSpec(
        **{**SMALL, "n_wall": "density"},
        gamma_deg=80.5,
        wall_width=4.0,
        wall_ka="same-c",
        wall_fixed="sides",
    )
    folder = write_scene(build_scene(spec), tmp_path / "short_wall")
    with pytest.raises(LammpsError, match="slid off the end of the wall"):
        run_scene(folder, RunOptions(dt=DEFAULT_DT))  # the step this scene was written at
    assert not (folder / "result.json").exists()
    assert (
        float(re.search(r"at time ([\d.]+)", lammps_error(folder / "log.lammps", "")).group(1))
        < 20.0
    )


RESPA = RunOptions(integrator="respa", dt=RESPA_DT, nrespa=RESPA_NRESPA)


@pytest.mark.lammps
@pytest.mark.mpi
@pytest.mark.parametrize(
    "roughness, gamma, bound, options",
    [
        (0.0, 45.0, 1e-12, RunOptions()),
        (0.0, 80.4, 1e-12, RunOptions()),
        pytest.param(0.03, 80.4, 1e-4, RunOptions(), marks=pytest.mark.slow),
        (0.0, 45.0, 1e-12, RESPA),
        (0.0, 80.4, 1e-12, RESPA),
    ],
    ids=["verlet-45", "verlet-80.4", "verlet-rough-80.4", "respa-45", "respa-80.4"],
)
def test_one_and_two_ranks_agree(tmp_path, roughness, gamma, bound, options):
    """One and two ranks sum the forces in different orders. On smooth surfaces
    the impact is regular and that round-off stays round-off (measured at the
    default dt: 1e-14 at 45 and 80.4 degrees; with rRESPA, the contact on the
    inner level, also 1e-14). The rough contact is chaotic: a
    1e-9 R move of the disk's points spreads e by 1e-2 at 80.4 degrees
    (docs/benchmarks/validation_table.md), so the bound there is that spread's 1e-2
    (measured: 7e-10); at 45 degrees on the default wall the two runs part
    by 4e-4, within that scene's spread, and are not compared."""
    scene = build_scene(SceneSpec(gamma_deg=gamma, roughness=roughness, **PAPER))
    results = [
        run_scene(write_scene(scene, tmp_path / str(n)), dataclasses.replace(options, nprocs=n))
        for n in (1, 2)
    ]
    assert results[0]["steps"] == results[1]["steps"]
    for key in ("e", "beta", "omega"):
        assert abs(results[0][key] - results[1][key]) < bound


@pytest.mark.lammps
def test_a_drift_above_the_threshold_is_flagged_and_warned_of(tmp_path):
    """The guard flags and warns of a drift above --max-drift, naming dt; below
    it, it stays silent. (The default 0.05 sits above the drift of the paper
    study's worst impacts at the default dt, docs/benchmarks/drift_tail.md.)"""
    out = tmp_path / "coarse"
    # the paper's scene, whose drifts the guard was set by
    proc = runner_cli(
        "impact",
        "--gamma",
        "60",
        "--seed",
        "3",
        *PAPER_ARGS,
        "--max-drift",
        "1e-5",
        "--out",
        str(out),
    )
    assert proc.returncode == 0, proc.stderr
    warning = proc.stderr.strip().splitlines()
    assert len(warning) == 1 and "warning: energy drift" in warning[0]
    assert f"dt = {DEFAULT_DT:g}" in warning[0] and "--max-drift 1e-05" in warning[0]
    result = json.loads((out / "result.json").read_text())
    assert result["drift_exceeded"] is True and abs(result["energy_drift"]) > result["max_drift"]
    # the default threshold: no warning, no flag
    proc = runner_cli("run", str(out))
    assert proc.returncode == 0 and proc.stderr == ""
    result = json.loads((out / "result.json").read_text())
    assert result["drift_exceeded"] is False and abs(result["energy_drift"]) < 1e-2


@pytest.mark.lammps
def test_a_step_that_blows_up_stops_with_an_error_naming_dt(tmp_path):
    """dt = 0.05 R/c (with checks every 40 steps, within 2 R/c) is beyond the
    stability of the springs: the run stops at a check, writes no result,
    and the error names dt and the default."""
    out = tmp_path / "unstable"
    # the paper's scene: its springs blow up (the default body's barrier stops
    # the run first, below)
    proc = runner_cli(
        "impact", "--gamma", "60", "--seed", "3", *PAPER_ARGS, "--dt", "0.05", "--check", "40",
        "--out", str(out),
    )  # fmt: skip
    assert proc.returncode == 1
    error = proc.stderr.strip().splitlines()
    assert len(error) == 1 and "the run went unstable" in error[0]
    assert f"dt = 0.05 R/c; the default, {DEFAULT_DT:g}" in error[0]
    assert not (out / "result.json").exists()
    # the default body: a triangle crosses the barrier within one step, and
    # the error names dt and the default too (no halved step: that retry is
    # tests/runner/test_barrier_halvings.py's)
    out = tmp_path / "unstable_body"
    proc = runner_cli(
        "impact", "--gamma", "60", "--seed", "3", "--dt", "0.05", "--check", "40",
        "--barrier-halvings", "0", "--out", str(out),
    )  # fmt: skip
    assert proc.returncode == 1
    error = proc.stderr.strip().splitlines()
    assert len(error) == 1 and "crossed the barrier within one step" in error[0]
    assert f"dt = 0.05 R/c; the default, {DEFAULT_DT:g}" in error[0]
    assert not (out / "result.json").exists()


def test_a_folder_with_spaces_is_refused_before_anything_is_written(tmp_path):
    out = tmp_path / "my run"
    proc = runner_cli("impact", "--n-disk", "200", "--out", str(out))
    assert proc.returncode == 2 and "must not contain whitespace" in proc.stderr
    assert not out.exists()


@pytest.mark.parametrize(
    "changes, words",
    [
        ({"check": 2000}, "check * dt must be at most 2 R/c"),
        ({"check": 30, "every": 25}, "check must be a multiple of every (25)"),
        ({"dt": -1.0}, "dt must be a number in [1e-05, 0.05]"),
    ],
)
def test_bad_run_options_are_refused(changes, words):
    with pytest.raises(InputError, match=re.escape(words)):
        RunOptions(**changes).validate()


@pytest.mark.parametrize("dt", [1e-4, 1e-3, 2e-3, 3e-3, 8e-3, 0.02, 0.05])
def test_rows_and_checks_keep_their_spacing_in_time_at_any_step(dt):
    """Left at 0, every and check follow dt: rows 0.08 R/c apart and checks
    the multiple of every nearest 0.8 R/c, so any valid dt runs without
    choosing them, and the deck gets the steps."""
    options = RunOptions(dt=dt)
    options.validate()
    every, check = options.every_steps, options.check_steps
    assert check % every == 0 and check * dt <= 2.0
    if dt <= 0.008:  # where a row is many steps, the spacing is the interval's to a step
        assert abs(every * dt - 0.08) <= dt / 2
        assert abs(check * dt - 0.8) <= every * dt / 2
    variables = options.deck_variables()
    assert (variables["every"], variables["check"]) == (str(every), str(check))
    # set by hand, they are kept
    fixed = RunOptions(dt=dt, every=1, check=1)
    assert (fixed.every_steps, fixed.check_steps) == (1, 1)
