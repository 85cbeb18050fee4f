"""The smooth disk's normal impact as quasi-static 2-D Hertz contact (docs/smooth_baseline.md).

A disk of mass M (per unit thickness) and radius R meets a flat elastic wall
at normal speed v. Both bodies are 2-D lattices whose E and nu are measured
by stretching a free strip (docs/calibration.md): they are the in-plane
constants of a sheet, so the continuum is in plane stress and each body's
contact modulus is its E, not E / (1 - nu^2) (plane strain's).

Quasi-static line contact (Johnson, Contact Mechanics, 1985, ch. 4 and 5),
written for plane stress, with P the force per unit thickness:

- half-width of the contact ``a = sqrt(4 P R / (pi E*))``, 1/E* = 1/E_d + 1/E_w;
- the disk's centre approaches the contact by
  ``P / (pi E_d) (2 ln(4 L_d / a) - 1)`` (the half of a diametrically
  compressed disk; L_d = R);
- the wall's surface approaches a point at depth D under the contact by
  ``P / (pi E_w) (2 ln(2 D / a) - nu_w)`` (a half-plane; D the wall's depth).

A 2-D contact has no approach without a reference length (the logarithm):
L_d and D are parameters. The model's exponential contact acts in series:
the surface point under the contact's centre carries
``f = P min(1, 2 h / (pi a))`` (h the disk's surface spacing) and sits at the
gap ``ln(a_c V0 / f) / a_c``. The disk's lowest point is then at the gap
``x = gap(P) - approach(P)`` from the wall's undeformed surface, which sets
P(x); ``M x'' = P(x)`` is integrated from the cutoff, where the model's
contact window opens, back to it. Nothing here dissipates: e = 1.

Not in the half-plane: the 8 R x 2 R wall held at its sides is a clamped
beam (``beam_compliance``, static Timoshenko), and neither body is
quasi-static (their lowest modes: ``analysis.theory.modal_smooth``).
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

TIMOSHENKO_KAPPA = 5.0 / 6.0  # shear coefficient of a rectangular section


@dataclass(frozen=True)
class Impact:
    """A smooth disk's normal impact on a flat wall, in the study's units (R, c, m).

    Attributes
    ----------
    mass : float
        The disk's mass M (its number of points).
    e_disk, e_wall : float
        The 2-D Young's moduli (force per length), E (in ka) times ka.
    nu_disk, nu_wall : float
        The 2-D Poisson ratios.
    vn : float
        Normal speed.
    radius : float
        R.
    disk_reference : float
        L_d, the length in the disk's logarithm (R by default).
    wall_depth : float
        D, the length in the wall's logarithm (its height, 2 R).
    contact_a, contact_v0, cutoff : float
        The exponential contact V0 exp(-a l), cut at ``cutoff``; ``contact_a``
        0 leaves it out (a hard contact, the window from touch to release).
    surface_spacing : float
        h, the spacing of the disk's surface points.
    beam : float
        Extra series compliance of the wall (length per force), 0 for a half-plane.
    """

    mass: float
    e_disk: float
    e_wall: float
    nu_disk: float
    nu_wall: float
    vn: float
    radius: float = 1.0
    disk_reference: float = 1.0
    wall_depth: float = 2.0
    contact_a: float = 0.0
    contact_v0: float = 0.0
    cutoff: float = 0.0
    surface_spacing: float = 0.0
    beam: float = 0.0

    @property
    def e_star(self) -> float:
        """The plane-stress contact modulus, 1 / (1/E_d + 1/E_w)."""
        return 1.0 / (1.0 / self.e_disk + 1.0 / self.e_wall)


def half_width(force: float, impact: Impact) -> float:
    """Hertz's half-width of the line contact, a = sqrt(4 P R / (pi E*))."""
    return float(np.sqrt(4.0 * force * impact.radius / (np.pi * impact.e_star)))


def elastic_approach(force: float, impact: Impact) -> float:
    """Approach of the disk's centre and the wall's reference under the force P.

    The disk's part P / (pi E_d) (2 ln(4 L_d / a) - 1), the wall's
    P / (pi E_w) (2 ln(2 D / a) - nu_w), and the beam's P * ``impact.beam``.
    """
    if force <= 0.0:
        return 0.0
    a = half_width(force, impact)
    disk_log = 2.0 * np.log(4.0 * impact.disk_reference / a) - 1.0
    wall_log = 2.0 * np.log(2.0 * impact.wall_depth / a) - impact.nu_wall
    disk = force / (np.pi * impact.e_disk) * disk_log
    wall = force / (np.pi * impact.e_wall) * wall_log
    return float(disk + wall + impact.beam * force)


def contact_gap(force: float, impact: Impact) -> float:
    """Gap of the exponential contact under the contact's centre at total force P."""
    if impact.contact_a <= 0.0:
        return 0.0
    share = min(1.0, 2.0 * impact.surface_spacing / (np.pi * half_width(force, impact)))
    return float(np.log(impact.contact_a * impact.contact_v0 / (force * share)) / impact.contact_a)


def force_at_gap(x: float, impact: Impact) -> float:
    """The contact force P at which the lowest point's undeformed gap is ``x``."""
    start = impact.cutoff if impact.contact_a > 0.0 else 0.0
    if x >= start:
        return 0.0

    def mismatch(log_force: float) -> float:
        force = np.exp(log_force)
        return contact_gap(force, impact) - elastic_approach(force, impact) - x

    # Hertz's approach holds while a << R; the search stops where a = R.
    low, high = -80.0, float(np.log(np.pi * impact.e_star * impact.radius / 4.0))
    if mismatch(low) < 0.0:  # below the force the cutoff allows: no contact yet
        return 0.0
    if mismatch(high) > 0.0:
        raise ValueError(f"gap {x:.4g} needs a contact wider than the disk: Hertz does not hold")
    return float(np.exp(brentq(mismatch, low, high, xtol=1e-13)))


@dataclass(frozen=True)
class Pulse:
    """The integrated impact: its window, the rebound and the force's history."""

    contact_time: float
    rebound_speed: float
    peak_force: float
    peak_half_width: float
    time: np.ndarray
    force: np.ndarray

    def force_window(self, fraction: float) -> float:
        """Time during which the force exceeds ``fraction`` of its peak."""
        return threshold_window(self.time, self.force, fraction)


def threshold_crossings(
    time: np.ndarray, force: np.ndarray, fraction: float
) -> tuple[float, float]:
    """First and last crossing of ``fraction`` x max(force), linearly interpolated."""
    time, force = np.asarray(time, float), np.asarray(force, float)
    level = fraction * force.max()
    above = np.flatnonzero(force > level)
    if above.size == 0:
        return float(time[0]), float(time[0])
    i, j = above[0], above[-1]

    def crossing(k0: int, k1: int) -> float:
        f0, f1 = force[k0] - level, force[k1] - level
        return float(time[k0] + (time[k1] - time[k0]) * f0 / (f0 - f1))

    start = crossing(i - 1, i) if i > 0 else float(time[0])
    end = crossing(j, j + 1) if j + 1 < time.size else float(time[-1])
    return start, end


def threshold_window(time: np.ndarray, force: np.ndarray, fraction: float) -> float:
    """Time between the first and last crossing of ``fraction`` x max(force)."""
    start, end = threshold_crossings(time, force, fraction)
    return end - start


def rise_share(time: np.ndarray, force: np.ndarray, fraction: float) -> float:
    """Where the peak falls in the force window: (t_peak - start) / window; 1/2 if symmetric."""
    start, end = threshold_crossings(time, force, fraction)
    return float((np.asarray(time)[np.argmax(force)] - start) / (end - start))


def integrate(
    force_of_gap: Callable[[float], float],
    mass: float,
    vn: float,
    start: float,
    samples: int = 2001,
    max_step: float = 0.02,
    horizon: float = 1e3,
) -> Pulse:
    """Integrate M x'' = P(x) from gap ``start`` at speed -vn until x returns to it.

    Parameters
    ----------
    force_of_gap : callable
        P(x), zero for x >= start.
    mass, vn, start : float
        The disk's mass, the approach speed and the gap where the window opens.
    samples : int
        Points of the force history returned.
    max_step, horizon : float
        The integrator's largest step and the longest contact allowed (R/c).

    Returns
    -------
    Pulse
        The window (first to last instant with x < start), the rebound speed
        and the force history.
    """

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        return [y[1], force_of_gap(y[0]) / mass]

    def leaves(_t: float, y: np.ndarray) -> float:
        return y[0] - start

    leaves.terminal = True
    leaves.direction = 1.0
    solution = solve_ivp(
        rhs,
        (0.0, horizon),
        [start - 1e-12, -vn],
        events=leaves,
        rtol=1e-10,
        atol=1e-13,
        dense_output=True,
        max_step=max_step,
        first_step=max_step / 100.0,
    )
    if solution.status != 1:
        raise RuntimeError("the disk did not leave the wall within the horizon")
    end = float(solution.t_events[0][0])
    times = np.linspace(0.0, end, samples)
    forces = np.array([force_of_gap(x) for x in solution.sol(times)[0]])
    return Pulse(
        contact_time=end,
        rebound_speed=float(solution.y_events[0][0][1]),
        peak_force=float(forces.max()),
        peak_half_width=0.0,
        time=times,
        force=forces,
    )


def hertz_pulse(impact: Impact, samples: int = 2001) -> Pulse:
    """The quasi-static Hertz impact, with the exponential contact in series if set."""
    start = impact.cutoff if impact.contact_a > 0.0 else 0.0
    pulse = integrate(lambda x: force_at_gap(x, impact), impact.mass, impact.vn, start, samples)
    return replace(pulse, peak_half_width=half_width(pulse.peak_force, impact))


def beam_compliance(e_wall: float, nu_wall: float, span: float = 8.0, depth: float = 2.0) -> float:
    """Static centre deflection per force of a beam clamped at both ends (Timoshenko).

    Bending L^3 / (192 E I) with I = depth^3 / 12 per unit thickness, and shear
    L / (4 kappa G depth), G = E / (2 (1 + nu)).
    """
    inertia = depth**3 / 12.0
    shear = e_wall / (2.0 * (1.0 + nu_wall))
    return span**3 / (192.0 * e_wall * inertia) + span / (4.0 * TIMOSHENKO_KAPPA * shear * depth)


def impact_from_scene(scene: dict, **overrides: float) -> Impact:
    """The Impact of a smooth-disk scene.json (both bodies' E from their calibration entries)."""
    spec = scene["spec"]
    contact = scene["contact"]
    radius = float(spec["radius"])
    n_surface = round(2.0 * np.pi * radius / scene["disk_spacing"])
    values = dict(
        mass=float(scene["disk_mass"]),
        e_disk=scene["disk_material"]["E"] * scene["ka_disk"],
        e_wall=scene["wall_material"]["E"] * scene["ka_wall"],
        nu_disk=scene["disk_material"]["nu"],
        nu_wall=scene["wall_material"]["nu"],
        vn=float(spec["vn"]),
        radius=radius,
        disk_reference=radius,
        wall_depth=float(spec["wall_height"]),
        contact_a=float(contact["a"]),
        contact_v0=float(contact["V0"]),
        cutoff=float(contact["cutoff"]),
        surface_spacing=2.0 * np.pi * radius / n_surface,
    )
    values.update(overrides)
    return Impact(**values)


MEASURED = ("e", "contact_time", "vibration_disk", "vibration_wall")


def read_series_force(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Time and normal contact force on the disk (fy) from a run's series.dat."""
    data = np.loadtxt(path, comments="#")
    return data[:, 1], data[:, 10]


def measured_impacts(study: Path | str, gamma_deg: float, fraction: float = 0.05) -> list[dict]:
    """The smooth study's impacts at one angle: result.json's numbers, the force's window and peak.

    Parameters
    ----------
    study : pathlib.Path or str
        A study folder (``<lattice>/s<seed>/g<angle>/result.json`` under it).
    gamma_deg : float
        The angle, degrees (matched to 1e-3).
    fraction : float
        The force window's threshold, as a fraction of the peak force.
    """
    rows = []
    for result in sorted(Path(study).glob("*/s*/g*/result.json")):
        values = json.loads(result.read_text())
        if abs(values["gamma_deg"] - gamma_deg) > 1e-3 or values.get("drift_exceeded"):
            continue
        time, force = read_series_force(result.parent / "series.dat")
        row = {key: float(values[key]) for key in MEASURED}
        row["seed"] = int(values["seed"])
        scene = json.loads((result.parent / "scene.json").read_text())
        row["n_disk"] = int(scene["spec"]["n_disk"])
        row["force_window"] = threshold_window(time, force, fraction)
        row["rise_share"] = rise_share(time, force, fraction)
        # the peak force in M v_n c / R: an oscillator's angular frequency
        row["peak_force"] = (
            float(force.max())
            * scene["spec"]["radius"]
            / (scene["disk_mass"] * scene["spec"]["vn"])
        )
        row["scene"] = str(result.parent / "scene.json")
        rows.append(row)
    return rows


def mean_and_error(values: list[float]) -> tuple[float, float]:
    """Mean over seeds and its standard error (sd / sqrt(n); nan for one seed)."""
    array = np.asarray(values, float)
    error = array.std(ddof=1) / np.sqrt(array.size) if array.size > 1 else float("nan")
    return float(array.mean()), float(error)


def table(studies: list[Path], gamma_deg: float, fraction: float = 0.05) -> str:
    """Markdown rows: measured against predicted, one row per study (resolution)."""
    lines = [
        "| N | seeds | e | contact time (cutoff window) | predicted | force > "
        f"{fraction:g} peak | predicted | peak force / (M v_n c / R) | predicted "
        "| peak's place in the window | predicted | disk vib. | wall vib. |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for study in studies:
        rows = measured_impacts(study, gamma_deg, fraction)
        if not rows:
            continue
        impact = impact_from_scene(json.loads(Path(rows[0]["scene"]).read_text()))
        pulse = hertz_pulse(impact)
        cells = [str(rows[0]["n_disk"]), str(len(rows))]
        for key, predicted in (
            ("e", None),
            ("contact_time", pulse.contact_time),
            ("force_window", pulse.force_window(fraction)),
            ("peak_force", pulse.peak_force / (impact.mass * impact.vn / impact.radius)),
            ("rise_share", rise_share(pulse.time, pulse.force, fraction)),
            ("vibration_disk", None),
            ("vibration_wall", None),
        ):
            mean, error = mean_and_error([row[key] for row in rows])
            cells.append(f"{mean:.4g} +- {error:.2g}")
            if predicted is not None:
                cells.append(f"{predicted:.4g}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def variants(impact: Impact, fraction: float = 0.05) -> str:
    """Markdown rows: the prediction under each choice of reference length, contact and wall."""
    beam = beam_compliance(impact.e_wall, impact.nu_wall)
    choices = (
        ("L_d = R, D = 2 R (the choice)", {}),
        ("L_d = 2 R", {"disk_reference": 2.0 * impact.radius}),
        ("L_d = 0.75 R", {"disk_reference": 0.75 * impact.radius}),
        ("D = R", {"wall_depth": impact.radius}),
        ("D = 8 R (the wall's width)", {"wall_depth": 8.0 * impact.radius}),
        ("hard contact (no exponential)", {"contact_a": 0.0}),
        ("+ clamped beam, static", {"beam": beam}),
        ("+ clamped beam, hard contact", {"beam": beam, "contact_a": 0.0}),
        (
            "+ clamped beam, L_d = 2 R, D = 8 R",
            {"beam": beam, "disk_reference": 2.0, "wall_depth": 8.0},
        ),
    )
    lines = [
        f"| reading | contact time (window) | force > {fraction:g} peak "
        "| peak force / (M v_n c / R) | a / R at the peak | rebound / approach speed |",
        "|---|---|---|---|---|---|",
    ]
    for name, change in choices:
        try:
            pulse = hertz_pulse(replace(impact, **change))
        except ValueError as error:
            lines.append(f"| {name} | {error} | | | | |")
            continue
        lines.append(
            f"| {name} | {pulse.contact_time:.3f} | {pulse.force_window(fraction):.3f} | "
            f"{pulse.peak_force * impact.radius / (impact.mass * impact.vn):.3f} | "
            f"{pulse.peak_half_width / impact.radius:.3f} | {pulse.rebound_speed / impact.vn:.8f} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """``python -m analysis.theory.continuum_smooth STUDY...``: the table of
    docs/smooth_baseline.md."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("studies", nargs="+", type=Path, help="smooth study folders")
    parser.add_argument("--gamma", type=float, default=5.7106, help="angle, degrees")
    parser.add_argument("--fraction", type=float, default=0.05, help="force window threshold")
    parser.add_argument(
        "--variants",
        action="store_true",
        help="also the prediction's choices, on the first study's scene",
    )
    args = parser.parse_args(argv)
    if not 0.0 < args.fraction < 1.0:
        parser.error(f"--fraction must be between 0 and 1, got {args.fraction}")
    print(table(args.studies, args.gamma, args.fraction))
    rows = measured_impacts(args.studies[0], args.gamma, args.fraction)
    if args.variants and rows:
        print()
        impact = impact_from_scene(json.loads(Path(rows[0]["scene"]).read_text()))
        print(variants(impact, args.fraction))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
