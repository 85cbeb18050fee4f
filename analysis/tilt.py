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
- the impulses: the disk's contact force (series.dat's fx, fy) split along
  the tilted surface's normal and tangent, N and T; the wall-normal impulse
  is the integral of N cos(tilt) plus the integral of T sin(tilt), the
  second being what the tilt turns from the tangential force.
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
    points: np.ndarray  # wall surface points under the disk at each frame


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


def impulses(folder: Path | str, tilt: Tilt) -> dict:
    """The wall-normal impulse on the disk and the part the tilt turns from T."""
    series = read_series(Path(folder) / "series.dat")
    t = np.asarray(series["time"], float)
    fx, fy = np.asarray(series["fx"], float), np.asarray(series["fy"], float)
    known = np.isfinite(tilt.tilt)
    theta = np.interp(t, tilt.time[known], tilt.tilt[known]) if known.any() else np.zeros_like(t)
    normal = -fx * np.sin(theta) + fy * np.cos(theta)
    tangential = fx * np.cos(theta) + fy * np.sin(theta)
    total = float(trapezoid(fy, t))
    turned = float(trapezoid(tangential * np.sin(theta), t))
    return {
        "normal_impulse": total,
        "from_normal_force": float(trapezoid(normal * np.cos(theta), t)),
        "turned_from_tangential": turned,
        "turned_share": turned / total if total else float("nan"),
        "largest_tilt_deg": float(np.degrees(np.nanmax(np.abs(tilt.tilt)))),
    }
