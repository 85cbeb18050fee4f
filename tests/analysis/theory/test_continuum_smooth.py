"""The quasi-static 2-D Hertz impact of analysis/theory/continuum_smooth.py."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from analysis.theory import continuum_smooth as cs

IMPACT = cs.Impact(mass=800.0, e_disk=250.0, e_wall=2500.0, nu_disk=0.29, nu_wall=0.29, vn=0.1)
LAYERED = replace(
    IMPACT, contact_a=300.0, contact_v0=120000.0, cutoff=0.1075, surface_spacing=0.0676
)


def flamant_vertical(x: float, depth: float, e: float, nu: float) -> float:
    """Downward displacement at (x, depth) under a unit line load at the origin (plane stress).

    Flamant's field integrated from the strains (Barber, Elasticity): with theta
    from the load's line, u_r = -(2/(pi E)) cos(t) ln r + ((1-nu)/(pi E)) (cos t - t sin t),
    u_t = (2 nu/(pi E)) sin t + (2/(pi E)) sin t ln r - ((1-nu)/(pi E)) t cos t.
    """
    r, t = np.hypot(x, depth), np.arctan2(x, depth)
    u_r = -2.0 / (np.pi * e) * np.cos(t) * np.log(r) + (1.0 - nu) / (np.pi * e) * (
        np.cos(t) - t * np.sin(t)
    )
    u_t = (
        2.0 * nu / (np.pi * e) * np.sin(t)
        + 2.0 / (np.pi * e) * np.sin(t) * np.log(r)
        - (1.0 - nu) / (np.pi * e) * t * np.cos(t)
    )
    return float(u_r * np.cos(t) - u_t * np.sin(t))


def hertz_pressure(s: float, force: float, a: float) -> float:
    return 2.0 * force / (np.pi * a) * np.sqrt(max(0.0, 1.0 - (s / a) ** 2))


def loaded(point, force: float, a: float, at: float | None = None) -> float:
    """A displacement kernel integrated over Hertz's pressure (``at``: its singular point)."""
    points = None if at is None else [at]
    return quad(lambda s: hertz_pressure(s, force, a) * point(s), -a, a, limit=200, points=points)[
        0
    ]


def test_elastic_rebound_and_symmetric_pulse():
    for impact in (IMPACT, LAYERED, replace(IMPACT, beam=0.003)):
        pulse = cs.hertz_pulse(impact, samples=401)
        assert pulse.rebound_speed == pytest.approx(impact.vn, rel=1e-6)
        assert cs.rise_share(pulse.time, pulse.force, 0.05) == pytest.approx(0.5, abs=3e-3)


def test_linear_spring_gives_half_a_period():
    pulse = cs.integrate(lambda x: -300.0 * x if x < 0.0 else 0.0, 800.0, 0.1, 0.0)
    assert pulse.contact_time == pytest.approx(np.pi * np.sqrt(800.0 / 300.0), rel=1e-6)
    assert pulse.peak_force == pytest.approx(0.1 * np.sqrt(800.0 * 300.0), rel=1e-4)


def test_time_scales_as_sqrt_mass_over_modulus():
    base = cs.hertz_pulse(IMPACT, samples=401).contact_time
    heavier = replace(IMPACT, mass=4.0 * IMPACT.mass, vn=IMPACT.vn / 2.0)
    assert cs.hertz_pulse(heavier, samples=401).contact_time == pytest.approx(2.0 * base, rel=1e-6)
    stiffer = replace(IMPACT, mass=3.0 * IMPACT.mass, e_disk=750.0, e_wall=7500.0)
    assert cs.hertz_pulse(stiffer, samples=401).contact_time == pytest.approx(base, rel=1e-6)


def test_contact_time_carries_the_logarithm():
    """T^2 grows as (pi M / E*) ln(1 / P_max): no power law of v."""
    pulses = [cs.hertz_pulse(replace(IMPACT, vn=v), samples=201) for v in (1e-5, 1e-6)]
    slope = (pulses[1].contact_time ** 2 - pulses[0].contact_time ** 2) / np.log(
        pulses[0].peak_force / pulses[1].peak_force
    )
    assert slope == pytest.approx(np.pi * IMPACT.mass / IMPACT.e_star, rel=2e-3)
    ratio = (
        cs.hertz_pulse(replace(IMPACT, vn=0.01), samples=401).contact_time
        / cs.hertz_pulse(IMPACT, samples=401).contact_time
    )
    assert 1.2 < ratio < 1.45  # 3-D Hertz's v^(-1/5) would give 1.585


def test_half_width_from_the_surface_kernel():
    """Hertz's a makes the two surfaces' displacement the cylinder's parabola."""
    force = 20.0
    a = cs.half_width(force, IMPACT)

    def surface(x: float) -> float:  # both bodies, the plane-stress surface kernel
        kernel = lambda s: -2.0 / (np.pi * IMPACT.e_star) * np.log(abs(x - s))  # noqa: E731
        return loaded(kernel, force, a, at=x)

    drop = surface(0.0) - surface(a / 2.0)
    assert drop == pytest.approx((a / 2.0) ** 2 / (2.0 * IMPACT.radius), rel=1e-4)


def test_wall_approach_from_flamant_field():
    """The wall's part, P/(pi E)(2 ln(2D/a) - nu), against Flamant's field at depth D."""
    wall_only = replace(IMPACT, e_disk=1e300)
    force, depth = 20.0, 2.0
    a = cs.half_width(force, wall_only)
    e, nu = wall_only.e_wall, wall_only.nu_wall
    surface = loaded(lambda s: flamant_vertical(-s, 0.0, e, nu), force, a, at=0.0)
    below = loaded(lambda s: flamant_vertical(-s, depth, e, nu), force, a)
    # the formula assumes a << D: its error is O((a/D)^2)
    assert surface - below == pytest.approx(cs.elastic_approach(force, wall_only), rel=2e-3)


def test_plane_stress_not_plane_strain():
    """Each body's compliance is 1/E: plane strain's (1 - nu^2)/E would be 8 % stiffer here."""
    poisson = replace(IMPACT, nu_disk=0.45)
    assert (
        cs.hertz_pulse(poisson, samples=401).contact_time
        == cs.hertz_pulse(IMPACT, samples=401).contact_time
    )


def test_layer_adds_the_travel_within_the_cutoff():
    hard, layered = cs.hertz_pulse(IMPACT, samples=401), cs.hertz_pulse(LAYERED, samples=401)
    extra = layered.contact_time - hard.contact_time
    onset = cs.contact_gap(hard.peak_force * 0.05, LAYERED)  # gap where the force is 5 % of peak
    assert 2.0 * (LAYERED.cutoff - onset) / IMPACT.vn == pytest.approx(extra, rel=0.15)
    assert layered.force_window(0.05) == pytest.approx(hard.force_window(0.05), rel=0.03)


def test_threshold_window_of_a_triangle():
    time = np.linspace(0.0, 4.0, 9)
    force = np.interp(time, [0.0, 1.0, 4.0], [0.0, 1.0, 0.0])
    assert cs.threshold_window(time, force, 0.5) == pytest.approx(0.5 * 4.0)
    assert cs.rise_share(time, force, 0.5) == pytest.approx(0.5 / 2.0)


def test_impact_from_scene():
    scene = {
        "spec": {"radius": 1.0, "vn": 0.1, "wall_height": 2.0},
        "contact": {"a": 300.0, "V0": 1.2e5, "cutoff": 0.1},
        "disk_mass": 811.0,
        "disk_spacing": 0.0673,
        "disk_material": {"E": 1.1, "nu": 0.3},
        "wall_material": {"E": 1.2, "nu": 0.25},
        "ka_disk": 200.0,
        "ka_wall": 2000.0,
    }
    impact = cs.impact_from_scene(scene)
    assert (impact.e_disk, impact.e_wall) == pytest.approx((220.0, 2400.0))
    assert impact.surface_spacing == pytest.approx(2.0 * np.pi / 93.0)
    assert cs.impact_from_scene(scene, wall_depth=8.0).wall_depth == 8.0


def test_bad_fraction_is_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        cs.main([str(tmp_path), "--fraction", "1.5"])
    assert stop.value.code != 0
    assert "--fraction" in capsys.readouterr().err
