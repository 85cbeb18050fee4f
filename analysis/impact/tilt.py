"""The tilt of the wall's surface under the disk, from a run's dump.

The seed paper's authors explained e > 1 at oblique incidence by the wall's
local deformation: the disk presses a dent, the surface under it tilts, and
the contact's normal is no longer the wall's, so part of the tangential
(friction) force acts along the wall's normal. This module measures both
from a run with a dump (``RunOptions.dump_every``):

- the tilt: at every frame, the wall surface points within ``HALF_WIDTH`` of
  the disk centre's x, their displacement from the first frame fitted by a
  line against their first-frame x (numpy.polyfit); its slope's angle is the
  tilt the deformation adds to the rough surface's own (positive: the
  surface rises in +x, against a disk moving in +x);
- what the tilt does to the approach: the disk comes in at v_n down and v_t
  along the wall; against a surface tilted by theta (rising ahead of it),
  its speed along the tilted normal is v_n cos(theta) + v_t sin(theta). So
  the tilt adds tan(gamma) tan(theta) of the normal approach speed, which a
  rebound along the tilted normal returns as wall-normal speed: e measured
  against the wall's normal can exceed 1 where that share is comparable to
  1 - e. theta is taken as the contact-force-weighted mean tilt (weights:
  series.dat's fy).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.integrate import trapezoid

from builder.scene import WALL_SURFACE

from .dump import DISK_MOLECULE, open_run
from .series import read_series

HALF_WIDTH = 0.5  # R: the wall under the disk's contact


@dataclass
class Tilt:
    time: np.ndarray  # the dump's frames, R / c
    tilt: np.ndarray  # radians
    points: np.ndarray  # how many wall surface points are under the disk, per frame


def surface_tilt(folder: Path | str, half_width: float = HALF_WIDTH) -> Tilt:
    """The deformation's tilt of the wall's surface under the disk, per frame."""
    universe = open_run(folder)
    folder = Path(folder)
    dt = float(json.loads((folder / "run.json").read_text())["options"]["dt"])
    order = np.argsort(universe.atoms.ids)
    disk = universe.atoms.resids[order] == DISK_MOLECULE
    surface = universe.atoms.types.astype(int)[order] == WALL_SURFACE
    universe.trajectory[0]
    # positions relative to the wall surface's mean: the box's shift drops out
    start = universe.atoms.positions[order, :2].astype(float)
    start = start - start[surface].mean(axis=0)
    times, tilts, counts = [], [], []
    for ts in universe.trajectory:
        now = universe.atoms.positions[order, :2].astype(float)
        shift = now[surface].mean(axis=0)
        now = now - shift
        centre = now[disk].mean(axis=0)
        under = surface & (np.abs(start[:, 0] - centre[0]) < half_width)
        if under.sum() >= 3:
            slope = np.polyfit(start[under, 0], now[under, 1] - start[under, 1], 1)[0]
            tilts.append(float(np.arctan(slope)))
        else:
            tilts.append(np.nan)
        counts.append(int(under.sum()))
        times.append(ts.time * dt)  # MDAnalysis: the dump's step times a dt of 1
    return Tilt(np.array(times), np.array(tilts), np.array(counts))


def tilt_effect(folder: Path | str, tilt: Tilt, gamma_deg: float) -> dict:
    """The force-weighted mean tilt during contact and the share of the normal
    approach speed it adds, tan(gamma) tan(mean tilt)."""
    series = read_series(Path(folder) / "series.dat")
    t = np.asarray(series["time"], float)
    fy = np.asarray(series["fy"], float)
    known = np.isfinite(tilt.tilt)
    theta = np.interp(t, tilt.time[known], tilt.tilt[known]) if known.any() else np.zeros_like(t)
    mean = float(trapezoid(fy * theta, t) / trapezoid(fy, t))
    return {
        "normal_impulse": float(trapezoid(fy, t)),
        "mean_tilt_deg": float(np.degrees(mean)),
        "approach_share": float(np.tan(np.radians(gamma_deg)) * np.tan(mean)),
    }


def tilted_e(result: dict, theta: float) -> float:
    """e against the normal (-sin theta, cos theta) of a surface tilted by
    theta, from a result's velocities before and after (vx_in, vy_in, ...)."""
    normal = np.array([-np.sin(theta), np.cos(theta)])
    v_in = np.array([result["vx_in"], result["vy_in"]])
    v_out = np.array([result["vx_out"], result["vy_out"]])
    return float(-(v_out @ normal) / (v_in @ normal))
