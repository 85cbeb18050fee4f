"""LAMMPS against the reference, scene by scene (make validate).

LAMMPS at its default settings (runner.options) runs the scenes of
reference/validate.py, whose reference runs and differences it compares with:
smooth surfaces for the accuracy of the integration, rough ones for the
implementation (the reference's velocity Verlet at the same step) and the
chaotic spread (copies of each scene with the disk's points moved by 1e-9 R).
The rough scenes include the default body's (the area barrier), whose
barrier counts both report.
Here, above runner, because it runs LAMMPS through runner.impact.run_scene;
the reference itself imports nothing of runner.

    python -m bench.validation [--out FOLDER] [--docs]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from builder.assembly import build_scene
from builder.cli import OneLineParser
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground import gate
from ground.checks import OutFolder, require_out_folder
from ground.errors import InputError
from ground.gate import runs_folder
from ground.paths import DOCS
from reference.run import ReferenceOptions, Unstable
from reference.validate import (
    markdown,
    reference_run,
    reference_runs,
    scenes,
    trajectory_difference,
)
from runner.impact import run_scene
from runner.options import DEFAULT_DT, RunOptions

PROG = "python -m bench.validation"


def compare(
    spec: SceneSpec,
    folder: Path,
    options: RunOptions,
    reference: dict,
    reference_folder: Path,
    same_step: bool = False,
) -> dict:
    """LAMMPS's run of ``spec`` in ``folder`` against the reference's result
    and run folder. ``same_step``: the reference is LAMMPS's twin at its
    step; a run whose step the barrier halved (runner.impact.run_scene) is
    compared with the reference's Verlet at the halved step, in a folder
    beside ``reference_folder``."""
    result = run_scene(write_scene(build_scene(spec), folder), options)
    ran = json.loads((folder / "run.json").read_text())["options"]
    if (
        same_step
        and ran["dt"] != json.loads((reference_folder / "run.json").read_text())["options"]["dt"]
    ):
        twin = ReferenceOptions(integrator="verlet", dt=ran["dt"])
        reference_folder = reference_folder.with_name(f"{reference_folder.name}_dt{ran['dt']:g}")
        reference = reference_run(spec, reference_folder, twin)
    row = {
        "e": result["e"],
        "beta": result["beta"],
        "de": result["e"] - reference["e"],
        "dbeta": result["beta"] - reference["beta"],
        "energy_drift": result["energy_drift"],
        "wall_seconds": result["wall_seconds"],
        "steps": result["steps"],
        "dt": ran["dt"],
    }
    # the area barrier's counts (fix area/barrier), LAMMPS's and the reference's
    for key in ("in_barrier_max", "area_ratio_min"):
        if key in result:
            row[key] = result[key]
            row[f"{key}_ref"] = reference.get(key)
    row.update(trajectory_difference(folder, reference_folder))
    return row


def perturbed_spread(
    spec: SceneSpec, folder: Path, options: RunOptions, copies: int = 6, size: float = 1e-9
) -> dict:
    """Spread of e and beta over copies of a scene whose disk points are moved by
    ``size`` R in random directions: how far apart chaos takes trajectories."""
    scene = build_scene(spec)
    values = []
    rng = np.random.default_rng(0)
    for k in range(copies):
        moved = build_scene(spec)
        disk = moved.molecule == 1
        moved.positions = moved.positions.copy()
        moved.positions[disk] += size * rng.standard_normal((disk.sum(), 2))
        moved.info = scene.info
        result = run_scene(write_scene(moved, folder / f"copy{k}"), options)
        values.append((result["e"], result["beta"]))
    values = np.array(values)
    return {
        "e_sd": float(values[:, 0].std(ddof=1)),
        "beta_sd": float(values[:, 1].std(ddof=1)),
        "e_mean": float(values[:, 0].mean()),
        "beta_mean": float(values[:, 1].mean()),
    }


def validate(out: Path, options: RunOptions, n_disk: int = 800, copies: int = 6) -> dict:
    """Both tables of make validate: smooth scenes (accuracy), rough scenes
    (implementation and chaos).

    Parameters
    ----------
    out : pathlib.Path
        Where the runs go (runs/validation); finished reference runs are reused.
    options : RunOptions
        How LAMMPS runs the scenes.
    n_disk : int
        Points in each disk.
    copies : int
        Perturbed copies of each rough scene, for the chaotic spread.

    Returns
    -------
    dict
        ``smooth`` and ``rough``: one row per scene, as ``markdown`` prints them.
    """
    smooth_specs = scenes(n_disk, roughness=0.0)
    # every scene has n_disk points: one step for all (dt "auto" follows the spacing)
    options = options.for_scene(next(iter(smooth_specs.values())))
    smooth_refs = reference_runs(smooth_specs, out / "smooth")
    smooth = {
        name: compare(
            spec,
            out / "smooth" / name / "lammps",
            options,
            smooth_refs[name],
            out / "smooth" / name / "reference",
        )
        for name, spec in smooth_specs.items()
    }
    for name in smooth:
        smooth[name]["reference"] = smooth_refs[name]
    rough_specs = scenes(n_disk, body=True)
    same_step = ReferenceOptions(integrator="verlet", dt=options.dt)
    twins = reference_runs(rough_specs, out / "rough", options=same_step, label="reference_verlet")
    converged = reference_runs(rough_specs, out / "rough")
    rough = {}
    for name, spec in rough_specs.items():
        row = compare(
            spec,
            out / "rough" / name / "lammps",
            options,
            twins[name],
            out / "rough" / name / "reference_verlet",
            same_step=True,
        )
        row["converged_de"] = row["e"] - converged[name]["e"]
        row["converged_dbeta"] = row["beta"] - converged[name]["beta"]
        row.update(perturbed_spread(spec, out / "rough" / name / "perturbed", options, copies))
        rough[name] = row
    return {"smooth": smooth, "rough": rough}


def parser() -> OneLineParser:
    """python -m bench.validation's options."""
    parser = OneLineParser(
        prog=PROG,
        description="LAMMPS against the reference on thirteen scenes (nine of the paper's on "
        "the wall, one of two disks, three of the default body with the area barrier)",
    )
    parser.add_argument(
        "--out",
        type=OutFolder(),
        default=None,
        help="folder for the runs and the table (default: runs/validation)",
    )
    parser.add_argument(
        "--docs",
        action="store_true",
        help="write the table into docs/benchmarks/validation_table.md (make validate does)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        options = RunOptions(dt=DEFAULT_DT)
        out = require_out_folder("--out", args.out or runs_folder() / "validation")
        tables = validate(out, options)
        text = markdown(tables)
        page = DOCS / "benchmarks" / "validation_table.md" if args.docs else out / "table.md"
        if args.docs:  # make validate: the committed table, granted
            gate.grant(page)
        gate.write_text(
            page,
            "# LAMMPS against the reference\n\n"
            f"Generated by `make validate`: LAMMPS at its defaults (velocity Verlet, dt = "
            f"{options.dt:g} R/c) on thirteen scenes of 800-point disks: nine of the paper's "
            "on the wall, random_disk_g45 (two disks colliding) and, rough only, body_random_* "
            "(the default body on the wall: one continuous surface, the physical contact, the "
            "area barrier at J_c 0.5). The reference is "
            "Suzuki's fourth-order composition at dt = 1e-3 R/c; centre, velocity, omega are "
            "the largest "
            "differences during contact of the disk's centre of mass, its velocity and L/I "
            "(units R, c, c/R). The chaotic spread: the standard deviation of e and beta over "
            "six copies of the scene with the disk's points moved by 1e-9 R. "
            "See docs/validation.md.\n\n" + text + "\n",
        )
        print(text)
        print(f"wrote {page}")
    except (InputError, Unstable) as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2 if isinstance(error, InputError) else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
