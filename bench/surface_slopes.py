"""The rms slope of the built surfaces, per reading and resolution.

    python bench/surface_slopes.py --n-disk 800 3200 [--seeds 8] [--docs]

docs/model.md, "The model as the resolution grows", quotes its table
(docs/benchmarks/surface_slopes.md). No LAMMPS: the builder's bodies only.
"""

from __future__ import annotations

import numpy as np

from bench.common import bench_parser, distinct, page_folder, refuse, write_report
from builder.bodies import Body
from builder.sample import build_bodies
from builder.scene import N_DISK, PAPER, SceneSpec
from ground.checks import Range
from ground.errors import InputError

SEEDS = Range(1, 1000, integer=True)

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


def parser():
    p = bench_parser(__file__, __doc__, out="surface_slopes.md")
    p.add_argument(
        "--n-disk",
        type=N_DISK,
        nargs="+",
        default=[800],
        help=f"disk points, each {N_DISK.describe()} (default: 800)",
    )
    p.add_argument(
        "--seeds", type=SEEDS, default=8, help=f"seeds 1..N, {SEEDS.describe()} (default: 8)"
    )
    return p


def table(n_disks: list[int], seeds: int) -> str:
    lines = ["| reading | disk points | disk rms slope | wall rms slope |", "|---|---|---|---|"]
    for label, options in READINGS.items():
        for n in n_disks:
            disk, wall = [], []
            for seed in range(1, seeds + 1):
                bodies = build_bodies(SceneSpec(n_disk=n, seed=seed, **{**PAPER, **options}))
                disk.append(disk_slopes(bodies[0]))
                wall.append(wall_slopes(bodies[1]))
            rms = [np.sqrt(np.mean(np.concatenate(x) ** 2)) for x in (disk, wall)]
            lines.append(f"| {label} | {n} | {rms[0]:.3f} | {rms[1]:.3f} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--n-disk", args.n_disk)
    except InputError as error:
        return refuse(__file__, error)
    body = table(args.n_disk, args.seeds)
    print(body)
    command = "python bench/surface_slopes.py --n-disk " + " ".join(map(str, args.n_disk))
    write_report(
        "surface_slopes",
        "The rms slope of the built surfaces",
        command
        + (f" --seeds {args.seeds}" if args.seeds != 8 else "")
        + (" --docs" if args.docs else ""),
        "The step between neighbouring surface points over their distance along the "
        "surface: radius against angle on the disk, height against x on the wall's top "
        f"face (its held corners left out), rms over seeds 1 to {args.seeds}.\n\n" + body,
        folder=page_folder(args),
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
