"""An independent check of c: a longitudinal pulse travelling along a random bar.

A Gaussian velocity pulse, long against the bar's width, splits into two
halves that travel at the bar speed sqrt(E_bar / rho); its centre of kinetic
energy is tracked in time. Units: spacing d, ka and m are 1.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from builder.strips import StripSpec, write_strip
from ground.launch import open_lammps


def pulse_speed(
    folder: Path | str,
    seed: int = 1,
    length: float = 300.0,
    width: float = 10.0,
    sigma: float = 15.0,
    dt: float = 0.05,
) -> float:
    """Speed of the right-going half of the pulse, in units of d sqrt(ka/m)."""
    spec = StripSpec("random", seed=seed, length=length, width=width)
    folder = write_strip(spec, folder)
    start = -length / 3.0
    lmp = open_lammps()
    for command in [
        "units lj",
        "dimension 2",
        "boundary s s p",
        "atom_style bond",
        "special_bonds lj/coul 1.0 1.0 1.0",
        "bond_style class2",
        f"read_data {folder}/strip.data",
        "pair_style zero 1.0",
        "pair_coeff * *",
        "comm_modify cutoff 4.0",
        "fix move all nve",
        f"timestep {dt}",
        f"variable pulse atom 1e-4*exp(-0.5*((x-({start}))/{sigma})^2)",
        "velocity all set v_pulse 0.0 0.0",
        "run 0",
    ]:
        lmp.command(command)
    times, centres = [], []
    travel = length / 2.0  # the right half stays clear of the far end
    for k in range(1, 41):
        lmp.command(f"run {round(travel / 40 / dt)}")
        x = lmp.numpy.extract_atom("x")[:, 0]
        vx = lmp.numpy.extract_atom("v")[:, 0]
        time = k * travel / 40
        # the right half is near start + c t; the left half, reflected at the
        # bar's end, trails it by length / 3: split the two halfway
        right = x > start + time - length / 6.0
        weight = vx[right] ** 2
        times.append(time)
        centres.append(np.sum(weight * x[right]) / np.sum(weight))
    lmp.close()
    times, centres = np.array(times), np.array(centres)
    late = times > 4 * sigma  # after the two halves have separated
    return float(np.polyfit(times[late], centres[late], 1)[0])
