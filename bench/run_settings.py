"""What the run's settings cost: stopping early, output, neighbour lists.

    python bench/run_settings.py [--repeats 3] [--docs]

The default scene (random lattice, 45 degrees) at the default time step, each
setting changed alone, interleaved and repeated; medians of the wall time
of the whole impact. Rough impacts are chaotic, so any change of summation
order (neighbour lists) moves e and beta a little: they are shown too.
"""

from __future__ import annotations

import argparse
import json
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

DEFAULT = RunOptions()
SETTINGS = {
    "defaults": {},
    "no early stop (run to t = 60)": {"early_stop": "no", "tmax": "60"},
    "series every step": {"every": "1"},
    "series every 100 steps": {"every": "100"},
    "checks every 1000 steps": {"check": "1000"},
    "skin 0.25 spacing": {"skin_factor": "0.25"},
    "skin 1 spacing": {"skin_factor": "1.0"},
    "neighbor bin": {"neighbor_style": "bin"},
}


def run(folder: Path, changes: dict[str, str]) -> dict:
    changes = dict(changes)
    skin_factor = changes.pop("skin_factor", None)
    if skin_factor:
        spacing = json.loads((folder / "scene.json").read_text())["wall_spacing"]
        changes["skin"] = repr(float(skin_factor) * spacing)
    result = run_scene(folder, DEFAULT, changes)
    loop, steps = loop_seconds(folder / "log.lammps")
    return {
        "seconds": result["wall_seconds"],
        "loop": loop,
        "steps": steps,
        "e": result["e"],
        "beta": result["beta"],
    }


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 3, "runs of each setting")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    scene = build_scene(SceneSpec(gamma_deg=45.0, **PAPER))
    times = {name: [] for name in SETTINGS}
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_scene(scene, Path(tmp) / "scene")
        for _ in range(args.repeats):
            for name, changes in SETTINGS.items():
                times[name].append(run(folder, changes))
    base = median([t["seconds"] for t in times["defaults"]])
    rows = []
    for name, runs in times.items():
        seconds = median([t["seconds"] for t in runs])
        rows.append(
            [
                name,
                f"{runs[0]['steps']}",
                f"{seconds:.2f}",
                f"{(seconds / base - 1) * 100:+.0f}",
                f"{runs[0]['e']:.5f}",
                f"{runs[0]['beta']:+.5f}",
            ]
        )
        print(" | ".join(rows[-1]), flush=True)
    body = (
        f"Default scene (random lattice, 45 degrees, dt = {DEFAULT.dt:g}), medians of "
        f"{args.repeats} interleaved runs.\n\n"
        + markdown_table(["setting", "steps", "s per impact", "% vs defaults", "e", "beta"], rows)
    )
    print(body)
    command = (
        "python bench/run_settings.py"
        + (f" --repeats {args.repeats}" if args.repeats != 3 else "")
        + (" --docs" if args.docs else "")
    )
    path = write_report("run_settings", "Run settings", command, body, args.docs)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
