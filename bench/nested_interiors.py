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
    .venv/bin/python bench/nested_interiors.py table
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from scipy import stats

from ground.paths import runs_folder

RUNS = runs_folder() / "nested_interiors"
ANGLES = (5.7106, 33.9998, 69.2325)
LEVELS = (800, 1600)
READINGS = {
    "profile": ["--roughness-length", "0.2", "--roughness-profile", "continuous"],
    "smooth": ["--roughness", "0"],
}
COMMON = ["--contact-scaling", "physical", "--vn", "0.1"]


def folder(reading: str, interior: str, n: int, seed: int, gamma: float) -> Path:
    """Where one impact's run goes; the base level has one folder for both."""
    interior = "drawn" if n < 1600 else interior
    return RUNS / reading / interior / f"n{n}" / f"s{seed}" / f"g{gamma:.4f}"


def plan(seeds: int, smooth_angles: tuple[float, ...]) -> list[tuple]:
    """Every impact, the profile's first (angle by angle), then the smooth disk's."""
    todo = []
    for reading, angles in (("profile", ANGLES), ("smooth", smooth_angles)):
        for gamma in angles:
            for seed in range(1, seeds + 1):  # seed by seed: a partial run pairs
                for interior in ("nested", "drawn"):
                    for n in LEVELS:
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


def pitman_morgan(a: np.ndarray, b: np.ndarray) -> float:
    """Two-sided p of equal variances of paired samples: the correlation of
    their sums and differences is zero exactly when the variances are equal."""
    return float(stats.pearsonr(a + b, a - b).pvalue)


def table(seeds: int) -> None:
    print(
        "| reading | angle | seeds | sd e(800) | sd e(1600), drawn | nested | "
        "sd of e(1600) - e(800), drawn | nested | variance ratio | F test p | "
        "Pitman-Morgan p |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for reading in READINGS:
        for gamma in ANGLES:
            base = e_of(reading, "drawn", 800, seeds, gamma)
            drawn = e_of(reading, "drawn", 1600, seeds, gamma)
            grown = e_of(reading, "nested", 1600, seeds, gamma)
            ok = ~(np.isnan(base) | np.isnan(drawn) | np.isnan(grown))
            k = int(ok.sum())
            if k < 3:
                continue
            d_drawn, d_grown = (drawn - base)[ok], (grown - base)[ok]
            ratio = np.var(d_drawn, ddof=1) / np.var(d_grown, ddof=1)
            f_p = 2 * min(stats.f.sf(ratio, k - 1, k - 1), stats.f.cdf(ratio, k - 1, k - 1))
            sd = lambda x: np.std(x, ddof=1)  # noqa: E731
            print(
                f"| {reading} | {gamma:.2f} | {k} | {sd(base[ok]):.4f} | {sd(drawn[ok]):.4f} | "
                f"{sd(grown[ok]):.4f} | {sd(d_drawn):.4f} | {sd(d_grown):.4f} | {ratio:.2f} | "
                f"{f_p:.2f} | {pitman_morgan(d_drawn, d_grown):.2f} |"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument("what", choices=("run", "table"))
    parser.add_argument("--seeds", type=int, default=16)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--smooth-angles", type=float, nargs="*", default=[ANGLES[0]])
    args = parser.parse_args()
    if args.what == "table":
        table(args.seeds)
        return
    todo = plan(args.seeds, tuple(args.smooth_angles))
    with ThreadPoolExecutor(args.jobs) as pool:
        for _ in pool.map(lambda job: run_one(*job), todo):
            pass


if __name__ == "__main__":
    main()
