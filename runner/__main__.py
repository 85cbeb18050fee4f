"""Command line: python -m runner {impact,run,study} --help"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from builder.cli import (
    OneLineParser,
    add_scene_arguments,
    add_wall_arguments,
    count,
    positive_float,
    spec_from_args,
)
from builder.errors import BuildError, InputError

from .lammps_run import LammpsError
from .options import (
    CHECK_INTERVAL,
    CONTACTS,
    INTEGRATORS,
    MAX_CHUNK_TIME,
    ROUTES,
    RULES,
    SPRINGS,
    RunOptions,
)
from .stopping import Stopped, stop_on_signals

MAX_DRIFT_HELP = (
    "flag a run whose energy drift (change of the total energy over the initial "
    "kinetic energy) exceeds this: its time step is too large (default: {:g}; "
    "99 %% of the paper study below 4.7e-3 at the default dt; docs/benchmarks/time_vs_error.md)"
)


def study_name(text: str) -> str:
    from .study import name_problem

    if problem := name_problem(text):
        raise argparse.ArgumentTypeError(f"{problem}, got {text!r}")
    return text


def add_run_arguments(parser) -> None:
    group = parser.add_argument_group("run")
    defaults = RunOptions()
    group.add_argument(
        "--dt",
        type=positive_float,
        default=defaults.dt,
        help=f"time step in R/c (default: {defaults.dt})",
    )
    group.add_argument(
        "--check",
        type=count(1),
        default=defaults.check,
        help="steps between checks whether the impact is over, a multiple of the "
        f"series' rows; check * dt must be at most {MAX_CHUNK_TIME:g} R/c (default: the "
        f"steps nearest {CHECK_INTERVAL:g} R/c, {defaults.check_steps} at the default dt)",
    )
    group.add_argument("--integrator", choices=INTEGRATORS, default=defaults.integrator)
    group.add_argument(
        "--nrespa",
        type=count(1),
        default=defaults.nrespa,
        help="respa: contact steps per step of --dt (the contact alone on the inner level)",
    )
    group.add_argument(
        "--contact",
        choices=CONTACTS,
        default=defaults.contact,
        help="segment: the paper's point-to-polyline contact (default); "
        "pair: the same exponential between points",
    )
    group.add_argument(
        "--rule",
        choices=RULES,
        default=defaults.rule,
        help="segment contact: lever rule (default) or explicit gradient",
    )
    group.add_argument(
        "--springs",
        choices=SPRINGS,
        default=defaults.springs,
        help="bond style: harmonic/quartic (the project's own, default) or "
        "class2, the same quartic springs; harmonic: no quartic",
    )
    group.add_argument(
        "--tmax",
        type=positive_float,
        default=defaults.tmax,
        help="stop with an error if the disk has not left by then (R/c)",
    )
    group.add_argument(
        "--dump-every", type=count(0), default=0, help="steps between dump frames (0: no dump)"
    )
    group.add_argument(
        "--stop-rule",
        choices=("predict", "clearance"),
        default=defaults.stop_rule,
        help="when the impact is over: predict (rigid-body extrapolation, default) "
        "or clearance (wait until the disk clears every asperity)",
    )
    group.add_argument("--np", dest="nprocs", type=count(1), default=1, help="MPI ranks")
    group.add_argument(
        "--route",
        choices=ROUTES,
        default="lmp",
        help="lmp program (default) or the lammps Python module",
    )
    group.add_argument(
        "--max-drift",
        type=positive_float,
        default=defaults.max_drift,
        help=MAX_DRIFT_HELP.format(defaults.max_drift),
    )


def options_from_args(args) -> RunOptions:
    return RunOptions(
        dt=args.dt,
        check=args.check,
        integrator=args.integrator,
        nrespa=args.nrespa,
        contact=args.contact,
        rule=args.rule,
        springs=args.springs,
        tmax=args.tmax,
        dump_every=args.dump_every,
        stop_rule=args.stop_rule,
        nprocs=args.nprocs,
        route=args.route,
        max_drift=args.max_drift,
    )


def unstable_hint(error: Exception, args) -> str:
    """For a run that blew up: its time step against the default's."""
    if not (
        isinstance(error, LammpsError)
        and "unstable" in str(error)
        and getattr(args, "dt", None) is not None
    ):
        return ""
    default = RunOptions().dt
    return (
        f" (dt = {args.dt:g} R/c; the default, {default:g}, is the largest step found "
        f"accurate, docs/benchmarks/time_vs_error.md)"
        if args.dt > default
        else f" (dt = {args.dt:g} R/c)"
    )


def warn_if_inaccurate(result: dict) -> None:
    """One line on stderr if the run's energy drift says its time step is too large."""
    if result.get("drift_exceeded"):
        print(
            f"python -m runner: warning: energy drift {result['energy_drift']:.3g} of the initial "
            f"kinetic energy exceeds --max-drift {result['max_drift']:g} at dt = {result['dt']:g} "
            f"R/c: the time step is too large for this scene, e and beta are inaccurate "
            f"(default dt {RunOptions().dt:g}; docs/benchmarks/time_vs_error.md)",
            file=sys.stderr,
        )


def main(argv: list[str] | None = None) -> int:
    from .impact import run_impact, run_scene
    from .report import format_table

    parser = OneLineParser(prog="python -m runner", description="Run oblique impacts with LAMMPS.")
    commands = parser.add_subparsers(dest="command", required=True)

    impact = commands.add_parser("impact", help="build a scene, run one impact, print its result")
    add_scene_arguments(impact)
    add_run_arguments(impact)
    impact.add_argument(
        "--out", default=None, help="run folder (default: runs/<lattice>_s<seed>_g<gamma>)"
    )

    run = commands.add_parser("run", help="run an existing scene folder (python -m builder scene)")
    run.add_argument("scene", help="folder with scene.data, scene.lmp and scene.json")
    add_run_arguments(run)

    study = commands.add_parser("study", help="the study: sweep, tables, fits, figures (resumable)")
    study.add_argument(
        "preset",
        choices=("paper", "demo"),
        help="paper: MODEL.md section 7 in full; demo: the random lattice, 4 samples",
    )
    study.add_argument(
        "--samples", type=count(1), default=None, help="samples per lattice and angle"
    )
    study.add_argument("--angles", type=count(2), default=None, help="number of angles")
    study.add_argument(
        "--lattices",
        nargs="+",
        default=None,
        help="among random triangular square_nu0.1 square_nu0.3",
    )
    study.add_argument(
        "--name",
        type=study_name,
        default=None,
        help="folder under runs/ (default: the preset): one folder name, "
        "no '/', '..' or whitespace",
    )
    study.add_argument("--workers", type=count(1), default=2, help="worker processes (default: 2)")
    study.add_argument(
        "--partitions",
        type=count(0),
        default=0,
        help="run on this many LAMMPS partitions under mpirun instead of workers",
    )
    study.add_argument(
        "--batch-size",
        type=count(1),
        default=16,
        help="with --partitions: impacts per partition in one MPI job (default: 16)",
    )
    study.add_argument("--retry-failed", action="store_true", help="run failed impacts again")
    study.add_argument("--dt", type=positive_float, default=None, help="time step, R/c")
    study.add_argument(
        "--n-disk", type=count(50), default=None, help="points in each disk (default: 800)"
    )
    study.add_argument(
        "--wall-width",
        type=positive_float,
        default=None,
        help="wall width in R (default: 8, MODEL.md's; see docs/model.md for grazing angles)",
    )
    study.add_argument(
        "--contact-a",
        type=positive_float,
        default=None,
        help="contact decay rate a R (default: 300; 300 * sqrt(n_disk / 800) for finer disks)",
    )
    add_wall_arguments(
        study.add_argument_group("the wall's reading (default: the preset's)"), defaults=False
    )
    study.add_argument(
        "--max-drift",
        type=positive_float,
        default=None,
        help=MAX_DRIFT_HELP.format(RunOptions().max_drift),
    )
    study.add_argument("--report-only", action="store_true", help="only tables, fits and figures")
    study.add_argument(
        "--from-tables",
        metavar="DIR",
        default=None,
        help="only docs/results.md and its figures, from a study's tables in DIR "
        "(docs/results: the committed paper study), without its runs",
    )

    args = parser.parse_args(argv)
    try:
        if args.command == "impact":
            spec = spec_from_args(args)
            out = args.out or f"runs/{spec.lattice}_s{spec.seed}_g{spec.gamma_deg:g}"
            results = [run_impact(spec, out, options_from_args(args))]
        elif args.command == "run":
            results = [run_scene(args.scene, options_from_args(args))]
        else:
            with stop_on_signals():
                return run_study_command(args)
    except (InputError, BuildError, LammpsError) as error:
        print(f"python -m runner: error: {error}{unstable_hint(error, args)}", file=sys.stderr)
        return 2 if isinstance(error, InputError) else 1
    except Stopped as stop:
        print(
            f"python -m runner: stopped by {stop}, workers ended; the same command resumes "
            f"the study",
            file=sys.stderr,
        )
        return 128 + stop.signum
    for result in results:
        warn_if_inaccurate(result)
    print(format_table(results))
    return 0


def run_study_command(args) -> int:
    from dataclasses import replace

    from analysis.report import report, report_from_tables

    from .study import PRESETS, record_wall_clock, run_study

    docs = Path(__file__).resolve().parents[1] / "docs"
    if args.from_tables:
        summary = report_from_tables(
            Path(args.from_tables), docs / "results.md", preset=args.preset
        )
        page = Path(summary["page"])
        page = page.relative_to(Path.cwd()) if page.is_relative_to(Path.cwd()) else page
        print(f"{summary['rows']} impacts, {summary['failed']} failed; results in {page}")
        return 0
    study = PRESETS[args.preset]
    changes = {
        key: value
        for key, value in (
            ("samples", args.samples),
            ("angles", args.angles),
            ("name", args.name),
            ("n_disk", args.n_disk),
            ("wall_width", args.wall_width),
            ("contact_a", args.contact_a),
            ("n_wall", args.n_wall),
            ("wall_ka", args.wall_ka),
            ("wall_fixed", args.wall_fixed),
        )
        if value is not None
    }
    if args.lattices:
        changes["lattices"] = tuple(args.lattices)
    options = {
        key: value for key, value in (("dt", args.dt), ("max_drift", args.max_drift)) if value
    }
    if options:
        changes["options"] = replace(study.options, **options)
    study = replace(study, **changes)
    study.validate()
    if args.report_only and not (study.folder / "study.json").exists():
        raise InputError(f"--report-only: no study in {study.folder}; run it first")
    if not args.report_only:
        start = time.monotonic()
        if args.partitions:
            from .partitions import run_study_partitions

            counts = run_study_partitions(
                study, args.partitions, args.retry_failed, args.batch_size
            )
        else:
            counts = run_study(study, args.workers, args.retry_failed)
        record_wall_clock(study, time.monotonic() - start, counts, args.partitions or args.workers)
    # the paper's study, whatever its sample count, is the one the docs show, and
    # its tables go into docs/results/, from which --from-tables remakes the page
    paper = args.preset == "paper" and args.name is None
    summary = report(
        study,
        page=docs / "results.md" if paper else None,
        preset=args.preset,
        tables=docs / "results" if paper else None,
    )
    causes = "; ".join(f"{count}: {cause}" for cause, count in summary["causes"].items())
    drift = (
        f", {summary['drift_exceeded']} above --max-drift {study.options.max_drift:g}"
        if summary["drift_exceeded"]
        else ""
    )
    shown = Path(summary["page"])
    if shown.is_relative_to(Path.cwd()):  # as the user would type it
        shown = shown.relative_to(Path.cwd())
    print(
        f"{summary['rows']} impacts{drift}, {summary['failed']} failed"
        f"{f' ({causes})' if causes else ''}; results in {shown}"
    )
    return 1 if summary["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
