"""The rms slope of the built surfaces, per reading and resolution (docs/model.md,
"The model as the resolution grows").

    python -m bench.surface_slopes --n-disk 800 3200

The slope is the step between neighbouring surface points over their
distance along the surface: radius against angle on the disk, height
against x on the wall's top face (its held corners left out), rms over
seeds 1 to 8.
"""

from __future__ import annotations

import argparse

import numpy as np

from builder.bodies import Body
from builder.sample import build_bodies
from builder.scene import SceneSpec

READINGS = {
    "paper per-point": {},
    "sampled L = 0.048 R": {"roughness_length": 0.048},
    "profile L = 0.2 R": {"roughness_length": 0.2, "roughness_profile": "continuous"},
}


def disk_slopes(disk: Body) -> np.ndarray:
    row = disk.points[disk.surface]
    angle = np.arctan2(row[:, 1], row[:, 0])
    order = np.argsort(angle)
    angle, radius = angle[order], np.hypot(row[order, 0], row[order, 1])
    return np.diff(np.append(radius, radius[0])) / np.diff(np.append(angle, angle[0] + 2 * np.pi))


def wall_slopes(wall: Body) -> np.ndarray:
    row = wall.points[wall.surface[1:-1]]
    order = np.argsort(row[:, 0])
    return np.diff(row[order, 1]) / np.diff(row[order, 0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-disk", type=int, nargs="+", default=[800])
    parser.add_argument("--seeds", type=int, default=8)
    args = parser.parse_args()
    print("| reading | disk points | disk rms slope | wall rms slope |\n|---|---|---|---|")
    for label, options in READINGS.items():
        for n in args.n_disk:
            disk, wall = [], []
            for seed in range(1, args.seeds + 1):
                bodies = build_bodies(SceneSpec(n_disk=n, seed=seed, **options))
                disk.append(disk_slopes(bodies[0]))
                wall.append(wall_slopes(bodies[1]))
            rms = [np.sqrt(np.mean(np.concatenate(x) ** 2)) for x in (disk, wall)]
            print(f"| {label} | {n} | {rms[0]:.3f} | {rms[1]:.3f} |")


if __name__ == "__main__":
    main()
