"""The run's options on the command line (runner impact, runner run)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ground.errors import InputError
from ground.launch import LammpsError

from ..impact import BARRIER_CROSSED
from ..options import AUTO, DEFAULT_DT, RUN_OPTIONS, RunOptions

# Options that apply to one integrator or contact: None means "not given",
# and giving them for another is refused (options_from_args).
GIVEN_ONLY = {"nrespa": ("integrator", "respa"), "rule": ("contact", "segment")}


def add_run_arguments(parser) -> None:
    """Every run option of runner impact and runner run (builder.run_options)."""
    group = parser.add_argument_group("run")
    for option in RUN_OPTIONS:
        if option.cli:
            option.add_argument(group, None if option.name in GIVEN_ONLY else option.default)


def options_from_args(args: argparse.Namespace) -> RunOptions:
    """The run's options; an option that does not apply to the chosen
    integrator or contact is refused, not ignored."""
    for name, (other, wanted) in GIVEN_ONLY.items():
        if getattr(args, name) is not None and getattr(args, other) != wanted:
            raise InputError(
                f"--{name} applies to --{other} {wanted} only, got {getattr(args, other)}"
            )
    given = {o.name: getattr(args, o.name) for o in RUN_OPTIONS if o.cli}
    return RunOptions(**{k: v for k, v in given.items() if v is not None})


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
    # the springs' blow-up, or (with --area-floor) a triangle that crossed the
    # barrier within one step: both a step too long for the scene
    if "unstable" not in text and BARRIER_CROSSED not in text:
        return ""
    return (
        f" (dt = {args.dt:g} R/c; the default, {default:g}, is the largest step found "
        f"accurate, docs/benchmarks/time_vs_error.md)"
        if args.dt > default
        else f" (dt = {args.dt:g} R/c)"
    )


def note_if_halved(folder: Path) -> None:
    """One line on stderr where the run halved the step it was given
    (runner.impact.may_halve): the table's dt is the step it ran at."""
    run = json.loads((Path(folder) / "run.json").read_text())
    if halvings := run.get("dt_halvings"):
        print(
            f"python -m runner: note: ran at dt = {run['options']['dt']:g} R/c, the step given "
            f"halved {halvings} time{'s' if halvings > 1 else ''}: at the longer one a triangle "
            "crossed the area barrier, or the contact was not resolved, within one step "
            "(--barrier-halvings)",
            file=sys.stderr,
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
