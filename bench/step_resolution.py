"""Time against error of the step that follows the spacing, at three resolutions.

    python bench/step_resolution.py [--sizes 400 1600 6400] [--docs]

dt "auto" is 0.008 R/c at 800 disk points, scaled with the spacing
(runner.options.RunOptions.for_scene). This checks that the scaled step keeps
the 800-point disk's accuracy at other resolutions: for each size, the random
disk of seed 1 on its wall of twice its points, the continuum reading
(roughness_length 0.048 R, the contact following the spacing), at 45 and 80.4
degrees, with the step at 2, 1.5, 1 and 0.5 times dt auto.

- **smooth** surfaces (roughness 0), where e and beta of an impact converge:
  the error of e and beta against the same LAMMPS run at dt auto / 8 (a
  self-convergence reference: velocity Verlet is second order, so its error
  at dt / 8 is 1/64 of the error at dt);
- **rough** surfaces, which are chaotic: the energy drift (change of the
  total energy over the initial kinetic energy) and whether the run survives.

The table gives LAMMPS's loop seconds (one rank) beside each; docs/benchmarks/
step_resolution.md with --docs.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from bench.common import bench_parser, distinct, loop_seconds, markdown_table, refuse, write_report
from builder.scene import N_DISK, PAPER, SceneSpec
from ground.errors import InputError
from ground.launch import LammpsError
from runner.impact import run_impact
from runner.options import RunOptions

FACTORS = (2.0, 1.5, 1.0, 0.5)
REFERENCE_FACTOR = 0.125
GAMMAS = (45.0, 80.4)
ROUGHNESS_LENGTH = 0.048


def spec(n_disk: int, gamma: float, rough: bool) -> SceneSpec:
    return SceneSpec(
        n_disk=n_disk,
        gamma_deg=gamma,
        seed=1,
        roughness=0.03 if rough else 0.0,
        roughness_length=ROUGHNESS_LENGTH if rough else 0.0,
        **{k: v for k, v in PAPER.items() if k != "roughness_length"},
    )


def one_run(scene: SceneSpec, factor: float, folder: Path) -> dict:
    """e, beta, drift and loop seconds of one run at ``factor`` times dt auto."""
    options = RunOptions(route="lmp")
    dt = options.for_scene(scene).dt * factor
    try:
        result = run_impact(scene, folder, RunOptions(dt=dt))
    except LammpsError as error:
        return {"dt": dt, "failed": str(error).splitlines()[0][:60]}
    seconds, steps = loop_seconds(folder / "log.lammps")
    return {
        "dt": dt,
        "e": result["e"],
        "beta": result["beta"],
        "drift": result["energy_drift"],
        "seconds": seconds,
        "steps": steps,
    }


def measure(sizes: list[int]) -> list[list[str]]:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n_disk in sizes:
            for gamma in GAMMAS:
                smooth = spec(n_disk, gamma, rough=False)
                reference = one_run(smooth, REFERENCE_FACTOR, Path(tmp) / "reference")
                for factor in FACTORS:
                    s = one_run(smooth, factor, Path(tmp) / "smooth")
                    r = one_run(spec(n_disk, gamma, rough=True), factor, Path(tmp) / "rough")
                    error = s.get("failed", "-")
                    if "e" in s and "e" in reference:
                        worst = max(abs(s[k] - reference[k]) for k in ("e", "beta"))
                        error = f"{worst:.1e}"
                    rows.append(
                        [
                            str(n_disk),
                            f"{gamma:g}",
                            f"{factor:g}",
                            f"{s['dt']:.4g}",
                            error,
                            f"{s['seconds']:.2f}" if "seconds" in s else "-",
                            f"{r['drift']:+.1e}" if "drift" in r else r["failed"],
                            f"{r['seconds']:.2f}" if "seconds" in r else "-",
                            str(r.get("steps", "-")),
                        ]
                    )
                    print(" | ".join(rows[-1]), flush=True)
    return rows


HEADER = [
    "disk points",
    "gamma, degrees",
    "step / dt auto",
    "dt, R/c",
    "smooth: max error of e, beta",
    "smooth: LAMMPS s",
    "rough: energy drift",
    "rough: LAMMPS s",
    "rough: steps",
]


def parser():
    """The benchmark's options."""
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--sizes",
        nargs="+",
        type=N_DISK,
        default=[400, 1600, 6400],
        help=f"disk points, each {N_DISK.describe()} (default: 400 1600 6400)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        sizes = distinct("--sizes", args.sizes)
    except InputError as error:
        return refuse(__file__, error)
    rows = measure(sizes)
    body = (
        "dt auto = 0.008 R/c sqrt(800 / N). Smooth: the largest difference of e and beta from "
        f"the same run at dt auto x {REFERENCE_FACTOR:g}; rough (roughness 0.03 R, correlation "
        f"length {ROUGHNESS_LENGTH:g} R): the energy drift over the initial kinetic energy. "
        "One rank, seed 1, v_n 0.1 c, the wall of twice the disk's points.\n\n"
        + markdown_table(HEADER, rows)
    )
    command = "python bench/step_resolution.py --sizes " + " ".join(map(str, sizes))
    page = write_report(
        "step_resolution",
        "The step that follows the spacing, at three resolutions",
        command,
        body,
        args.docs,
    )
    print(f"wrote {page}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
