"""Energy a contact pulse leaves in each body's vibrations: the modal picture of Gerl and Zippelius.

Gerl and Zippelius (Phys. Rev. E 59, 2361, 1999) expand an elastic disk in
its vibration modes and find e < 1 from the energy the contact leaves in
them. Here the same bookkeeping is done to first order on the model's own
lattices: each body's springs, linearised at rest (all start at their natural
length), give its modes (m = 1: K phi = omega^2 phi); a prescribed normal
force history P(t), spread over the surface points under the contact as
Hertz's semi-ellipse of half-width a(P), leaves in mode k the energy

    E_k = |int q_k(t) exp(i omega_k t) dt|^2 / 2,   q_k(t) = phi_k . f(t),

summed over the elastic modes (the free disk's three rigid modes carry its
rebound; the wall's held points have no degrees of freedom). The force is
prescribed, not solved with the modes (Gerl and Zippelius solve both): a
quasi-static pulse (``analysis.theory.continuum_smooth``) gives what a quasi-static
contact would leave, the measured pulse (series.dat) what the model's own
contact force leaves.
"""

from __future__ import annotations

import argparse
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from builder.lammps_data import read_data

DISK_TYPES = (1, 2)
DISK_SURFACE = 1
WALL_TYPES = (3, 4)
WALL_SURFACE = 3


@dataclass(frozen=True)
class Modes:
    """A body's modes: its free points' rest positions, angular frequencies, shapes."""

    x: np.ndarray  # (n, 2) rest positions of the free points
    surface: np.ndarray  # (n,) True for the body's surface row
    omega: np.ndarray  # (2n,) ascending
    shapes: np.ndarray  # (2n, 2n) columns: mass-normalised modes, (x0, y0, x1, y1, ...)


def stiffness(x: np.ndarray, bonds: np.ndarray, ka: np.ndarray, free: np.ndarray) -> np.ndarray:
    """The springs' stiffness matrix at rest over the free points (ka n n^T per spring)."""
    index = -np.ones(len(x), int)
    index[free] = np.arange(free.sum())
    k = np.zeros((2 * free.sum(), 2 * free.sum()))
    for (i, j), spring in zip(bonds, ka, strict=True):
        n = x[j] - x[i]
        block = spring * np.outer(n, n) / n.dot(n)
        for a, b, sign in ((i, i, 1.0), (j, j, 1.0), (i, j, -1.0), (j, i, -1.0)):
            if index[a] >= 0 and index[b] >= 0:
                k[2 * index[a] : 2 * index[a] + 2, 2 * index[b] : 2 * index[b] + 2] += sign * block
    return k


def body_modes(data: Path | str, body: str) -> Modes:
    """The modes of the disk or the wall of a scene.data (the wall's held points fixed)."""
    system = read_data(data)
    types, surface_type = (
        (DISK_TYPES, DISK_SURFACE) if body == "disk" else (WALL_TYPES, WALL_SURFACE)
    )
    free = np.isin(system.types, types)
    keep = free[system.bonds[:, 0]] | free[system.bonds[:, 1]]
    k = stiffness(system.x, system.bonds[keep], 2.0 * system.k2[keep], free)
    omega2, shapes = np.linalg.eigh(k)
    return Modes(
        x=system.x[free],
        surface=system.types[free] == surface_type,
        omega=np.sqrt(np.clip(omega2, 0.0, None)),
        shapes=shapes,
    )


def contact_loads(
    modes: Modes, force: np.ndarray, half_width: np.ndarray, centre: float, sign: float
) -> tuple[np.ndarray, np.ndarray]:
    """The y-degrees of freedom under the contact and their forces at each time.

    The surface points nearest the contact line (the lowest for the disk, the
    highest for the wall) within ``half_width`` of ``centre`` share P as
    Hertz's semi-ellipse; with none within, the nearest point takes all of it.
    """
    rows = np.flatnonzero(modes.surface)
    rows = rows[np.abs(modes.x[rows, 0] - centre) < 2.0]
    height = modes.x[rows, 1]
    rows = rows[np.abs(height - (height.min() if sign > 0 else height.max())) < 0.5]
    offset = modes.x[rows, 0] - centre
    weights = np.sqrt(
        np.clip(1.0 - (offset[:, None] / np.maximum(half_width, 1e-12)) ** 2, 0, None)
    )
    nearest = np.argmin(np.abs(offset))
    empty = weights.sum(axis=0) == 0.0
    weights[nearest, empty] = 1.0
    loads = sign * force * weights / weights.sum(axis=0)
    return 2 * rows + 1, loads


def residual_energy(
    modes: Modes, dofs: np.ndarray, loads: np.ndarray, time: np.ndarray, rigid: int = 0
) -> np.ndarray:
    """Energy left in each mode once the loads (dofs x times) have acted; rigid modes 0.

    The loads are linear between the times, and each mode's integral of
    q_k(t) exp(i omega_k t) is exact for such a q.
    """
    q = modes.shapes[dofs].T @ loads  # (modes, times)
    omega = modes.omega[:, None]
    dt = np.diff(time)[None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        phase0, phase1 = np.exp(1j * omega * time[None, :-1]), np.exp(1j * omega * time[None, 1:])
        # int over [t0, t1] of (q0 + (q1 - q0) s / dt) exp(i w t) dt, s = t - t0
        slope = (q[:, 1:] - q[:, :-1]) / dt
        part = (q[:, 1:] * phase1 - q[:, :-1] * phase0) / (1j * omega) + slope * (
            phase1 - phase0
        ) / omega**2
    amplitude = part.sum(axis=1)
    energy = 0.5 * np.abs(amplitude) ** 2
    energy[:rigid] = 0.0
    energy[modes.omega < 1e-6] = 0.0
    return energy


def shares(run: Path | str, data: Path | str, samples: int = 4000) -> dict[str, float]:
    """Each body's vibration share left by the measured and the quasi-static pulse of a run.

    Parameters
    ----------
    run : pathlib.Path or str
        An impact folder (scene.json, series.dat, result.json) of a smooth disk.
    data : pathlib.Path or str
        The same seed's scene.data (``python -m builder scene --roughness 0 --seed S``).
    samples : int
        Times at which the measured force is interpolated.

    Returns
    -------
    dict
        ``{pulse}_{body}`` shares of the impact energy M v_n^2 / 2, the run's own
        ``vibration_disk`` and ``vibration_wall``, and each body's lowest
        elastic angular frequency.
    """
    from .continuum_smooth import half_width, hertz_pulse, impact_from_scene, read_series_force

    run = Path(run)
    scene = json.loads((run / "scene.json").read_text())
    result = json.loads((run / "result.json").read_text())
    impact = impact_from_scene(scene)
    energy_in = 0.5 * impact.mass * impact.vn**2
    time, force = read_series_force(run / "series.dat")
    x_disk = np.loadtxt(run / "series.dat", comments="#")[:, 2]
    fine = np.linspace(time[0], time[-1], samples)
    quasi = hertz_pulse(impact)
    pulses = {
        "measured": (fine, np.interp(fine, time, force)),
        "quasi_static": (quasi.time, quasi.force),
    }
    out = {"vibration_disk": result["vibration_disk"], "vibration_wall": result["vibration_wall"]}
    for body, sign in (("disk", 1.0), ("wall", -1.0)):
        modes = body_modes(data, body)
        out[f"omega_{body}"] = float(modes.omega[modes.omega > 1e-6][0])
        if body == "disk":
            rim = modes.x[modes.surface]
            centre = float(rim[np.argmin(rim[:, 1]), 0])
        else:
            centre = float(np.mean(x_disk[force > 0.0]))
        for name, (t, f) in pulses.items():
            a = np.array([half_width(max(value, 1e-12), impact) for value in f])
            dofs, loads = contact_loads(modes, f, a, centre, sign)
            out[f"{name}_{body}"] = float(residual_energy(modes, dofs, loads, t).sum() / energy_in)
    return out


def main(argv: list[str] | None = None) -> int:
    """``python -m analysis.theory.modal_smooth RUN DATA``: the modal shares of
    docs/smooth_baseline.md."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("run", type=Path, help="an impact folder of the smooth study")
    parser.add_argument("data", type=Path, help="the same seed's scene.data")
    args = parser.parse_args(argv)
    for path in (args.run / "series.dat", args.data):
        if not path.exists():
            parser.error(f"{path} does not exist")
    print(json.dumps(shares(args.run, args.data), indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
