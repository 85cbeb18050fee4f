"""The demo: a random-lattice disk on a random-lattice wall at a few angles."""

from __future__ import annotations

from pathlib import Path

from builder.scene import SceneSpec

from .impact import run_impact
from .options import RunOptions

# cot(gamma) from 10 down to 0.17: 5.7 to 80.4 degrees (MODEL.md section 4).
DEMO_ANGLES = (5.7, 26.6, 55.0, 80.4)


def run_demo(out: Path | str, seeds: int, options: RunOptions) -> list[dict]:
    results = []
    for seed in range(1, seeds + 1):
        for gamma in DEMO_ANGLES:
            spec = SceneSpec(lattice="random", seed=seed, gamma_deg=gamma)
            folder = Path(out) / f"random_s{seed}_g{gamma:g}"
            results.append(run_impact(spec, folder, options))
    return results
