"""Why a run stops with "a disk point is inside the wall": the geometry just before.

    python bench/inside_wall.py --n-wall 800 --wall-ka same-c --wall-fixed sides --seed 1 \
        --gamma 61.6996

Reruns one impact with a dump every 10 steps and, for the last frames before
the stop, reports what could have put a disk point inside the wall:

- wall surface points inside the disk's outline (the polygon of its surface
  points): only the disk's points feel the contact, so nothing stops a wall
  point from passing between two of them;
- folds of the wall's surface (a segment running backwards in x), where the
  vertical-ray test of the contact style could misread a point in a dip;
- how far the wall sags under the disk and how near the disk is to a held side.

It prints its diagnosis and writes no page (--docs is refused).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np
from matplotlib.path import Path as Polygon

from analysis.dump import open_run
from bench.common import bench_parser, refuse
from builder.checks import Range
from builder.cli import wall_points, wall_spring
from builder.errors import InputError
from builder.lammps_data import write_scene
from builder.scene import (
    ANGLE,
    DISK_INTERIOR,
    DISK_SURFACE,
    N_WALL,
    SEED,
    WALL_FIXED,
    WALL_FIXED_CHOICES,
    WALL_KA,
    SceneSpec,
    build_scene,
)
from runner.impact import run_scene
from runner.lammps_run import LammpsError
from runner.options import DT, SPRINGS
from runner.study import PRESETS

FRAMES = Range(1, 1_000, integer=True)


def diagnose(step: int, x: np.ndarray, types: np.ndarray, first: int, last: int) -> dict:
    """What a frame shows about the disk and the wall's surface (atoms in tag
    order; MDAnalysis shifts positions by the box's corner, so heights and
    sides are taken from the wall's held points, which do not move)."""
    row = x[first - 1 : last]
    disk = (types == DISK_SURFACE) | (types == DISK_INTERIOR)
    surface = np.flatnonzero(types == DISK_SURFACE)
    centre = x[disk].mean(axis=0)
    order = np.argsort(np.arctan2(*(x[surface] - centre).T[::-1]))
    inside = np.flatnonzero(Polygon(x[surface][order]).contains_points(row)) + first
    folds = np.flatnonzero(np.diff(row[:, 0]) <= 0.0) + first
    held = x[types == WALL_FIXED]
    return {
        "step": step,
        "wall points inside the disk": inside.tolist(),
        "folds (segment starts)": folds.tolist(),
        "deepest sag of the wall's surface, R": round(float(held[:, 1].max() - row[:, 1].min()), 3),
        "disk centre to the nearer held side, R": round(
            float(min(centre[0] - held[:, 0].min(), held[:, 0].max() - centre[0])), 3
        ),
    }


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--n-wall",
        type=wall_points,
        default=SceneSpec.n_wall,
        help=f"points in the wall, {N_WALL.describe()}, or 'density' (default: {SceneSpec.n_wall})",
    )
    parser.add_argument(
        "--wall-ka",
        type=wall_spring,
        default=SceneSpec.wall_ka,
        help=f"the wall's spring constant, {WALL_KA.describe()}, or 'same-c' "
        f"(default: {SceneSpec.wall_ka:g})",
    )
    parser.add_argument(
        "--wall-fixed",
        choices=WALL_FIXED_CHOICES,
        default=SceneSpec.wall_fixed,
        help=f"which wall points are held (default: {SceneSpec.wall_fixed})",
    )
    parser.add_argument(
        "--seed", type=SEED, default=1, help=f"sample seed, {SEED.describe()} (default: 1)"
    )
    parser.add_argument(
        "--gamma",
        type=ANGLE,
        default=61.6996,
        help=f"incidence angle, {ANGLE.describe()} (default: 61.6996)",
    )
    # the settings of docs/benchmarks/scene_readings.md, whose failures this explains
    parser.add_argument(
        "--dt", type=DT, default=0.004, help=f"time step, {DT.describe()} (default: 0.004)"
    )
    parser.add_argument(
        "--springs", choices=SPRINGS, default="class2", help="bond style (default: class2)"
    )
    parser.add_argument(
        "--frames",
        type=FRAMES,
        default=4,
        help=f"frames before the stop to report, {FRAMES.describe()} (default: 4)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    if args.docs:
        return refuse(__file__, InputError("--docs: this script writes no page, it prints"))
    spec = SceneSpec(
        seed=args.seed,
        gamma_deg=args.gamma,
        n_wall=args.n_wall,
        wall_ka=args.wall_ka,
        wall_fixed=args.wall_fixed,
    )
    scene = build_scene(spec)
    options = replace(
        PRESETS["paper"].options, dt=args.dt, every=25, check=100, springs=args.springs
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_scene(scene, Path(tmp) / "scene", options.springs)
        run = dict(vars(options), dump_every=10, route="lmp")
        try:
            run_scene(folder, type(options)(**run))
            print("the impact finished: nothing to diagnose")
            return 0
        except LammpsError as error:
            print(f"stopped: {error}")
        universe = open_run(folder)
        order = np.argsort(universe.atoms.ids)
        types = universe.atoms.types.astype(int)[order]
        first, last = scene.info["wall_row_tags"]
        for ts in universe.trajectory[-args.frames :]:
            x = universe.atoms.positions[order, :2].astype(float)
            print(diagnose(ts.data.get("step", ts.frame), x, types, first, last))
    return 0


if __name__ == "__main__":
    sys.exit(main())
