"""Does the wall's width change grazing impacts? The 8 R wall against a wider one.

    python bench/wall_width.py [--seeds 12] [--widths 8 16] [--angles 63.52 73.9 80.5]
                               [--workers 2] [--docs]

At grazing angles the disk slides several R during contact, and on MODEL.md's
8 R wall its centre can pass an end of the wall, where the wall is held
fixed, before the contact is over. Each (seed, angle) runs on every wall
width (random lattice, the study's settings; the wall keeps the disk's number
density, so a wider wall is a different random sample of the same material).
The table gives, per width and angle, the mean and standard error of e and
beta over the seeds, the median contact time, and how many impacts had the
disk's centre within 1 R of a fixed side during contact (side_clearance < 1,
the disk's radius), or past it (< 0).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from bench.common import SEED_COUNT, bench_parser, distinct, markdown_table, refuse, write_report
from builder.errors import BuildError, InputError
from builder.scene import ANGLE, WALL_WIDTH, SceneSpec
from runner.clusters import WORKERS
from runner.impact import run_impact
from runner.lammps_run import LammpsError
from runner.options import RunOptions


def one_impact(args: tuple[float, float, int, str]) -> dict:
    width, gamma, seed, folder = args
    spec = SceneSpec(seed=seed, gamma_deg=gamma, wall_width=width)
    try:
        result = run_impact(spec, folder, RunOptions())
    except (BuildError, LammpsError) as error:
        return {"width": width, "gamma": gamma, "seed": seed, "error": str(error)}
    return {
        "width": width,
        "gamma": gamma,
        "seed": seed,
        **{k: result[k] for k in ("e", "beta", "contact_time", "side_clearance")},
    }


def mean_se(values: list[float]) -> str:
    a = np.asarray(values)
    return f"{a.mean():.3f} +- {a.std(ddof=1) / np.sqrt(len(a)):.3f}" if len(a) > 1 else "-"


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--seeds",
        type=SEED_COUNT,
        default=12,
        help=f"seeds 1 to N, {SEED_COUNT.describe()} (default: 12)",
    )
    parser.add_argument(
        "--widths",
        type=WALL_WIDTH,
        nargs="+",
        default=[8.0, 16.0],
        help=f"wall widths, each {WALL_WIDTH.describe()} (default: 8 16)",
    )
    parser.add_argument(
        "--angles",
        type=ANGLE,
        nargs="+",
        default=[63.52, 73.9, 80.5],
        help=f"incidence angles, each {ANGLE.describe()} (default: 63.52 73.9 80.5)",
    )
    parser.add_argument(
        "--workers",
        type=WORKERS,
        default=2,
        help=f"worker processes, {WORKERS.describe()} (default: 2)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--widths", args.widths)
        distinct("--angles", args.angles)
        for width in args.widths:  # the scenes' own checks, before any impact
            for gamma in args.angles:
                SceneSpec(gamma_deg=gamma, wall_width=width).validate()
    except InputError as error:
        return refuse(__file__, error)
    # an impact that fails (a LAMMPS error, or a wall the builder refuses) is counted, not fatal

    with tempfile.TemporaryDirectory() as tmp:
        tasks = [
            (w, g, s, str(Path(tmp) / f"w{w:g}_g{g:g}_s{s}"))
            for s in range(1, args.seeds + 1)
            for g in args.angles
            for w in args.widths
        ]
        with ProcessPoolExecutor(args.workers) as pool:
            results = list(pool.map(one_impact, tasks))

    rows = []
    for gamma in args.angles:
        for width in args.widths:
            runs = [r for r in results if r["gamma"] == gamma and r["width"] == width]
            good = [r for r in runs if "error" not in r]
            clearance = np.array([r["side_clearance"] for r in good])
            rows.append(
                [
                    f"{gamma:g}",
                    f"{width:g}",
                    str(len(good)),
                    str(len(runs) - len(good)),
                    mean_se([r["e"] for r in good]),
                    mean_se([r["beta"] for r in good]),
                    f"{np.median([r['contact_time'] for r in good]):.1f}",
                    str(int((clearance < 1.0).sum())),
                    str(int((clearance < 0.0).sum())),
                ]
            )
            print(" | ".join(rows[-1]), flush=True)
    errors = sorted({r["error"][:100] for r in results if "error" in r})
    body = (
        f"Random lattice, seeds 1 to {args.seeds}, the study's settings; a wall of each width "
        "at the disk's number density.\n\n"
        + markdown_table(
            [
                "gamma",
                "wall width, R",
                "impacts",
                "failed",
                "e",
                "beta",
                "median contact time, R/c",
                "centre within 1 R of a side",
                "centre past a side",
            ],
            rows,
        )
        + ("\n\nFailures: " + "; ".join(errors) if errors else "")
    )
    print(body)
    command = (
        f"python bench/wall_width.py --seeds {args.seeds} --widths "
        + " ".join(f"{w:g}" for w in args.widths)
        + " --angles "
        + " ".join(f"{g:g}" for g in args.angles)
        + (f" --workers {args.workers}" if args.workers != 2 else "")
        + (" --docs" if args.docs else "")
    )
    title = "Wall width at grazing angles"
    print(f"wrote {write_report('wall_width', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
