"""One impact: scene -> LAMMPS -> result.json."""

from __future__ import annotations

import json
import math
from pathlib import Path

from analysis.impact.result import analyse_run, write_json_atomically
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.checks import word_problem
from ground.errors import InputError
from ground.launch import LammpsError, lammps_version, mpi_launcher, run_lmp, run_python
from ground.provenance import git_revision

from .options import AUTO, DT, RunOptions, halved_step

RUN_OUTPUTS = (
    "log.lammps",
    "series.dat",
    "energy.dat",
    "dump.lammpstrj",
    "run.json",
    "result.json",
    "barrier.dat",
)
# decks/area_barrier.lmp's angle style stops the run with this when a triangle
# turned over between two steps (potentials/angle_area_barrier.cpp)
BARRIER_CROSSED = "crossed the barrier within one step"
# What the contact says when the step is too long for it
# (potentials/pair_polyline_exp.cpp): a surface segment torn past the
# contact's reach between two checks, or a disk point stepped into the wall.
# At speeds along the wall above about c (grazing angles at 0.1 c) the
# spacing's step no longer resolves the contact; a step the program chose
# ("auto") is then the program's to halve, a step the user gave is not.
STEP_TOO_LONG = ("the run went unstable", "is inside the wall")


def check_folder(folder: Path | str) -> None:
    """A run folder's path must be one word to LAMMPS."""
    folder = Path(folder).resolve()
    if problem := word_problem(str(folder)):
        raise InputError(f"scene: the folder's path {problem}: {folder}")


def scene_data(folder: Path) -> Path:
    """The data file a scene folder's scene.lmp names, or its own scene.data."""
    for line in (folder / "scene.lmp").read_text().splitlines():
        words = line.split()
        if words[:3] == ["variable", "data", "index"] and len(words) > 3:
            return Path(words[3])
    return folder / "scene.data"


def run_scene(
    folder: Path | str,
    options: RunOptions,
    deck_overrides: dict[str, str] | None = None,
    halvings: int = 0,
) -> dict:
    """Run the scene in ``folder`` (scene.data, scene.lmp, scene.json) and analyse it.

    Outputs go into the same folder; result.json is written last and
    atomically, and only if the run finished and every number is finite.
    ``deck_overrides`` sets deck variables that are not run options (the
    benchmarks' early_stop, stop_slack, ...); run.json records them.

    Parameters
    ----------
    folder : pathlib.Path or str
        A scene folder (``builder.lammps_data.write_scene``); no spaces in its path.
    options : RunOptions
        How to run it: time step, integrator, contact, route (lmp or the lammps
        module), MPI ranks, outputs.
    deck_overrides : dict of str to str, optional
        Further ``-var`` settings of decks/impact.lmp.
    halvings : int
        Start at the step halved this many times: a study's worker starts an
        impact again so after a start at the longer step crossed the area
        barrier (runner.cluster.tasks; in-process LAMMPS ends the worker on
        an error). Counts towards ``options.barrier_halvings``.

    Returns
    -------
    dict
        The result (``analysis.impact.result.analyse_run``), as written to result.json.

    Raises
    ------
    ground.errors.InputError
        If the folder or the options are invalid.
    ground.launch.LammpsError
        If LAMMPS stops with an error (its message).
    """
    options.validate()
    folder = Path(folder).resolve()
    check_folder(folder)
    for name in ("scene.lmp", "scene.json"):
        if not (folder / name).is_file():
            raise InputError(
                f"scene: no {name} in {folder} (write one with python -m builder scene)"
            )
    data = scene_data(folder)
    if not data.is_file():
        if ".bodies" in data.parts:  # runner.study.BODIES_FOLDER
            raise InputError(
                f"scene: {data}, its sample's bodies, was a study's scratch, removed when the "
                "study's run ended: run the study again (--retry-failed for a failed impact)"
            )
        raise InputError(f"scene: no data file {data} (write one with python -m builder scene)")
    try:
        scene = json.loads((folder / "scene.json").read_text(encoding="utf-8"))
        if not isinstance(scene, dict) or not isinstance(scene.get("spec"), dict):
            raise ValueError("no scene's spec in it")
    except (OSError, ValueError) as error:
        raise InputError(
            f"scene: {folder / 'scene.json'} is not a scene's record ({error}); "
            "write the folder again with python -m builder scene"
        ) from None
    if scene.get("springs", "class2") != options.springs:
        raise InputError(
            f"springs must match the data file ({scene.get('springs')}), got {options.springs}"
        )
    for name in RUN_OUTPUTS:
        (folder / name).unlink(missing_ok=True)
    automatic = options.dt == AUTO
    options = halved_step(options.for_scene(scene_spec(scene)), halvings)
    options.validate()

    log = folder / "log.lammps"
    while True:
        variables = {"scene": str(folder), "out": str(folder)}
        variables.update(options.deck_variables())
        variables.update(deck_overrides or {})
        try:
            if options.route == "lmp":
                seconds = run_lmp(variables, log, options.nprocs)
            else:
                seconds = run_python(variables, log)
            break
        except LammpsError as error:
            # the barrier's energy diverges as a triangle's area vanishes, so a
            # crossing is a step too long for it, not the body's physics
            if not may_halve(str(error), halvings, options, automatic):
                raise
            halvings += 1
            options = halved_step(options)
            for name in RUN_OUTPUTS:
                (folder / name).unlink(missing_ok=True)

    run = {
        "options": options.as_dict(),
        "dt_halvings": halvings,
        "deck_overrides": deck_overrides or {},
        "wall_seconds": seconds,
        # how the ranks were started: mpirun, IMPACT_MPIRUN's srun, '' for one
        "launcher": " ".join(mpi_launcher(options.nprocs)) if options.route == "lmp" else "",
        "lammps_version": lammps_version(log),
        "git_revision": git_revision(),
    }
    write_json_atomically(run, folder / "run.json")
    result = analyse_run(folder)
    bad = [k for k, v in result.items() if isinstance(v, float) and not math.isfinite(v)]
    if bad:
        raise LammpsError(f"non-finite results ({', '.join(bad)}); no result written")
    write_json_atomically(result, folder / "result.json")
    return result


def may_halve(error: str, halvings: int, options: RunOptions, automatic: bool = False) -> bool:
    """Whether a run that stopped with ``error`` after ``halvings`` halvings
    of the step runs again at half its step (``options``: the step run):
    after a barrier's crossing, and, where the step was the program's
    (``automatic``: dt "auto"), after the contact's step-too-long errors
    (STEP_TOO_LONG)."""
    too_long = BARRIER_CROSSED in error or (
        automatic and any(words in error for words in STEP_TOO_LONG)
    )
    return too_long and halvings < options.barrier_halvings and DT.contains(options.dt / 2)


def scene_spec(scene: dict) -> SceneSpec:
    """The SceneSpec a scene.json records (fields it lacks take their defaults)."""
    known = SceneSpec.__dataclass_fields__
    return SceneSpec(**{k: v for k, v in scene["spec"].items() if k in known})


def run_impact(spec: SceneSpec, folder: Path | str, options: RunOptions) -> dict:
    """Build the scene of ``spec`` into ``folder`` and run it.

    Parameters
    ----------
    spec : SceneSpec
        The scene (``builder.scene.SceneSpec``).
    folder : pathlib.Path or str
        The run folder; created if missing.
    options : RunOptions
        How to run it (``runner.options.RunOptions``).

    Returns
    -------
    dict
        The result, as written to result.json (``run_scene``).
    """
    spec.validate()
    options.validate()
    check_folder(folder)  # before anything is written
    folder = Path(folder)
    write_scene(build_scene(spec), folder, options.springs)
    return run_scene(folder, options)
