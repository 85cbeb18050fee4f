"""Steps per second of the default scene: bond styles, 1 vs 2 ranks.

    make bench-impact        (or: python bench/impact_speed.py --repeats 3 [--docs])

Each configuration runs the whole default impact (random lattice, seed 1,
45 degrees, segment contact, the default dt) several times; the table gives medians
of the steps per second inside LAMMPS's run loops and of the wall time of the
whole impact (start of lmp to result).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from bench.common import (
    add_repeats,
    bench_parser,
    loop_seconds,
    markdown_table,
    median,
    write_report,
)
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import PAPER, SceneSpec
from runner.impact import run_scene
from runner.options import RunOptions


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 3, "runs of each configuration")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)

    scene = build_scene(SceneSpec(gamma_deg=45.0, **PAPER))
    atoms = scene.info["n_atoms"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        # the default harmonic/quartic, LAMMPS's class2 (the same springs) and
        # harmonic (no quartic term: not the model, a floor for a bond style)
        for springs in ("harmonic/quartic", "class2", "harmonic"):
            folder = write_scene(scene, Path(tmp) / springs.replace("/", "_"), springs)
            for nprocs in (1, 2):
                rates, walls, steps = [], [], 0
                for _ in range(args.repeats):
                    result = run_scene(folder, RunOptions(springs=springs, nprocs=nprocs))
                    seconds, steps = loop_seconds(folder / "log.lammps")
                    rates.append(steps / seconds)
                    walls.append(result["wall_seconds"])
                rate = median(rates)
                rows.append(
                    [
                        springs,
                        str(nprocs),
                        str(steps),
                        f"{rate:,.0f}",
                        f"{rate * atoms / 1e6:.1f}",
                        f"{median(walls):.2f}",
                    ]
                )
                print(" ".join(rows[-1]), flush=True)
    body = (
        f"Default scene: {atoms} atoms, {scene.info['n_springs']} springs, "
        f"medians of {args.repeats} runs.\n\n"
        + markdown_table(
            ["springs", "ranks", "steps", "steps/s", "Matom-steps/s", "wall s per impact"], rows
        )
    )
    print(body)
    # make bench-impact is exactly the defaults and --docs
    command = (
        "make bench-impact"
        if args.docs and args.repeats == 3
        else f"python bench/impact_speed.py --repeats {args.repeats}"
        + (" --docs" if args.docs else "")
    )
    print(f"wrote {write_report('impact_speed', 'Impact speed', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
