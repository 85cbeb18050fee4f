"""The reference's side of LAMMPS against the reference (make validate,
bench/validation.py, which runs LAMMPS): the scenes, the reference's runs of
them, the trajectories' differences and the tables.

Impacts on rough surfaces are chaotic: perturbations of 1e-16 grow to 1e-9
over a grazing impact, and a change of time step moves e by up to 0.02 there,
for any integrator. A single rough impact therefore has no e to compare to
1e-3; smooth surfaces (roughness 0) do, and converge. So the accuracy of
LAMMPS's integration is measured on smooth versions of the scenes, and on the
rough ones LAMMPS is compared with the reference's velocity Verlet at the
same step (the same algorithm on independently written forces), and the
chaotic spread is measured by perturbing the initial state.

The reference runs Suzuki's fourth-order composition at dt = 1e-3 R/c; its
runs are kept under the output folder and reused while their options match.

Besides the paper's scenes, the rough table has the default body on the wall
(builder.scene.BODY: one continuous surface per seed, the physical contact
and the area barrier, ``body_random_g*``), whose barrier the reference
implements on its own (reference.forces.area_barrier).
"""

from __future__ import annotations

import json
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict
from pathlib import Path

import numpy as np

from analysis.impact.restitution import contact_window
from analysis.impact.series import read_series
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.materials import square_ratio_for_poisson
from builder.scene import PAPER, SceneSpec

from .run import ReferenceOptions, run_reference

LATTICES = {"random": {}, "triangular": {}, "square": {"k2_over_k1": square_ratio_for_poisson(0.3)}}
ANGLES = (5.7, 45.0, 80.4)  # near-normal, middle, grazing
REFERENCE = ReferenceOptions(integrator="suzuki", dt=1e-3)


# Two random disks colliding (builder/binary.py) at the middle angle.
BINARY = {"random_disk_g45": {"lattice": "random", "gamma_deg": 45.0, "target": "disk"}}
# The default body (builder.scene.BODY, the scene with no options) at the three angles.
BODY_LATTICES = ("random",)


def scenes(
    n_disk: int = 800, roughness: float = 0.03, two_disks: bool = True, body: bool = False
) -> dict[str, SceneSpec]:
    """The nine scenes of the disks on the wall, and (``two_disks``) one of two disks:
    the paper's scene (builder.scene.PAPER; a binary scene's default), as validated;
    with ``body`` also the default body's scenes (``body_scenes``)."""
    on_the_wall = {
        f"{lattice}_g{gamma:g}": SceneSpec(
            lattice=lattice, gamma_deg=gamma, n_disk=n_disk, roughness=roughness, **extra, **PAPER
        )
        for lattice, extra in LATTICES.items()
        for gamma in ANGLES
    }
    binary = {
        name: SceneSpec(n_disk=n_disk, roughness=roughness, **fields)
        for name, fields in BINARY.items()
    }
    return {
        **on_the_wall,
        **(binary if two_disks else {}),
        **(body_scenes(n_disk, roughness) if body else {}),
    }


def body_scenes(n_disk: int = 800, roughness: float = 0.03) -> dict[str, SceneSpec]:
    """The default body on the wall (builder.scene.BODY: a continuous surface
    of correlation length 0.2 R, the physical contact, the area barrier at
    J_c 0.5), random disk, at ``ANGLES``: ``body_random_g5.7`` ..."""
    return {
        f"body_{lattice}_g{gamma:g}": SceneSpec(
            lattice=lattice, gamma_deg=gamma, n_disk=n_disk, roughness=roughness
        )
        for lattice in BODY_LATTICES
        for gamma in ANGLES
    }


def reference_run(spec: SceneSpec, folder: Path, options: ReferenceOptions = REFERENCE) -> dict:
    """The reference result for ``spec``, reusing a finished run with the same options.

    Parameters
    ----------
    spec : SceneSpec
        The scene.
    folder : pathlib.Path
        Its run folder.
    options : ReferenceOptions
        How the reference integrates it.

    Returns
    -------
    dict
        The reference's result.json.
    """
    folder = Path(folder)
    done = folder / "result.json"
    if done.exists():
        run = json.loads((folder / "run.json").read_text())
        scene = json.loads((folder / "scene.json").read_text())
        if (
            run["options"]["dt"] == options.dt
            and run["options"]["integrator"] == options.integrator
            and run["options"].get("barrier", True) == options.barrier
            and scene["spec"] == asdict(spec)
        ):
            return json.loads(done.read_text())
    write_scene(build_scene(spec), folder)
    return run_reference(folder, options)


def _reference_job(job):
    return reference_run(*job)


def reference_runs(
    specs: dict[str, SceneSpec],
    out: Path,
    workers: int = 2,
    options: ReferenceOptions = REFERENCE,
    label: str = "reference",
) -> dict[str, dict]:
    jobs = [(spec, out / name / label, options) for name, spec in specs.items()]
    with ProcessPoolExecutor(workers) as pool:
        return dict(zip(specs, pool.map(_reference_job, jobs)))


def trajectory_difference(lammps: Path, reference: Path) -> dict[str, float]:
    """Largest differences during contact of the disk's centre, velocity and spin.

    Parameters
    ----------
    lammps : pathlib.Path
        A LAMMPS run folder (series.dat).
    reference : pathlib.Path
        The reference's run folder of the same scene.

    Returns
    -------
    dict
        ``position``, ``velocity`` and ``omega``: the largest differences over
        the reference's contact window, LAMMPS's rows against the reference
        interpolated to their times.
    """
    ours, theirs = read_series(lammps / "series.dat"), read_series(reference / "series.dat")
    start, end = contact_window(theirs)
    during = (ours["time"] >= start) & (ours["time"] <= end)
    t = ours["time"][during]

    def worst(*columns):
        return max(
            float(np.abs(np.interp(t, theirs["time"], theirs[c]) - ours[c][during]).max())
            for c in columns
        )

    spin = lambda s: s["Lz"] / s["Izz"]  # noqa: E731
    return {
        "position": worst("x", "y"),
        "velocity": worst("vx", "vy"),
        "omega": float(
            np.abs(np.interp(t, theirs["time"], spin(theirs)) - spin(ours)[during]).max()
        ),
    }


def markdown(tables: dict) -> str:
    smooth = [
        "| scene | e_ref | beta_ref | e - e_ref | beta - beta_ref | centre | velocity | omega |",
        "|" + "---|" * 8,
    ]
    for name, row in tables["smooth"].items():
        ref = row["reference"]
        smooth.append(
            f"| {name} | {ref['e']:.5f} | {ref['beta']:+.5f} | {row['de']:+.1e} "
            f"| {row['dbeta']:+.1e} | {row['position']:.1e} | {row['velocity']:.1e} "
            f"| {row['omega']:.1e} |"
        )
    rough = [
        "| scene | e | beta | vs reference Verlet, same step: e, beta | vs converged "
        "reference: e, beta | chaotic spread: sd e, sd beta | energy drift |",
        "|" + "---|" * 7,
    ]
    for name, row in tables["rough"].items():
        rough.append(
            f"| {name} | {row['e']:.4f} | {row['beta']:+.4f} | {row['de']:+.0e}, "
            f"{row['dbeta']:+.0e} | {row['converged_de']:+.1e}, {row['converged_dbeta']:+.1e} "
            f"| {row['e_sd']:.1e}, {row['beta_sd']:.1e} | {row['energy_drift']:+.1e} |"
        )
    barrier = [
        "| scene | most triangles in the barrier at once: LAMMPS, reference | smallest J: "
        "LAMMPS, reference |",
        "|" + "---|" * 3,
    ]
    for name, row in tables["rough"].items():
        if "in_barrier_max" in row:
            barrier.append(
                f"| {name} | {row['in_barrier_max']}, {row['in_barrier_max_ref']} "
                f"| {row['area_ratio_min']:.6f}, {row['area_ratio_min_ref']:.6f} |"
            )
    return (
        "## Smooth surfaces: accuracy\n\n"
        + "\n".join(smooth)
        + "\n\n## Rough surfaces: implementation and chaos\n\n"
        + "\n".join(rough)
        + (
            "\n\n## The default body's area barrier (same-step Verlet runs)\n\n"
            + "\n".join(barrier)
            if len(barrier) > 2
            else ""
        )
    )
