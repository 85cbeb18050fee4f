"""Stability stress tests: where runs fail, what the user sees, long runs.

    python bench/stability.py [--docs]        (make bench-study: with --docs)

1. Time-step sweeps, velocity Verlet and rRESPA (the contact alone on the
   inner level at dt / RESPA_NRESPA; dt its outer step), until the run fails: rough
   random and square disks at the most grazing angle of the study (80.5
   degrees) at 0.1 c, and at 45 degrees at 0.1, 0.2, 0.3 and 0.5 c.
2. The speeds at which the contact is resolved at the default integrator and
   step: normal speeds 0.05 to 0.5 c at four angles, three seeds each; the
   range of --vn (builder/cli.py) is taken from it.
3. A long run after the impact (to t = 400 R/c, the conservative "gradient"
   rule): the total energy's drift, and whether the disk's springs are intact.
Writes runs/bench/stability.md, or with --docs docs/benchmarks/stability.md.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

from analysis.impact.series import read_energies
from bench.common import bench_parser, markdown_table, write_report
from builder.assembly import build_scene
from builder.lammps_data import read_data, write_scene
from builder.materials import square_ratio_for_poisson
from builder.scene import MAX_TANGENTIAL_SPEED, PAPER, SceneSpec
from ground.launch import LammpsError
from runner.impact import run_scene
from runner.options import DEFAULT_DT, RESPA_NRESPA, RunOptions

STEPS = (1e-3, 2e-3, 4e-3, 6e-3, 8e-3, 1.2e-2, 1.6e-2, 2.4e-2, 3.2e-2)
CASES = [
    ("random", 80.5, 0.1),
    ("square", 80.5, 0.1),
    ("random", 45.0, 0.1),
    ("random", 45.0, 0.2),
    ("random", 45.0, 0.3),
    ("random", 45.0, 0.5),
]


def spec_for(lattice: str, gamma: float, vn: float) -> SceneSpec:
    extra = {"k2_over_k1": square_ratio_for_poisson(0.3)} if lattice == "square" else {}
    return SceneSpec(lattice=lattice, gamma_deg=gamma, vn=vn, **extra, **PAPER)


def sweep(tmp: Path) -> list[list[str]]:
    rows = []
    for lattice, gamma, vn in CASES:
        scene = build_scene(spec_for(lattice, gamma, vn))
        for label, make in (
            ("verlet", lambda dt: RunOptions(dt=dt)),
            (
                f"respa {RESPA_NRESPA} (contact at dt/{RESPA_NRESPA})",
                lambda dt: RunOptions(dt=dt, integrator="respa", nrespa=RESPA_NRESPA),
            ),
        ):
            last_good, failure = None, None
            for dt in STEPS:
                folder = write_scene(
                    scene, tmp / f"{lattice}_{gamma}_{vn}_{label.replace(' ', '')}_{dt}"
                )
                try:
                    result = run_scene(folder, make(dt))
                    last_good = (dt, result)
                except LammpsError as error:
                    failure = (dt, str(error))
                    assert not (folder / "result.json").exists()
                    break
            good = (
                (
                    f"{last_good[0]:g} (energy error {abs(last_good[1]['energy_drift']):.0e}, "
                    f"e = {last_good[1]['e']:.3f})"
                )
                if last_good
                else "none"
            )
            fail = f"{failure[0]:g}: {failure[1][:90]}" if failure else f"none up to {STEPS[-1]:g}"
            rows.append([f"{lattice} {gamma:g} deg {vn:g} c", label, good, fail])
            print(" | ".join(rows[-1]), flush=True)
    return rows


SPEEDS = (0.05, 0.1, 0.2, 0.3, 0.4, 0.5)
SPEED_ANGLES = (5.7106, 45.0, 63.52, 80.5)
SPEED_SEEDS = (1, 2, 3)


def speed_limits(tmp: Path) -> list[list[str]]:
    """Which (angle, v_n) the default run resolves: every seed finishes with
    its drift below the guard."""
    rows = []
    options = RunOptions()
    for gamma in SPEED_ANGLES:
        for vn in SPEEDS:
            drifts, failures = [], []
            for seed in SPEED_SEEDS:
                spec = SceneSpec(gamma_deg=gamma, vn=vn, seed=seed, **PAPER)
                folder = write_scene(build_scene(spec), tmp / f"speed_{gamma}_{vn}_{seed}")
                try:
                    drifts.append(abs(run_scene(folder, options)["energy_drift"]))
                except LammpsError as error:
                    failures.append(str(error).replace("ERROR on proc 0: ", "")[:70])
            flagged = sum(d > options.max_drift for d in drifts)
            rows.append(
                [
                    f"{gamma:g}",
                    f"{vn:g}",
                    f"{vn * np.tan(np.radians(gamma)):.2f}",
                    f"{len(drifts)} of {len(SPEED_SEEDS)}",
                    f"{max(drifts):.1e}" if drifts else "-",
                    str(flagged),
                    failures[0] if failures else "",
                ]
            )
            print(" | ".join(rows[-1]), flush=True)
    return rows


def spring_strain(folder: Path) -> float:
    """Largest relative stretch of a disk spring in the last dump frame."""
    system = read_data(folder / "scene.data")
    lines = (folder / "dump.lammpstrj").read_text().splitlines()
    start = max(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    n = len(system.x)
    frame = np.array([line.split() for line in lines[start + 1 : start + 1 + n]], float)
    x = np.empty((n, 2))
    x[frame[:, 0].astype(int) - 1] = frame[:, 4:6]  # id mol type mass x y ...
    disk = system.molecule[system.bonds[:, 0]] == 1
    d = x[system.bonds[disk, 1]] - x[system.bonds[disk, 0]]
    return float(np.max(np.abs(np.linalg.norm(d, axis=1) / system.r0[disk] - 1.0)))


def long_run(tmp: Path, dt: float) -> list[str]:
    folder = write_scene(build_scene(SceneSpec(gamma_deg=80.5, **PAPER)), tmp / "long")
    # early_stop no: the deck runs on to tmax after the disk has left
    # one frame per check: the strain is read from the last
    options = RunOptions(dt=dt, rule="gradient", tmax=400.0)
    options.dump_every = options.check_steps
    run_scene(folder, options, {"early_stop": "no"})
    energies = read_energies(folder / "energy.dat")
    total = [
        sum(row[k] for k in ("ke_disk", "pe_disk", "ke_wall", "pe_wall", "pe_contact"))
        for row in energies
    ]
    drift = (total[-1] - total[0]) / energies[0]["ke_disk"]
    return [f"{dt:g}", "400", f"{drift:+.1e}", f"{spring_strain(folder):.3f}"]


PARTS = ("steps", "speeds", "long")


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--parts",
        nargs="+",
        choices=PARTS,
        default=list(PARTS),
        help="which tests to run (default: all); each writes its own section, and a "
        "page of only some is named after them (stability_speeds.md, ...)",
    )
    return parser


SPEED_HEADER = [
    "gamma, deg",
    "v_n, c",
    "v_n tan gamma, c",
    "finished",
    "largest |drift|",
    "drift above --max-drift",
    "a failure",
]


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    parts = [p for p in PARTS if p in args.parts]
    sections = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        if "steps" in parts:
            sections.append(
                "## Time steps until failure\n\n"
                + markdown_table(
                    ["scene", "integrator", "largest time step that ran", "first failure"],
                    sweep(tmp),
                )
            )
        if "speeds" in parts:
            seeds = ", ".join(map(str, SPEED_SEEDS))
            sections.append(
                "## Speeds at which the contact is resolved\n\n"
                f"Random disk on the default scene at the default run settings (dt "
                f"{DEFAULT_DT:g}), seeds {seeds}. `--vn` takes (0, 0.3] and a run whose "
                f"speed along the wall, v_n tan gamma, exceeds {MAX_TANGENTIAL_SPEED:g} c is "
                "warned of "
                "(builder/scene.py's VN and MAX_TANGENTIAL_SPEED): every run below both "
                "finished.\n\n" + markdown_table(SPEED_HEADER, speed_limits(tmp))
            )
        if "long" in parts:
            sections.append(
                "## A long run after the impact\n\nRandom disk at 80.5 degrees and 0.1 c, "
                "conservative rule, run on to t = 400 R/c after it has left the wall.\n\n"
                + markdown_table(
                    [
                        "dt",
                        "t end",
                        "total energy change / initial kinetic energy",
                        "largest strain of a disk spring at the end",
                    ],
                    [long_run(tmp, dt) for dt in (DEFAULT_DT,)],
                )
            )
    body = "\n\n".join(sections)
    print(body)
    name = "stability" if parts == list(PARTS) else "stability_" + "_".join(parts)
    command = (
        "python bench/stability.py"
        + ("" if parts == list(PARTS) else " --parts " + " ".join(parts))
        + (" --docs" if args.docs else "")
    )
    path = write_report(name, "Stability stress tests", command, body, args.docs)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
