"""Nested interiors against interiors drawn anew: the seed-to-seed sd of e(N) - e(N/2).

Issue 46's multilevel estimate pairs the levels by seed. With the continuous
profile the rough surface is one function per seed at every N; the random
interiors (the disk's and the wall's Poisson samples) are still drawn anew at
every N unless --interior nested grows each level's sample from the coarser
one's (builder/nested.py). This runs e at a few angles for seeds 1..k at 800
and 1,600 points both ways (resumable: an impact whose result.json exists is
not run again) and prints, per reading and angle, the sd of the levels and of
the paired differences, their variance ratio with the F test's two-sided p
(15 and 15 degrees of freedom for 16 seeds) and the Pitman-Morgan test's,
which allows for the two sets of differences sharing each seed's 800-point e
(nested 800 is drawn 800, byte for byte in its bodies).

    nice -n 10 .venv/bin/python bench/nested_interiors.py run --jobs 2
    nice -n 10 .venv/bin/python bench/nested_interiors.py run --jobs 2 --levels 1600 3200 \
        --angles 5.7106 --smooth-angles
    .venv/bin/python bench/nested_interiors.py table --docs
    nice -n 10 .venv/bin/python bench/nested_interiors.py density --seeds 6 --docs

(--docs writes the table into docs/benchmarks/nested_interiors_<what>.md.)
"""

from __future__ import annotations

import argparse
import io
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from contextlib import redirect_stdout
from pathlib import Path

import numpy as np
from scipy import stats
from scipy.spatial import Delaunay, cKDTree

from bench.common import DOCS, SEED_COUNT, bench_parser
from builder import bodies
from builder.network import unique_edges
from ground.checks import Range
from ground.paths import runs_folder

RUNS = runs_folder() / "nested_interiors"
ANGLES = (5.7106, 33.9998, 69.2325)
READINGS = {
    "profile": ["--roughness-length", "0.2", "--roughness-profile", "continuous"],
    "smooth": ["--roughness", "0"],
}
READS = ("drawn", "nested")
JOBS = Range(1, 64, integer=True)
ANGLE = Range(0.0, 90.0, low_open=True, high_open=True, unit="degrees")
LEVEL = Range(800, 51_200, integer=True)
COMMON = ["--contact-scaling", "physical", "--vn", "0.1"]


def folder(reading: str, interior: str, n: int, seed: int, gamma: float) -> Path:
    """Where one impact's run goes; the base level has one folder for both."""
    interior = "drawn" if n < 1600 else interior
    return RUNS / reading / interior / f"n{n}" / f"s{seed}" / f"g{gamma:.4f}"


def plan(seeds: int, readings: dict[str, tuple], levels: tuple[int, ...]) -> list[tuple]:
    """Every impact: reading by reading, angle by angle, seed by seed (so that
    a partial run pairs)."""
    todo = []
    for reading, angles in readings.items():
        for gamma in angles:
            for seed in range(1, seeds + 1):
                for interior in READS:
                    for n in levels:
                        todo.append((reading, interior, n, seed, gamma))
    return list(dict.fromkeys(todo, None))


def run_one(reading: str, interior: str, n: int, seed: int, gamma: float) -> None:
    out = folder(reading, interior, n, seed, gamma)
    if (out / "result.json").exists():
        return
    command = [str(Path(sys.executable).parent / "oblique-impact"), "impact", "--n-disk", str(n)]
    command += ["--seed", str(seed), "--gamma", str(gamma), "--interior", interior]
    command += READINGS[reading] + COMMON + ["--out", str(out)]
    subprocess.run(command, check=True, capture_output=True)


def e_of(reading: str, interior: str, n: int, seeds: int, gamma: float) -> np.ndarray:
    values = []
    for seed in range(1, seeds + 1):
        path = folder(reading, interior, n, seed, gamma) / "result.json"
        values.append(json.loads(path.read_text())["e"] if path.exists() else np.nan)
    return np.array(values)


def points_of(reading: str, interior: str, n: int, seeds: int, gamma: float) -> np.ndarray:
    """The disk's and the wall's points as built, per seed that ran."""
    counts = []
    for seed in range(1, seeds + 1):
        path = folder(reading, interior, n, seed, gamma) / "result.json"
        if path.exists():
            result = json.loads(path.read_text())
            counts.append((result["n_disk_points"], result["n_wall_points"]))
    return np.array(counts).reshape(-1, 2)


def pitman_morgan(a: np.ndarray, b: np.ndarray) -> float:
    """Two-sided p of equal variances of paired samples: the correlation of
    their sums and differences is zero exactly when the variances are equal."""
    return float(stats.pearsonr(a + b, a - b).pvalue)


def table(seeds: int) -> None:
    print(
        "| reading | angle | N | seeds | sd e(N/2), drawn | nested | sd e(N), drawn | nested | "
        "sd of e(N) - e(N/2), drawn | nested | variance ratio | F test p | Pitman-Morgan p | "
        "mean e(N) - e(N/2), drawn | nested | correlation of e(N/2) and e(N), drawn | nested | "
        "mean e(N), nested - drawn | disk / wall points at N, drawn | nested |"
    )
    print("|---" * 20 + "|")
    for reading in READINGS:
        for gamma in ANGLES:
            for n in (1600, 3200, 6400):
                e = {(i, m): e_of(reading, i, m, seeds, gamma) for i in READS for m in (n // 2, n)}
                ok = ~np.any(np.isnan(np.array(list(e.values()))), axis=0)
                k = int(ok.sum())
                if k < 3:
                    continue
                e = {key: value[ok] for key, value in e.items()}
                d_drawn = e["drawn", n] - e["drawn", n // 2]
                d_grown = e["nested", n] - e["nested", n // 2]
                ratio = np.var(d_drawn, ddof=1) / np.var(d_grown, ddof=1)
                f_p = 2 * min(stats.f.sf(ratio, k - 1, k - 1), stats.f.cdf(ratio, k - 1, k - 1))
                sd = [np.std(x, ddof=1) for x in e.values()]  # drawn N/2, N; nested N/2, N
                counts = [points_of(reading, i, n, seeds, gamma).mean(axis=0) for i in READS]
                r = [stats.pearsonr(e[i, n // 2], e[i, n]).statistic for i in READS]
                shift = e["nested", n] - e["drawn", n]
                print(
                    f"| {reading} | {gamma:.2f} | {n} | {k} | {sd[0]:.4f} | {sd[2]:.4f} | "
                    f"{sd[1]:.4f} | {sd[3]:.4f} | {np.std(d_drawn, ddof=1):.4f} | "
                    f"{np.std(d_grown, ddof=1):.4f} | {ratio:.2f} | {f_p:.2f} | "
                    f"{pitman_morgan(d_drawn, d_grown):.2f} | {np.mean(d_drawn):+.4f} | "
                    f"{np.mean(d_grown):+.4f} | {r[0]:.2f} | {r[1]:.2f} | {np.mean(shift):+.4f} +- "
                    f"{np.std(shift, ddof=1) / np.sqrt(k):.4f} | "
                    f"{counts[0][0]:.0f} / {counts[0][1]:.0f} | "
                    f"{counts[1][0]:.0f} / {counts[1][1]:.0f} |"
                )


def sample_statistics(points: np.ndarray, radius: float) -> list[float]:
    """Points per radius squared, mean nearest-neighbour distance and the
    Delaunay edges' mean and sd (in radii), in the inner square |x|, |y| < 0.8."""
    inner = np.all(np.abs(points) < 0.8, axis=1)
    distance, _ = cKDTree(points).query(points[inner], k=2)
    edges = unique_edges(Delaunay(points).simplices)
    edges = edges[np.all(np.abs(points[edges].mean(axis=1)) < 0.8, axis=1)]
    length = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1) / radius
    density = inner.sum() / 1.6**2 * radius**2
    return [density, distance[:, 1].mean() / radius, length.mean(), length.std()]


def density(seeds: int) -> None:
    """A plain Poisson sample of the n-point disk's density in [-1, 1]^2
    against one grown from a sample of half its density, seeds 1..k."""
    box = ([-1.0, -1.0], [1.0, 1.0])
    print(
        "| points per disk | sample | points per radius^2 | mean nearest neighbour (radii) "
        "| Delaunay edge mean | edge sd |"
    )
    print("|---|---|---|---|---|---|")
    for n in (1600, 3200):
        spacing = bodies.triangular_spacing(n / np.pi)
        radius = float(np.sqrt(bodies.POISSON_FILL * np.sqrt(3.0) * spacing**2 / 2.0))
        rows: dict[str, list] = {"plain": [], "grown": []}
        for seed in range(1, seeds + 1):
            rows["plain"].append(
                sample_statistics(
                    bodies.poisson_points(np.random.default_rng([seed, 1]), spacing, *box), radius
                )
            )
            coarse = bodies.poisson_points(np.random.default_rng([seed, 2]), spacing * 2**0.5, *box)
            grown = bodies.poisson_points(np.random.default_rng([seed, 3]), spacing, *box, coarse)
            rows["grown"].append(sample_statistics(grown, radius))
        for name, values in rows.items():
            mean = np.mean(values, axis=0)
            error = np.std(values, axis=0, ddof=1) / np.sqrt(len(values))
            cells = " | ".join(f"{m:.4f} +- {e:.4f}" for m, e in zip(mean, error))
            print(f"| {n} | {name} | {cells} |")


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument("what", choices=("run", "table", "density"), help="what to do")
    parser.add_argument(
        "--seeds", type=SEED_COUNT, default=16, help=f"seeds 1..k, {SEED_COUNT.describe()}"
    )
    parser.add_argument("--jobs", type=JOBS, default=1, help=f"impacts at once, {JOBS.describe()}")
    parser.add_argument(
        "--angles", type=ANGLE, nargs="*", default=list(ANGLES), help="the profile's angles"
    )
    parser.add_argument(
        "--smooth-angles", type=ANGLE, nargs="*", default=[ANGLES[0]], help="the smooth disk's"
    )
    parser.add_argument(
        "--levels", type=LEVEL, nargs="*", default=[800, 1600], help=f"N, {LEVEL.describe()}"
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    if args.what == "run":
        readings = {"profile": tuple(args.angles), "smooth": tuple(args.smooth_angles)}
        todo = plan(args.seeds, readings, tuple(args.levels))
        with ThreadPoolExecutor(args.jobs) as pool:
            for _ in pool.map(lambda job: run_one(*job), todo):
                pass
        return 0
    output = io.StringIO()
    with redirect_stdout(output):
        (table if args.what == "table" else density)(args.seeds)
    print(output.getvalue(), end="")
    if args.docs:  # the page's tables, as docs/benchmarks/nested_interiors.md quotes them
        (DOCS / f"nested_interiors_{args.what}.md").write_text(output.getvalue())
    return 0


if __name__ == "__main__":
    sys.exit(main())
