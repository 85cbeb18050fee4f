"""The run's options on the command line (runner impact, runner run)."""

from __future__ import annotations

import argparse
import sys

from builder.errors import InputError

from .lammps_run import LammpsError
from .options import (
    AUTO,
    CHECK_INTERVAL,
    CONTACTS,
    DEFAULT_DT,
    DRIFT,
    DT,
    DUMP_EVERY,
    INTEGRATORS,
    MAX_CHUNK_TIME,
    NPROCS,
    NRESPA,
    ROUTES,
    RULES,
    SPRINGS,
    STEPS,
    TMAX,
    RunOptions,
)

MAX_DRIFT_HELP = (
    "flag a run whose energy drift (change of the total energy over the initial "
    "kinetic energy) exceeds this: its time step is too large (default: {:g}; "
    "99 %% of the paper study below 4.7e-3 at the default dt; docs/benchmarks/time_vs_error.md)"
)


def time_step(text: str) -> float | str:
    """--dt: a step, or "auto" (runner.options.RunOptions.for_scene)."""
    if text == AUTO:
        return text
    try:
        return DT(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"must be {DT.describe()} or 'auto', got {text}") from None


time_step.numbers = DT  # tests/test_bad_input.py feeds it bad numbers


def add_run_arguments(parser) -> None:
    group = parser.add_argument_group("run")
    defaults = RunOptions()
    group.add_argument(
        "--dt",
        type=time_step,
        default=defaults.dt,
        help=f"time step, {DT.describe()}, or auto: {DEFAULT_DT:g} at 800 disk points, "
        "scaled with the finer body's spacing (default: auto)",
    )
    group.add_argument(
        "--check",
        type=STEPS,
        default=defaults.check,
        help="steps between checks whether the impact is over, a multiple of the "
        f"series' rows; check * dt must be at most {MAX_CHUNK_TIME:g} R/c (default: the "
        f"steps nearest {CHECK_INTERVAL:g} R/c, {defaults.check_steps} at dt {DEFAULT_DT:g})",
    )
    group.add_argument("--integrator", choices=INTEGRATORS, default=defaults.integrator)
    group.add_argument(
        "--nrespa",
        type=NRESPA,
        default=None,
        help=f"respa: contact steps per step of --dt (the contact alone on the inner "
        f"level), {NRESPA.describe()} (default: {defaults.nrespa})",
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
        default=None,
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
        type=TMAX,
        default=defaults.tmax,
        help=f"stop with an error if the disk has not left by then, {TMAX.describe()}",
    )
    group.add_argument(
        "--dump-every",
        type=DUMP_EVERY,
        default=0,
        help=f"steps between dump frames, {DUMP_EVERY.describe()} (0: no dump)",
    )
    group.add_argument(
        "--stop-rule",
        choices=("predict", "clearance"),
        default=defaults.stop_rule,
        help="when the impact is over: predict (rigid-body extrapolation, default) "
        "or clearance (wait until the disk clears every asperity)",
    )
    group.add_argument(
        "--np", dest="nprocs", type=NPROCS, default=1, help=f"MPI ranks, {NPROCS.describe()}"
    )
    group.add_argument(
        "--route",
        choices=ROUTES,
        default="lmp",
        help="lmp program (default) or the lammps Python module",
    )
    group.add_argument(
        "--max-drift",
        type=DRIFT,
        default=defaults.max_drift,
        help=MAX_DRIFT_HELP.format(defaults.max_drift),
    )


def options_from_args(args: argparse.Namespace) -> RunOptions:
    """The run's options; an option that does not apply to the chosen
    integrator or contact is refused, not ignored."""
    if args.nrespa is not None and args.integrator != "respa":
        raise InputError(f"--nrespa applies to --integrator respa only, got {args.integrator}")
    if args.rule is not None and args.contact != "segment":
        raise InputError(f"--rule applies to --contact segment only, got {args.contact}")
    defaults = RunOptions()
    return RunOptions(
        dt=args.dt,
        check=args.check,
        integrator=args.integrator,
        nrespa=args.nrespa if args.nrespa is not None else defaults.nrespa,
        contact=args.contact,
        rule=args.rule if args.rule is not None else defaults.rule,
        springs=args.springs,
        tmax=args.tmax,
        dump_every=args.dump_every,
        stop_rule=args.stop_rule,
        nprocs=args.nprocs,
        route=args.route,
        max_drift=args.max_drift,
    )


def unstable_hint(error: Exception, args) -> str:
    """For a run that blew up or let a disk point into the wall: the step and
    speed it ran at, and what to try."""
    text = str(error)
    if not isinstance(error, LammpsError) or getattr(args, "dt", None) in (None, AUTO):
        return ""
    default = DEFAULT_DT
    if "inside the wall" in text:
        vn = f"v_n = {args.vn:g} c, " if getattr(args, "vn", None) is not None else ""
        return (
            f" ({vn}dt = {args.dt:g} R/c: the contact was not resolved; try a smaller --dt"
            f"{' or --vn' if vn else ''}; docs/benchmarks/stability_speeds.md)"
        )
    if "unstable" not in text:
        return ""
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
            f"(default dt {DEFAULT_DT:g} at 800 points; docs/benchmarks/time_vs_error.md)",
            file=sys.stderr,
        )
