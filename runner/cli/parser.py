"""Command line: python -m runner {impact,run,study,page,tilt} --help

One parser with a subcommand each; what a study command does is runner/cli/study.py's,
where its tables and page go runner/study/outputs.py's.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from builder.cli import (
    OneLineParser,
    add_scene_arguments,
    spec_from_args,
    validate_spec,
)
from builder.scene import (
    speed_warning,
)
from ground.checks import InPath, OutFolder, require_out_folder
from ground.errors import BuildError, InputError, clipped, os_error_line
from ground.gate import environment_paths, gate
from ground.launch import LammpsError, mpi_launcher, require_lmp

from ..stopping import Stopped, stop_on_signals
from ..study import runs_folder
from ..study.file import StudyFile
from ..study.outputs import remake_page, shown
from ..wall_tilt import add_tilt_arguments, wall_tilt
from .run_args import (
    add_run_arguments,
    note_if_halved,
    options_from_args,
    unstable_hint,
    warn_if_inaccurate,
)
from .study import add_study_arguments, run_study_command, study_argument
from .study_args import EnvironmentFault

# What each command's --help shows (the rest: --help-all), by dest.
COMMON = {
    "impact": ("lattice", "seed", "gamma_deg", "vn", "roughness", "n_disk", "wall_width")
    + ("dt", "nprocs", "dump_every", "out"),
    "run": ("dt", "integrator", "nprocs", "dump_every", "tmax"),
    "study": ("samples", "angles", "lattices", "name", "docs", "retry_failed")
    + ("cluster", "workers"),
}


def program() -> str:
    """The name the user typed: the console script, or python -m runner."""
    return "oblique-impact" if Path(sys.argv[0]).name == "oblique-impact" else "python -m runner"


def parser() -> OneLineParser:
    """python -m runner's options."""
    parser = OneLineParser(prog=program(), description="Run oblique impacts with LAMMPS.")
    commands = parser.add_subparsers(dest="command", required=True)

    what = "build a scene, run one impact, print its result"
    impact = commands.add_parser("impact", help=what, description=f"{what[0].upper()}{what[1:]}.")
    add_scene_arguments(impact)
    add_run_arguments(impact)
    impact.add_argument(
        "--out",
        type=OutFolder(),
        default=None,
        help="run folder (default: runs/<lattice>_s<seed>_g<gamma>)",
    )

    what = "run an existing scene folder (python -m builder scene)"
    run = commands.add_parser("run", help=what, description=f"{what[0].upper()}{what[1:]}.")
    run.add_argument(
        "scene",
        type=InPath("folder", ("scene.data", "scene.lmp", "scene.json")),
        help="folder with scene.data, scene.lmp and scene.json",
    )
    add_run_arguments(run)

    what = "the study: sweep, tables, fits, figures (resumable)"
    study = commands.add_parser("study", help=what, description=f"{what[0].upper()}{what[1:]}.")
    add_study_arguments(study)

    tilt = commands.add_parser(
        "tilt", help="the wall's tilt under the disk, from dumps of a grazing study's impacts"
    )
    add_tilt_arguments(tilt)
    for name, command in (("impact", impact), ("run", run), ("study", study)):
        command.show_common(COMMON[name])

    page = commands.add_parser(
        "page", help="a study's page in docs/ again from its committed tables, without its runs"
    )
    page.add_argument(
        "preset",
        metavar="STUDY",
        nargs="?",
        type=study_argument,
        help="a study file with a page (its tables in docs/studies/<page>/)",
    )
    page.add_argument(
        "--all",
        action="store_true",
        help="every study of studies/ whose tables are committed in docs/: each page, its "
        "tables and figures made again from those tables alone (no run), and the tables "
        "of the readings it tabulates in this version's format",
    )
    page.add_argument(
        "--out",
        type=OutFolder(lammps=False),
        default=None,
        help="write the page and its figures into this folder instead of docs/ "
        "(a results page's tables too)",
    )
    return parser


def check_launch(options) -> None:
    """Refuse, before anything is built, a run that cannot start: more ranks
    than this machine's cores (mpirun would refuse them after, in a message
    of dashes) unless MPI is told to oversubscribe or IMPACT_MPIRUN launches
    elsewhere; no mpirun or IMPACT_MPIRUN's program; no lmp."""
    nprocs = options.nprocs
    if options.route == "lmp" or nprocs > 1:
        mpi_launcher(nprocs)
        require_lmp()
    cores = os.cpu_count() or 1
    told = os.environ.get("OMPI_MCA_rmaps_base_oversubscribe") or os.environ.get("IMPACT_MPIRUN")
    if nprocs > cores and not told:
        raise InputError(
            f"--np must be at most this machine's {cores} cores, got {nprocs} "
            "(OMPI_MCA_rmaps_base_oversubscribe=1 runs more ranks than cores, slowly)"
        )


def main(argv: list[str] | None = None) -> int:
    from analysis.text_table import format_table

    from ..impact import run_impact, run_scene

    args = parser().parse_args(argv)
    if isinstance(getattr(args, "preset", None), StudyFile):  # the file, and its study's name
        args.described, args.preset = args.preset, args.preset.study.name
    try:
        environment_paths()  # IMPACT_RUNS, IMPACT_POISSON_CACHE: through the one gate
        if args.command == "impact":
            spec = spec_from_args(args)
            out = args.out or runs_folder() / f"{spec.lattice}_s{spec.seed}_g{spec.gamma_deg:g}"
            require_out_folder("--out", out)
            validate_spec(spec)
            options = options_from_args(args)
            if problem := options.scene_problem(spec):  # before anything is built
                raise InputError(problem)
            check_launch(options)
            if warning := speed_warning(spec.vn, spec.gamma_deg):
                print(f"python -m runner: warning: {warning}", file=sys.stderr)
            results = [run_impact(spec, out, options)]
            note_if_halved(out)
        elif args.command == "run":
            gate(args.scene, "scene")  # it writes its results into the folder
            options = options_from_args(args)
            check_launch(options)
            results = [run_scene(args.scene, options)]
            note_if_halved(args.scene)
        elif args.command == "page":
            with stop_on_signals():  # every file whole or not at all (ground.gate.atomic)
                return remake_page(args)
        elif args.command == "tilt":
            with stop_on_signals():
                print(f"wrote {shown(wall_tilt(args))}")
            return 0
        else:
            with stop_on_signals():
                return run_study_command(args)
    except (InputError, BuildError, LammpsError, EnvironmentFault) as error:
        print(
            f"python -m runner: error: {clipped(str(error))}{unstable_hint(error, args)}",
            file=sys.stderr,
        )
        return 2 if isinstance(error, InputError) else 1
    except Stopped as stop:
        after = {
            "page": "no file half-written; the same command makes the page again",
            "tilt": "no file half-written; the same command starts again",
        }.get(args.command, "workers ended; the same command resumes the study")
        print(f"python -m runner: stopped by {stop}, {after}", file=sys.stderr)
        return 128 + stop.signum
    except OSError as error:  # a full disk, a read-only folder, a dangling link
        print(f"python -m runner: error: {os_error_line(error)}", file=sys.stderr)
        return 1
    for result in results:
        warn_if_inaccurate(result)
    print(format_table(results))
    return 0
