"""Is the surface roughness still docs/model.md's, now that every seed builds?

    python bench/roughness.py [--seeds 100] [--first-seed 1] [--write [--docs]]

Builds the disk of every lattice of the study (runner/study/__init__.py LATTICES) and
the wall of every reading (800, 1,600 points, the disk's number density;
sides or sides and bottom held) for each seed, as the study does (the streams
of builder.sample.sample_seeds), and reports per body and reading:

- how many seeds built, and how many needed a steep surface segment flipped
  into the triangulation (builder/network.py ``constrain``; before it, the
  builder refused these seeds);
- the standard deviation of the applied displacements along the normal
  (the disk's radii less 1, the wall's top row less 0, its fixed corners
  left out), pooled over the seeds, against delta = 0.03 R, with its
  standard error delta / sqrt(2 N);
- the largest |displacement| / delta, and the steps between the two ends of
  the flipped segments in units of their std sqrt(2) delta: these are the
  tails a redraw of the offending displacements would have cut.

``--write`` puts the table in runs/bench/roughness.md, with ``--docs`` in
docs/benchmarks/roughness.md. 100 seeds take about 10 minutes on one core.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from bench.common import SEED_COUNT, bench_parser, markdown_table, refuse, write_report
from builder import bodies
from builder.sample import sample_seeds
from builder.scene import SEED
from ground.errors import BuildError, InputError
from runner.study import LATTICES

DELTA = 0.03
DISK_POINTS = 800
WALL_READINGS = [
    (800, "sides"),
    (800, "sides+bottom"),
    (1600, "sides"),
    (1600, "sides+bottom"),
    (None, "sides"),
    (None, "sides+bottom"),
]
WIDTH, HEIGHT = 8.0, 2.0


def wall_points(n_wall: int | None) -> int:
    """Points of the wall; None is the disk's number density (SceneSpec.wall_points)."""
    if n_wall is not None:
        return n_wall
    return int(round(DISK_POINTS / np.pi * WIDTH * HEIGHT))


def displacements(body: bodies.Body, kind: str) -> np.ndarray:
    """The roughness applied to a body's surface row, along its outward normal."""
    row = body.points[body.surface]
    if kind == "disk":
        return np.linalg.norm(row, axis=1) - 1.0
    return row[1:-1, 1]  # the wall's top corners are not displaced


def segment_steps(body: bodies.Body, kind: str) -> list[float]:
    """Normal step between the ends of each segment that needed the fix, in sqrt(2) delta."""
    heights = np.linalg.norm(body.points, axis=1) - 1.0 if kind == "disk" else body.points[:, 1]
    return [abs(heights[a] - heights[b]) / (np.sqrt(2.0) * DELTA) for a, b in body.steep]


def survey(seeds: range) -> list[dict]:
    """One record per body kind and reading, accumulated over the seeds."""
    cases = [("disk", name, kw) for name, kw in LATTICES.items()]
    cases += [
        (
            "wall",
            f"{wall_points(n)} points ({'dens.' if n is None else n}), {fixed}",
            {"n": wall_points(n), "fixed": fixed},
        )
        for n, fixed in WALL_READINGS
    ]
    records = [
        {
            "kind": kind,
            "reading": label,
            "kw": kw,
            "built": 0,
            "failed": [],
            "fixed": [],
            "steps": [],
            "u": [],
        }
        for kind, label, kw in cases
    ]
    for seed in seeds:
        for record in records:
            kw = record["kw"]
            # Fresh streams for every body, as builder.scene does: scipy's
            # Poisson-disk sampler spawns from the generator's SeedSequence, so
            # a second body drawn from the same SeedSequence object would differ.
            disk_seed, wall_seed = sample_seeds(seed)
            rng = np.random.default_rng(disk_seed if record["kind"] == "disk" else wall_seed)
            try:
                if record["kind"] == "disk":
                    body = bodies.make_disk(
                        rng, kw["lattice"], DISK_POINTS, DELTA, kw.get("k2_over_k1", 3.0 / 7.0)
                    )
                else:
                    body = bodies.make_wall(rng, kw["n"], WIDTH, HEIGHT, DELTA, kw["fixed"])
            except BuildError:
                record["failed"].append(seed)
                continue
            record["built"] += 1
            if len(body.steep):
                record["fixed"].append(seed)
                record["steps"] += segment_steps(body, record["kind"])
            record["u"].append(displacements(body, record["kind"]))
    return records


def table(records: list[dict]) -> str:
    header = [
        "body",
        "reading",
        "built",
        "needed the fix (seeds)",
        "N displacements",
        "std / delta",
        "(std - delta) / SE",
        "max abs / delta",
        "step across the fixed segments / (sqrt2 delta)",
    ]
    rows = []
    for r in records:
        u = np.concatenate(r["u"])
        std = float(u.std())
        se = DELTA / np.sqrt(2.0 * len(u))
        fixed = f"{len(r['fixed'])} ({', '.join(map(str, r['fixed']))})" if r["fixed"] else "0"
        steps = ", ".join(f"{s:.2f}" for s in r["steps"]) or "-"
        rows.append(
            [
                r["kind"],
                r["reading"],
                f"{r['built']}",
                fixed,
                f"{len(u)}",
                f"{std / DELTA:.4f}",
                f"{(std - DELTA) / se:+.2f}",
                f"{np.abs(u).max() / DELTA:.2f}",
                steps,
            ]
        )
    return markdown_table(header, rows)


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--seeds",
        type=SEED_COUNT,
        default=100,
        help=f"number of seeds, {SEED_COUNT.describe()} (default: 100)",
    )
    parser.add_argument(
        "--first-seed",
        type=SEED,
        default=1,
        help=f"first seed, {SEED.describe()} (default: 1)",
    )
    parser.add_argument(
        "--write",
        action="store_true",
        help="write the page: runs/bench/roughness.md, with --docs the committed one",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        if args.docs and not args.write:
            raise InputError("--docs applies with --write only (without it nothing is written)")
        if args.first_seed + args.seeds - 1 > SEED.high:
            raise InputError(
                f"--first-seed + --seeds - 1 must be at most {SEED.high}, the largest seed"
            )
    except InputError as error:
        return refuse(__file__, error)
    seeds = range(args.first_seed, args.first_seed + args.seeds)
    start = time.time()
    records = survey(seeds)
    failed = sum(len(r["failed"]) for r in records)
    body = (
        f"Seeds {seeds.start} to {seeds.stop - 1}; delta = {DELTA} R; disks of {DISK_POINTS} "
        f"points, walls {WIDTH:g} R x {HEIGHT:g} R. Bodies that failed to build: {failed}. "
        f"std is pooled over all seeds' displacements, SE = delta / sqrt(2 N).\n\n" + table(records)
    )
    print(body)
    print(f"\n({time.time() - start:.0f} s)")
    if args.write:
        command = (
            "python bench/roughness.py"
            + (f" --seeds {args.seeds}" if args.seeds != 100 else "")
            + (f" --first-seed {args.first_seed}" if args.first_seed != 1 else "")
            + " --write"
            + (" --docs" if args.docs else "")
        )
        path = write_report(
            "roughness", "Surface roughness and the steep-segment fix", command, body, args.docs
        )
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
