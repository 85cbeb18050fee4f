"""The three normals of a binary impact (analysis/impact/binary.py) and the wall's
impulse normal (analysis/normal_check.py): where they must agree they do,
where the contact turns the line of centres they differ, and the impulse's
normal is the contact's even with friction."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from analysis.impact.binary import binary_normals, first_touch, impulse_normal
from analysis.impact.series import BINARY_COLUMNS
from analysis.normal_check import robustness, wall_impulse

MASSES = (800.0, 790.0)


def central_collision(gamma_deg: float, reach: float, cutoff: float, speed: float = 0.1):
    """series.dat of two rigid, spinless disks of radius 1 meeting under a
    smooth central repulsion exp(-(d - 2) / reach), felt within 2 + cutoff:
    no friction, no loss, an orbit symmetric about its apse. The relative
    velocity (speed tan gamma, -speed) is aimed at first touch with the line
    of centres along +y, as builder/binary.py aims."""
    m_a, m_b = MASSES
    reduced = m_a * m_b / (m_a + m_b)
    strength = 0.5 * reduced * speed**2 * 50.0  # turns back well before d = 2

    def force(r):
        d = np.linalg.norm(r)
        # the exponent capped: a trial step of the integrator may overshoot
        push = np.exp(np.minimum(-(d - 2.0) / reach, 50.0))
        return np.where(d < 2.0 + cutoff, strength / reach * push, 0.0)

    def rates(_, state):
        r, v = state[:2], state[2:]
        return [*v, *(force(r) * r / np.linalg.norm(r) / reduced)]

    gamma = np.radians(gamma_deg)
    v0 = np.array([speed * np.tan(gamma), -speed])
    touch = (2.0 + cutoff) * np.array([0.0, 1.0])
    start = touch - 0.5 * v0 / np.linalg.norm(v0)  # half a radius before first touch
    duration = 2.0 * 0.5 / np.linalg.norm(v0) + 40.0 * reach / speed
    times = np.arange(0.0, duration, 0.01)
    orbit = solve_ivp(rates, (0.0, times[-1]), [*start, *v0], t_eval=times, rtol=1e-11, atol=1e-13)
    r, v = orbit.y[:2].T, orbit.y[2:].T
    share_a, share_b = m_b / (m_a + m_b), -m_a / (m_a + m_b)
    d = np.linalg.norm(r, axis=1)
    values = {name: np.zeros(len(times)) for name in BINARY_COLUMNS}
    values.update(
        step=np.arange(len(times)),
        time=times,
        x=share_a * r[:, 0],
        y=share_a * r[:, 1],
        vx=share_a * v[:, 0],
        vy=share_a * v[:, 1],
        tx=share_b * r[:, 0],
        ty=share_b * r[:, 1],
        tvx=share_b * v[:, 0],
        tvy=share_b * v[:, 1],
        Izz=np.full(len(times), 0.45 * m_a),
        tIzz=np.full(len(times), 0.45 * m_b),
        pe_contact=np.where(d < 2.0 + cutoff, strength * np.exp(-(d - 2.0) / reach), 0.0),
    )
    assert values["pe_contact"][0] == 0.0 and values["pe_contact"][-1] == 0.0
    return np.rec.fromarrays([values[c] for c in BINARY_COLUMNS], names=BINARY_COLUMNS)


def test_a_stiff_smooth_contact_gives_one_normal():
    """A short-ranged repulsion: the line of centres hardly turns, so the
    apse, first touch and impulse give the same e = 1 and beta = -1, and the
    first touch is at the aimed incidence."""
    series = central_collision(30.0, reach=1e-4, cutoff=1e-3)
    found = binary_normals(series, MASSES)
    for name in ("apse", "first_touch", "impulse"):
        assert found[f"e_{name}"] == pytest.approx(1.0, abs=2e-3), name
        assert found[f"beta_{name}"] == pytest.approx(-1.0, abs=2e-3), name
    assert abs(found["impulse_tilt_deg"]) < 1e-6  # no friction: J along the normal
    cot = 1 / np.tan(np.radians(30.0))
    assert found["cot_gamma_first_touch"] == pytest.approx(cot, rel=5e-3)


def test_a_soft_contact_at_grazing_incidence_separates_the_first_touch():
    """A long-ranged repulsion at 70 degrees: the orbit turns long before the
    apse, so the line of centres at first touch is another normal, whose e is
    not 1; the apse and the impulse, on the orbit's symmetry line, still give
    e = 1, and the robustness check withholds such an e."""
    series = central_collision(70.0, reach=0.05, cutoff=0.3)
    found = binary_normals(series, MASSES)
    assert found["e_apse"] == pytest.approx(1.0, abs=1e-6)
    assert found["e_impulse"] == pytest.approx(1.0, abs=1e-6)
    assert found["normal_angle_deg_impulse"] == pytest.approx(
        found["normal_angle_deg_apse"], abs=1e-4
    )
    assert abs(found["e_first_touch"] - 1.0) > 0.05
    assert abs(found["normal_angle_deg_first_touch"] - found["normal_angle_deg_apse"]) > 1.0


def test_first_touch_is_midway_between_the_rows_around_it():
    series = central_collision(45.0, reach=0.01, cutoff=0.05)
    k = int(np.flatnonzero(series["pe_contact"] > 0)[0])
    at, normal = first_touch(series)
    assert at == pytest.approx(0.5 * (series["time"][k - 1] + series["time"][k]))
    r = np.array([series["x"] - series["tx"], series["y"] - series["ty"]]).T
    assert normal @ (r[k - 1] / np.linalg.norm(r[k - 1])) > np.cos(np.radians(1.0))


def frictional_series(normal_deg: float, j_n: float, j_t: float):
    """Rigid disks (radius 1) given an impulse J = j_n n + j_t t at contact
    points R from their centres along n, in one row: each spin changes by
    R j_t / I (dL_A = dL_B = R J.t)."""
    theta = np.radians(normal_deg)
    n = np.array([np.sin(theta), np.cos(theta)])
    t = np.array([n[1], -n[0]])
    m_a, m_b = MASSES
    inertia = (0.45 * m_a, 0.45 * m_b)
    j = j_n * n + j_t * t
    v_a_in = (-0.1 * n + 0.2 * t) * m_b / (m_a + m_b)
    v_b_in = -v_a_in * m_a / m_b
    v_a_out, v_b_out = v_a_in + j / m_a, v_b_in - j / m_b
    rows = {name: np.zeros(2) for name in BINARY_COLUMNS}
    rows.update(
        step=np.arange(2.0),
        time=np.array([0.0, 10.0]),
        x=np.array([2.0 * n[0] * m_b / (m_a + m_b)] * 2),
        y=np.array([2.0 * n[1] * m_b / (m_a + m_b)] * 2),
        vx=np.array([v_a_in[0], v_a_out[0]]),
        vy=np.array([v_a_in[1], v_a_out[1]]),
        tvx=np.array([v_b_in[0], v_b_out[0]]),
        tvy=np.array([v_b_in[1], v_b_out[1]]),
        Lz=np.array([0.0, j_t]),
        tLz=np.array([0.0, j_t]),
        Izz=np.full(2, inertia[0]),
        tIzz=np.full(2, inertia[1]),
    )
    return np.rec.fromarrays([rows[c] for c in BINARY_COLUMNS], names=BINARY_COLUMNS), n


@pytest.mark.parametrize("normal_deg", [0.0, 25.0, -40.0])
def test_the_impulse_s_normal_is_the_contact_s_despite_friction(normal_deg):
    """A tangential impulse tilts J by atan(j_t / j_n); the spins' change
    turns it back onto the contact's normal."""
    j_n, j_t = 30.0, -6.0
    series, n = frictional_series(normal_deg, j_n, j_t)
    found, tilt = impulse_normal(series, MASSES, 1.0)
    assert found == pytest.approx(n, abs=1e-12)
    assert tilt == pytest.approx(np.degrees(np.arctan2(j_t, j_n)), abs=1e-9)


def wall_row(normal_deg: float, e: float, mu: float, gamma_deg: float = 60.0, ratio: float = 0.5):
    """A wall impact's table row: a disk (radius 1, I0 = ratio M) sliding
    onto a contact plane tilted by normal_deg, restituting e along its normal
    and Coulomb friction mu along it; e, beta, cot gamma and omega measured
    at the wall's fixed normal +y, as the tables have them."""
    theta = np.radians(normal_deg)
    n = np.array([np.sin(theta), np.cos(theta)])
    t = np.array([n[1], -n[0]])
    v_n = 0.05
    v_in = np.array([v_n * np.tan(np.radians(gamma_deg)), -v_n])
    j_n = -(1 + e) * (v_in @ n)  # per mass
    j = j_n * n - mu * j_n * np.sign(v_in @ t) * t
    omega = (j @ t) / ratio  # dL = R J.t, I0 = ratio M R^2
    v_out = v_in + j
    c_in, c_out = v_in, v_out + omega * np.array([1.0, 0.0])
    row = {
        "vn_in_c": v_n,
        "cot_gamma": -c_in[1] / c_in[0],
        "e": -c_out[1] / c_in[1],
        "beta": -c_out[0] / c_in[0],
        "omega": omega,
        "disk_inertia_ratio": ratio,
    }
    return row, n, t, v_in, v_out, omega


def test_a_flat_wall_s_impulse_normal_is_its_fixed_normal():
    row, *_ = wall_row(0.0, 0.9, 0.2)
    found = wall_impulse(row)
    assert found["normal_angle_deg_impulse"] == pytest.approx(0.0, abs=1e-9)
    assert found["e_impulse"] == pytest.approx(row["e"], rel=1e-12)
    assert found["beta_impulse"] == pytest.approx(row["beta"], rel=1e-12)
    assert found["impulse_tilt_deg"] == pytest.approx(-np.degrees(np.arctan(0.2)), abs=1e-9)


def test_a_tilted_contact_plane_shows_in_the_wall_s_impulse_normal():
    """A contact plane tilted 4 degrees: the fixed normal's e is not the
    contact's 0.9 (it is above 1 here), the impulse's normal finds the plane
    and its e is 0.9."""
    row, n, t, v_in, v_out, omega = wall_row(-4.0, 0.9, 0.2, gamma_deg=75.0)
    found = wall_impulse(row)
    assert found["normal_angle_deg_impulse"] == pytest.approx(-4.0, abs=1e-9)
    assert found["e_impulse"] == pytest.approx(0.9, rel=1e-9)
    assert row["e"] > 1.0


def test_robustness_withholds_what_the_normals_disagree_on():
    """Wall rows at two angles, one on a flat contact and one on a tilted one
    (a seed's tilt scattered about it): e is reported at the first and
    withheld at the second."""
    rng = np.random.default_rng(1)
    rows = []
    for seed in range(1, 21):
        for gamma, tilt in ((30.0, 0.0), (75.0, -4.0)):
            e = 0.9 + 0.01 * rng.standard_normal()
            row, *_ = wall_row(tilt, e, 0.2, gamma_deg=gamma)
            rows.append(
                {
                    **row,
                    "seed": seed,
                    "gamma_deg": gamma,
                    "study_lattice": "random",
                    "target": "wall",
                }
            )
    check = robustness(rows, resamples=50)["lattices"]["random"]
    assert check["e_robust"] == [True, False]
    assert check["e_spread"][0] < 1e-12


def test_first_touch_at_the_builder_s_time_is_the_aimed_line():
    """The synthetic pair is aimed as the builder aims: at the first touch
    (0.5 / |v| after the start) the line of centres is +y, and the rows,
    between which the centres move uniformly, give it exactly."""
    speed, gamma = 0.1, 55.0
    series = central_collision(gamma, reach=0.01, cutoff=0.05, speed=speed)
    at = 0.5 / (speed / np.cos(np.radians(gamma)))
    assert not np.any(np.isclose(series["time"], at))  # between two rows
    when, normal = first_touch(series, at)
    assert when == at
    assert normal == pytest.approx([0.0, 1.0], abs=1e-9)  # the integrator's tolerance
    found = binary_normals(series, MASSES, touch_time=at)
    assert found["cot_gamma_first_touch"] == pytest.approx(1 / np.tan(np.radians(gamma)), rel=1e-9)


def test_robustness_checks_every_lattice_on_its_own():
    """Two lattices with the same rows: the same verdicts for both."""
    rows = []
    for seed in range(1, 11):
        for gamma in (30.0, 60.0):
            row, *_ = wall_row(0.0, 0.9 + 0.001 * seed, 0.2, gamma_deg=gamma)
            for lattice in ("random", "triangular"):
                rows.append({**row, "seed": seed, "gamma_deg": gamma, "study_lattice": lattice})
    check = robustness(rows, resamples=20)["lattices"]
    assert check["random"]["e_robust"] == check["triangular"]["e_robust"] == [True, True]


def test_the_synthetic_wall_rows_hit_a_flat_wall():
    """tests/synthetic.py's rows: their spin makes the impulse's normal the
    wall's, so the two normals agree exactly."""
    from tests.synthetic import impact_rows

    rows = impact_rows("random", lambda psi: -0.5 + 0.1 * psi, seeds=2)
    for row in rows:
        found = wall_impulse(row)
        assert found["normal_angle_deg_impulse"] == pytest.approx(0.0, abs=1e-9)
        assert found["e_impulse"] == pytest.approx(row["e"], rel=1e-9)
