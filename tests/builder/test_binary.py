"""Two disks colliding (target disk): the scene, its run by LAMMPS, its analysis."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from analysis.impact.binary import apse, binary_rebound, momentum_change
from analysis.impact.series import BINARY_COLUMNS
from builder.assembly import build_scene
from builder.binary import SURFACE_RADIUS, counter_clockwise
from builder.scene import DISK, SceneSpec
from builder.study_names import LIMITS
from ground.errors import InputError
from runner.impact import run_impact
from runner.options import RESPA_DT, RESPA_NRESPA, RunOptions
from runner.study import Study
from tests.helpers import ROOT

BINARY = dict(target="disk", n_disk=200, gamma_deg=45.0)


def rings(scene):
    """The target's ring and the disk's, as the pair style reads them (tags)."""
    (b_first, b_last), (a_first, a_last) = (
        scene.info["wall_row_tags"],
        scene.info["partner_row_tags"],
    )
    return scene.positions[b_first - 1 : b_last], scene.positions[a_first - 1 : a_last]


@pytest.mark.parametrize("lattice", ["random", "triangular", "square"])
def test_the_scene_is_at_rest_in_the_centre_of_mass_and_its_rings_run_counter_clockwise(lattice):
    spec = SceneSpec(**{**BINARY, "lattice": lattice, "gamma_deg": 60.0, "seed": 3})
    scene = build_scene(spec)
    in_disk = scene.molecule == DISK
    momentum = scene.velocities.sum(axis=0)  # unit masses
    assert np.abs(momentum).max() < 1e-15 * np.abs(scene.velocities).sum()
    relative = scene.velocities[in_disk][0] - scene.velocities[~in_disk][0]
    assert relative == pytest.approx([0.1 * np.tan(np.radians(60.0)), -0.1], rel=1e-14)
    ring_b, ring_a = rings(scene)
    assert counter_clockwise(ring_a) and counter_clockwise(ring_b)
    first, last = scene.info["partner_row_tags"]
    assert set(scene.types[first - 1 : last]) == {1}
    assert set(scene.types[: scene.info["wall_row_tags"][1]]) == {3}
    # nothing of the disk's is in the target's rows and the other way round
    assert np.all(in_disk[first - 1 :]) and not np.any(in_disk[: first - 1])


@pytest.mark.parametrize(
    "lattice, gamma, vn, seed",
    [
        ("random", 45.0, 0.1, 5),
        ("triangular", 80.5, 0.1, 5),
        ("random", 76.0, 0.01, 5),
        # no line of the unturned pair first touches at 86 degrees: turned
        ("random", 86.0, 0.01, 2),
    ],
)
def test_the_disk_is_aimed_by_the_contact(lattice, gamma, vn, seed):
    """The disk starts the cutoff and the start gap from the target, and on
    its line of motion the rings first come within the contact's stand-off
    (checked here with the distance to the polylines, not the builder's rays)
    where the line of centres makes the nominal angle with the relative
    velocity; rigid circles of radius R would have been aimed short of it."""
    from builder.aim import AIM_TOLERANCE_DEG, first_contact, gap_between

    spec = SceneSpec(**{**BINARY, "lattice": lattice, "gamma_deg": gamma, "vn": vn, "seed": seed})
    scene = build_scene(spec)
    ring_b, ring_a = rings(scene)
    cutoff, aimed = scene.info["contact"]["cutoff"], scene.info["aim"]
    assert gap_between(ring_a, ring_b) == pytest.approx(cutoff * (1 + spec.start_gap), rel=1e-6)
    # the stand-off: one point's contact energy is the approach's normal kinetic energy
    m_a, m_b = scene.info["disk_mass"], scene.info["target_mass"]
    energy = 0.5 * m_a * m_b / (m_a + m_b) * vn**2
    v0, a = scene.info["contact"]["V0"], spec.contact_a
    assert v0 * np.exp(-a * aimed["reach"]) == pytest.approx(energy, rel=1e-9)
    relative = np.array(scene.info["initial_relative_velocity"])
    u = relative / np.linalg.norm(relative)
    own = ring_a - scene.disk_centre
    travel = first_contact(own, ring_b, scene.disk_centre, u, aimed["reach"])
    assert travel / np.linalg.norm(relative) == pytest.approx(aimed["first_touch_time"])
    touch = scene.disk_centre + travel * u
    assert gap_between(own + touch, ring_b) == pytest.approx(aimed["reach"], rel=1e-9)
    path = np.linspace(0, travel, 50)[:-1]
    assert min(gap_between(own + scene.disk_centre + s * u, ring_b) for s in path) > aimed["reach"]
    # the incidence at the line of the centres of mass, as the analysis measures it
    in_disk = scene.molecule == DISK
    line = (
        scene.positions[in_disk].mean(axis=0) + travel * u - scene.positions[~in_disk].mean(axis=0)
    )
    across = np.array([-u[1], u[0]])
    measured = np.degrees(np.arctan2(line @ across, -(line @ u)))
    assert aimed["hit"] and abs(measured - gamma) <= AIM_TOLERANCE_DEG
    assert measured == pytest.approx(aimed["first_touch_incidence_deg"], abs=1e-9)
    assert aimed["offset"] > aimed["rigid_offset"]


def test_where_no_line_first_touches_at_gamma_the_pair_is_turned():
    """Seed 2's rings have no line that first touches at 86 degrees (the
    incidence jumps past it); the aim turns the approach by whole quarters of
    the disk's surface spacing, and keeps the normal speed and the nominal
    incidence (an unturned pair keeps its data file to the bit:
    tests/builder/test_builder.py's pinned scenes)."""
    from builder.aim import aim, hits

    spec = SceneSpec(**{**BINARY, "gamma_deg": 86.0, "vn": 0.01, "seed": 2})
    scene = build_scene(spec)
    aimed = scene.info["aim"]
    ring_b, ring_a = rings(scene)
    in_disk = scene.molecule == DISK
    com_a, com_b = scene.positions[in_disk].mean(axis=0), scene.positions[~in_disk].mean(axis=0)
    gamma = np.radians(86.0)
    unturned = np.array([np.sin(gamma), -np.cos(gamma)])
    _, miss = aim(ring_a - com_a, ring_b - com_b, unturned, gamma, aimed["reach"], spec.radius)
    assert not hits(miss)  # the jump the turn avoids
    step = 0.25 * scene.info["disk_spacing"] / spec.radius
    turns = np.radians(aimed["turn_deg"]) / step
    assert turns != 0 and turns == pytest.approx(round(turns), abs=1e-9)
    relative = np.array(scene.info["initial_relative_velocity"])
    turn = np.radians(aimed["turn_deg"])
    assert np.arctan2(relative[1], relative[0]) == pytest.approx(gamma - np.pi / 2 + turn)
    # the normal speed of the same disks at 45 degrees, where they meet unturned
    at_45 = build_scene(dataclasses.replace(spec, gamma_deg=45.0))
    assert at_45.info["aim"]["turn_deg"] == 0.0 and at_45.info["aim"]["hit"]
    speed = np.linalg.norm(at_45.info["initial_relative_velocity"]) * np.cos(np.radians(45.0))
    assert np.linalg.norm(relative) * np.cos(gamma) == pytest.approx(speed, rel=1e-12)
    assert scene.info["cot_gamma"] == pytest.approx(1 / np.tan(gamma), rel=1e-12)


def test_the_disk_is_the_wall_scenes_and_the_second_disk_another():
    wall = build_scene(SceneSpec(n_disk=200, seed=4, **LIMITS["paper"]))  # a binary's reading
    binary = build_scene(SceneSpec(**{**BINARY, "seed": 4}))
    own = binary.frame_positions[binary.molecule == DISK]
    assert np.array_equal(own, wall.frame_positions[wall.molecule == DISK])
    target = binary.frame_positions[binary.molecule != DISK]
    assert len(target) != len(own) or not np.array_equal(target, own)


def test_partner_seed_takes_that_samples_disk():
    sample_7 = build_scene(SceneSpec(**{**BINARY, "seed": 7}))
    paired = build_scene(SceneSpec(**{**BINARY, "seed": 4, "partner_seed": 7}))
    disk_7 = sample_7.frame_positions[sample_7.molecule == DISK]
    assert np.array_equal(paired.frame_positions[paired.molecule != DISK], disk_7)


def test_the_image_partner_is_the_disks_point_image_through_the_midpoint():
    scene = build_scene(SceneSpec(**{**BINARY, "seed": 4, "partner": "image", "gamma_deg": 60.0}))
    disk = scene.positions[scene.molecule == DISK]
    target = scene.positions[scene.molecule != DISK]
    # the target's ring first, then its interior; the disk's likewise: the
    # same order, so each target point is its disk point's image through c / 2
    assert np.array_equal(target, scene.disk_centre - disk)
    velocities = scene.velocities
    assert np.array_equal(velocities[scene.molecule != DISK], -velocities[scene.molecule == DISK])


@pytest.mark.lammps
def test_the_image_partners_collision_is_symmetric(tmp_path):
    """Turned by 180 degrees about the midpoint, the scene is itself: both
    disks end with the same spin and vibration, and opposite momenta."""
    spec = SceneSpec(**{**BINARY, "seed": 3, "partner": "image", "gamma_deg": 50.0})
    result = run_impact(spec, tmp_path / "image", RunOptions())
    assert result["touches"] >= 1
    series = np.loadtxt(tmp_path / "image" / "series.dat")
    columns = {name: k for k, name in enumerate(BINARY_COLUMNS)}
    end = series[-1]
    # summation order differs between the two disks' points: round-off only
    for own, other, sign in (("omega_z", "tomega_z", 1), ("vx", "tvx", -1), ("vy", "tvy", -1)):
        assert end[columns[own]] == pytest.approx(sign * end[columns[other]], rel=1e-9, abs=1e-12)
    assert result["vibration_disk"] == pytest.approx(result["vibration_target"], rel=1e-9)
    # a binary pair of independent disks is not symmetric: the check can fail
    other = run_impact(
        dataclasses.replace(spec, partner="independent"), tmp_path / "pair", RunOptions()
    )
    assert abs(other["vibration_disk"] / other["vibration_target"] - 1) > 1e-3


@pytest.mark.lammps
def test_a_held_image_neither_moves_nor_gives(tmp_path):
    """partner image-held: the image's points are held (molecule 3, no
    springs), the disk brings the whole relative velocity, and the run keeps
    the energy while the hold takes momentum."""
    spec = SceneSpec(
        **{**BINARY, "seed": 3, "partner": "image-held", "gamma_deg": 50.0, "vn": 0.05}
    )
    scene = build_scene(spec)
    target = scene.molecule != DISK
    assert set(scene.molecule[target]) == {3}
    assert not np.isin(scene.springs, np.flatnonzero(target)).any()
    assert not scene.velocities[target].any()
    result = run_impact(spec, tmp_path / "held", RunOptions())
    series = np.loadtxt(tmp_path / "held" / "series.dat")
    columns = {name: k for k, name in enumerate(BINARY_COLUMNS)}
    for name in ("tx", "ty"):
        assert np.ptp(series[:, columns[name]]) == 0.0
    for name in ("tvx", "tvy", "tLz"):
        assert not series[:, columns[name]].any()
    assert result["vibration_target"] == 0.0 and result["target_held"]
    assert abs(result["energy_drift"]) < 1e-3
    # the disk's momentum reversed along the normal: the hold took (1 + e) M v_n of it
    assert result["momentum_change"] > 0.5


@pytest.mark.lammps
def test_the_surface_partner_is_a_held_ring_built_like_the_disks_surface(tmp_path):
    """partner surface: a held ring of radius 20 R at the disk's surface
    spacing, its points moved along the normal by the disk's roughness; met
    by the disk, the line of centres at the apse and at the first touch agree
    to within what the ring's curvature turns them by (a wall's fixed normal)."""
    spec = SceneSpec(**{**BINARY, "seed": 5, "partner": "surface", "gamma_deg": 45.0, "vn": 0.05})
    scene = build_scene(spec)
    target = scene.molecule != DISK
    ring = scene.positions[target]
    radius = np.linalg.norm(ring, axis=1) / spec.radius
    assert set(scene.molecule[target]) == {3} and set(scene.types[target]) == {3}
    assert abs(np.median(radius) - SURFACE_RADIUS) < 0.01
    assert np.std(radius) == pytest.approx(spec.roughness, rel=0.1)
    steps = np.linalg.norm(np.diff(ring, axis=0), axis=1) / spec.radius
    assert np.median(steps) == pytest.approx(scene.info["disk_spacing"] / spec.radius, rel=0.05)
    result = run_impact(spec, tmp_path / "surface", RunOptions())
    angles = [result[f"normal_angle_deg_{name}"] for name in ("apse", "first_touch")]
    # the contact slides about v_t T = 0.05 c x 8 R/c = 0.4 R: 1.1 degrees of a 21 R orbit
    assert np.ptp(angles) < 2.0
    assert result["vibration_target"] == 0.0 and abs(result["energy_drift"]) < 1e-3


@pytest.mark.parametrize(
    "changes, words",
    [
        (dict(partner="mirror"), "partner must be one of"),
        (dict(target="wall", partner="image"), "partner applies to target disk"),
        (dict(partner="image", partner_seed=3), "partner_seed applies to partner independent"),
        (dict(wall_width=12.0), "wall_width applies to target wall"),
        (dict(n_wall=800), "n_wall applies to target wall"),
        (dict(target="floor"), "target must be one of"),
        (dict(target="wall", partner_lattice="random"), "partner_lattice applies to target disk"),
        (dict(partner_lattice="hexagonal"), "partner_lattice must be one of"),
    ],
)
def test_a_binary_scene_refuses_what_does_not_apply(changes, words):
    with pytest.raises(InputError, match=words):
        SceneSpec(**{**BINARY, **changes}).validate()


@pytest.mark.parametrize(
    "args, words",
    [
        (["--target", "disk", "--n-wall", "800"], "--n-wall applies to --target wall"),
        (["--target", "disk", "--wall-width", "12"], "--wall-width applies to --target wall"),
        (["--target", "disk", "--wall-fixed", "all"], "--wall-fixed applies to --target wall"),
        (["--target", "disk", "--wall-ka", "1"], "--wall-ka applies to --target wall"),
        (["--partner-lattice", "random"], "--partner-lattice applies to --target disk"),
        (["--partner-seed", "3"], "--partner-seed applies to --target disk"),
        (["--partner", "image"], "--partner applies to --target disk"),
    ],
)
def test_the_command_line_refuses_wall_options_for_two_disks(tmp_path, args, words):
    out = tmp_path / "scene"
    proc = subprocess.run(
        [sys.executable, "-m", "builder", "scene", "--out", str(out), *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert words in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_a_binary_study_refuses_wall_options():
    with pytest.raises(InputError, match="wall_fixed applies to target wall"):
        Study("binary_wall_fixed", target="disk", wall_fixed="all").validate()


@pytest.fixture(scope="module")
def binary_runs(tmp_path_factory):
    """One impact of two 200-point disks, by velocity Verlet on one rank and
    two, and by rRESPA."""
    root = tmp_path_factory.mktemp("binary")
    spec = SceneSpec(**{**BINARY, "seed": 2})
    runs = {}
    for name, options in {
        "verlet": RunOptions(),
        "two ranks": RunOptions(nprocs=2),
        "respa": RunOptions(integrator="respa", dt=RESPA_DT, nrespa=RESPA_NRESPA),
    }.items():
        runs[name] = run_impact(dataclasses.replace(spec), root / name.replace(" ", "_"), options)
    return runs


@pytest.mark.lammps
@pytest.mark.mpi
@pytest.mark.slow
@pytest.mark.parametrize("run", ["verlet", "two ranks", "respa"])
def test_a_binary_impact_conserves_momentum_and_angular_momentum(binary_runs, run):
    """Nothing is held: the springs and the lever rule are central, Verlet
    and rRESPA keep both momenta to round-off (1e-10 relative, the issue's)."""
    result = binary_runs[run]
    assert result["momentum_change"] < 1e-10
    assert result["angular_momentum_change"] < 1e-10
    assert abs(result["energy_drift"]) < 1e-3
    assert 0.0 < result["e"] < 1.2 and -1.5 < result["beta"] < 1.0


@pytest.mark.lammps
@pytest.mark.mpi
@pytest.mark.slow
def test_one_and_two_ranks_give_the_same_rebound(binary_runs):
    one, two = binary_runs["verlet"], binary_runs["two ranks"]
    assert two["e"] == pytest.approx(one["e"], abs=1e-6)
    assert two["beta"] == pytest.approx(one["beta"], abs=1e-6)


# Synthetic series: two rigid disks whose centres move on straight lines and
# meet, with the line of their centres along n, at one row.


def synthetic_series(normal, v_in, v_out, spins_in, spins_out, masses=(800.0, 790.0), rows=41):
    """A binary series.dat of rigid disks of radius 1: relative velocity
    v_in before the row in the middle, v_out after it, the centre of mass at
    rest; the centres 2 apart along ``normal`` at that row, where the
    contact acts (pe_contact > 0 on the rows around it)."""
    m_a, m_b = masses
    inertia = (0.45 * m_a, 0.45 * m_b)
    time = np.linspace(-2.0, 2.0, rows)
    relative = np.where(time[:, None] < 0, time[:, None] * v_in, time[:, None] * v_out)
    relative = relative + 2.0 * np.asarray(normal)
    share_a, share_b = m_b / (m_a + m_b), -m_a / (m_a + m_b)
    velocity = np.where(time[:, None] < 0, v_in, v_out)
    spin_a = np.where(time < 0, spins_in[0], spins_out[0])
    spin_b = np.where(time < 0, spins_in[1], spins_out[1])
    values = {
        "step": np.arange(rows),
        "time": time,
        "x": share_a * relative[:, 0],
        "y": share_a * relative[:, 1],
        "vx": share_a * velocity[:, 0],
        "vy": share_a * velocity[:, 1],
        "Lz": inertia[0] * spin_a,
        "Izz": np.full(rows, inertia[0]),
        "omega_z": spin_a,
        "tx": share_b * relative[:, 0],
        "ty": share_b * relative[:, 1],
        "tvx": share_b * velocity[:, 0],
        "tvy": share_b * velocity[:, 1],
        "tLz": inertia[1] * spin_b,
        "tIzz": np.full(rows, inertia[1]),
        "tomega_z": spin_b,
        "pe_contact": (np.abs(time) < 0.5).astype(float),
    }
    for name in ("fx", "fy", "tfx", "tfy"):
        values[name] = np.zeros(rows)
    return np.rec.fromarrays([values[c] for c in BINARY_COLUMNS], names=BINARY_COLUMNS)


@pytest.mark.parametrize("angle", [0.0, 12.0, -30.0])
def test_a_smooth_elastic_collision_gives_e_one_and_beta_minus_one(angle):
    """Reflection about the apse's normal, spins unchanged: e = 1 and beta =
    -1 at any orientation of the line of centres, and the normal found is it."""
    theta = np.radians(angle)
    normal = np.array([np.sin(theta), np.cos(theta)])
    tangent = np.array([normal[1], -normal[0]])
    v_in = -0.1 * normal + 0.07 * tangent
    v_out = 0.1 * normal + 0.07 * tangent
    series = synthetic_series(normal, v_in, v_out, (0.0, 0.0), (0.0, 0.0))
    at, found = apse(series)
    assert at == pytest.approx(0.0, abs=1e-12)
    assert found == pytest.approx(normal, abs=1e-12)
    rebound, where = binary_rebound(series)
    assert rebound.e == pytest.approx(1.0, abs=1e-12)
    assert rebound.beta == pytest.approx(-1.0, abs=1e-12)
    assert rebound.cot_gamma == pytest.approx(0.1 / 0.07, rel=1e-12)
    assert where["apse_angle_deg"] == pytest.approx(angle, abs=1e-9)


def test_the_spins_enter_the_contact_points_velocity():
    """Spins after the impact that stop the contact points' slip: beta = 0;
    each disk's spin counts with R, both with the same sign (v_c = v_A - v_B
    + R (w_A + w_B) t)."""
    normal, tangent = np.array([0.0, 1.0]), np.array([1.0, 0.0])
    v_in, v_out = -0.1 * normal + 0.1 * tangent, 0.1 * normal + 0.1 * tangent
    series = synthetic_series(normal, v_in, v_out, (0.0, 0.0), (-0.04, -0.06))
    rebound, _ = binary_rebound(series)
    assert rebound.beta == pytest.approx(0.0, abs=1e-12)
    assert rebound.e == pytest.approx(1.0, abs=1e-12)


def test_momentum_change_measures_a_lost_momentum():
    normal = np.array([0.0, 1.0])
    v_in, v_out = np.array([0.05, -0.1]), np.array([0.05, 0.1])
    series = synthetic_series(normal, v_in, v_out, (0.0, 0.0), (0.0, 0.0))
    kept = momentum_change(series, (800.0, 790.0), 1.0)
    assert kept["momentum_change"] < 1e-15 and kept["angular_momentum_change"] < 1e-15
    series["tvx"][-1] += 1e-6  # the target loses momentum at the end
    lost = momentum_change(series, (800.0, 790.0), 1.0)
    scale = (800.0 + 790.0) * np.hypot(0.05, 0.1) * 0.5  # each disk: half the relative speed
    assert lost["momentum_change"] == pytest.approx(790.0 * 1e-6 / scale, rel=1e-3)


def test_the_apse_between_rows_is_found_from_its_neighbours():
    """Centres that come closest between two rows (at t0, the rows 0.1 apart
    and 0.037 off it), on a curved path: the parabola through the closest row
    and its neighbours finds the normal there far closer than the closest
    row's own line of centres does."""
    theta = np.radians(20.0)
    normal = np.array([np.sin(theta), np.cos(theta)])
    tangent = np.array([normal[1], -normal[0]])
    time = np.arange(-2.0, 2.0, 0.1) + 0.037
    tau = time[:, None]
    relative = (2.0 + 0.05 * tau**2) * normal + 0.1 * tau * tangent
    values = {name: np.zeros(len(time)) for name in BINARY_COLUMNS}
    values.update(time=time, x=relative[:, 0], y=relative[:, 1])
    values["pe_contact"] = (np.abs(time) < 0.5).astype(float)
    series = np.rec.fromarrays([values[c] for c in BINARY_COLUMNS], names=BINARY_COLUMNS)
    at, found = apse(series)
    nearest = relative[np.argmin(np.linalg.norm(relative, axis=1))]
    nearest_error = np.linalg.norm(nearest / np.linalg.norm(nearest) - normal)
    assert nearest_error > 1e-3  # the rows alone miss the normal
    assert np.linalg.norm(found - normal) < 1e-3 * nearest_error
    assert at == pytest.approx(0.0, abs=1e-3)


@pytest.mark.lammps
def test_the_disks_stop_only_once_parted_for_good(tmp_path):
    """Run on to tmax instead of stopping at the deck's first check after the
    disks parted: e and beta change by round-off only (nothing acts on
    either disk's centre or spin once they are apart)."""
    from builder.lammps_data import write_scene
    from runner.impact import run_scene

    scene = build_scene(SceneSpec(**{**BINARY, "seed": 5}))
    stopped = run_scene(write_scene(scene, tmp_path / "stopped"), RunOptions(tmax=30.0))
    on = run_scene(write_scene(scene, tmp_path / "on"), RunOptions(tmax=30.0), {"early_stop": "no"})
    assert on["time_end"] > stopped["time_end"] + 5.0
    assert on["e"] == pytest.approx(stopped["e"], abs=1e-10)
    assert on["beta"] == pytest.approx(stopped["beta"], abs=1e-10)
    assert on["touches"] == stopped["touches"]
