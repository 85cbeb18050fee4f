"""runner study: its options, and one study or a study with axes run."""

from __future__ import annotations

import argparse
import time

from builder.scene import VN
from ground.checks import InPath, Range, require_out_folder
from ground.errors import InputError

from ..study import (
    ANGLES,
    COT_GAMMA,
    LATTICES,
    MAX_IMPACTS,
    SAMPLES,
    Study,
    impact_cap,
    runs_folder,
)
from ..study.file import READINGS_KINDS, StudyFile, axis_studies
from ..study.lock import study_lock
from ..study.outputs import (
    combine_tables,
    docs_page,
    remake_tabulating_page,
    shown,
    study_places,
)
from ..study.provenance import record_wall_clock
from ..study.studies import study_file, study_names
from ..values import GRID
from .cluster_args import SLURM_ONLY, add_cluster_arguments, cluster_from_args, option
from .study_args import STUDY_RUN, STUDY_SCENE, study_from_args


def study_name(text: str) -> str:
    from ..study import name_problem

    if problem := name_problem(text):
        shown = text if len(text) <= 60 else f"{text[:60]}..."
        raise argparse.ArgumentTypeError(f"{problem}, got {shown!r}")
    return text


# tests/test_bad_input.py
study_name.bad_values = ("", ".", "a b", "../up", "a/b", "x$y", "n" * 300)


def study_argument(text: str) -> StudyFile:
    """A study file's name (studies/<name>.toml) or path: what it says
    (runner.study.studies.study_file); the study takes the file's name."""
    try:
        return study_file(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


study_argument.bad_values = ("no-such-study", "{tmp}/missing.toml")


def add_study_arguments(study) -> None:
    """runner study's options; None means 'the study's own' (its study.json, or the preset)."""
    study.add_argument(
        "preset",
        metavar="STUDY",
        type=study_argument,
        help=f"a study file (studies/*.toml, or a path to one), or its name: "
        f"{', '.join(study_names())}; paper: the study of docs/model.md section 7 in full; demo: "
        "the random lattice, 4 samples; speed: e and beta against v_n (docs/studies/speed/); "
        "grazing: e up to 86 degrees (docs/studies/grazing/)",
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
        help="let --samples, --lattices, and a study file's angles and retries "
        "(barrier_halvings), add to an existing study (never remove)",
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
    study.add_argument(
        "--max-impacts",
        type=Range(1, 100_000_000, integer=True),
        default=None,
        help=f"the most impacts the command may run, every combination of a study file's "
        f"axes together (default: {MAX_IMPACTS:,})",
    )
    study.add_argument(
        "--wait",
        action="store_true",
        help="if another run of the same study folder is under way, wait for it to end "
        "(default: refuse, naming its process)",
    )
    scene = study.add_argument_group("the scene and the run (default: the study's)")
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
    for declared in (*STUDY_SCENE, *STUDY_RUN):  # builder.scene, builder.run_options
        declared.add_argument(scene, default=None)
    pages = study.add_argument_group("tables, fits and the page")
    pages.add_argument("--report-only", action="store_true", help="only tables, fits and figures")
    pages.add_argument(
        "--from-tables",
        metavar="DIR",
        type=InPath("folder", ("impacts.csv", "failed.csv", "study.json")),
        default=None,
        help="only the page and its figures, from a study's tables in DIR (docs/studies/results: "
        "the committed paper study), without its runs; into runs/<name>/ (default name: "
        "<preset>_from_tables), or with --docs into docs/",
    )
    pages.add_argument(
        "--docs",
        action="store_true",
        help="write the page, its figures and tables into docs/studies/<page>/ instead of the "
        "study's folder (docs/studies/results/ for paper: make paper does this); with another "
        "--name, a reading its page tabulates, into docs/studies/<name>/",
    )


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
    "vn",
    "speeds",
    *(option.name for option in (*STUDY_SCENE, *STUDY_RUN)),
    "report_only",
)


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
    from ..study.readings import run_readings_study

    impact_cap(getattr(args, "max_impacts", None) or MAX_IMPACTS)

    described = args.described
    readings_kind = described.kind in READINGS_KINDS
    axes = described.axes if not readings_kind else {}
    if axes and (args.docs or args.from_tables):
        given = "--docs" if args.docs else "--from-tables"
        raise InputError(
            f"{given}: the {args.preset} study has axes ({', '.join(axes)}); "
            "each combination's tables and page go under runs/"
        )
    docs_page(args, described)
    if readings_kind:
        cluster = cluster_from_args(args, runs_folder() / args.preset)
        return run_readings_study(args, described, cluster)
    if not axes:
        return run_one_study(args, described)
    flattened = [key for key in axes if getattr(args, key, None) is not None]
    if flattened:
        key = flattened[0]
        raise InputError(
            f"{option(key)}: {key} is an axis of the {args.preset} study "
            f"({', '.join(map(str, axes[key]))}); change its values in the file"
        )
    name = args.name or args.preset
    combined = runs_folder() / name
    if (combined / "study.json").exists():
        raise InputError(f"--name {name}: {combined} holds a study; give another --name")
    require_out_folder("--name", combined)
    planned = []
    files = set(study_names())
    for sub in axis_studies(described.study, axes, name, described.sweep):
        if sub.name in files and sub.name != args.preset:
            raise InputError(
                f"{described.path}: the combination {sub.name} has the name of the study "
                f"file studies/{sub.name}.toml; give another --name"
            )
        sub_args = argparse.Namespace(
            **{**vars(args), "preset": sub.name, "name": sub.name, "described": None}
        )
        refuse_idle_options(sub_args)
        try:
            planned.append((sub_args, study_from_args(sub_args, sub, file=described.path)))
        except InputError as error:  # which combination, and which file
            told = str(error).removeprefix(f"{described.path}: ")
            raise InputError(f"{described.path}: combination {sub.name}: {told}") from None
    total = sum(study.size() for _, study in planned)
    if total > impact_cap():
        sizes = " + ".join(str(study.size()) for _, study in planned[:6])
        more = " + ..." if len(planned) > 6 else ""
        raise InputError(
            f"{described.path}: its {len(planned)} combinations have {total:,} impacts together "
            f"({sizes}{more}), more than {impact_cap():,}: give fewer values or samples, or "
            "--max-impacts"
        )
    status = 0
    for sub_args, study in planned:
        print(f"{args.preset}: {study.name}", flush=True)
        status = max(status, run_one_study(sub_args, None, study))
    table = combine_tables([study.folder for _, study in planned], combined)
    print(f"{len(planned)} studies of {args.preset}; their impacts together in {shown(table)}")
    return status


def run_one_study(args, described: StudyFile | None, study: Study | None = None) -> int:
    """One study (``study``, if already made from ``args``; ``described`` its
    file, None for a combination of a file's axes): its impacts, then its
    tables and page; or its page from tables alone (--from-tables)."""
    from pages.report import report, report_from_tables

    from ..cluster.driver import run_study

    refuse_idle_options(args)
    # the study's page, or (with --name) a reading its page tabulates: the
    # reading's tables go into docs/studies/<name>/ and the study's page is made again
    # with them; the reading's own page stays under runs/
    places = study_places(args, described)
    sections = (described.sections or None) if described else None
    if args.from_tables:
        summary = report_from_tables(
            args.from_tables,
            places.page,
            preset=args.preset,
            out=places.tables,
            readings=places.readings,
            sections=sections,
        )
        print(
            f"{summary['rows']} impacts, {summary['failed']} failed; "
            f"results in {shown(summary['page'])}"
        )
        if places.tabulated:
            remake_tabulating_page(described, places.readings)
        return 0
    cluster = cluster_from_args(args, runs_folder() / (args.name or args.preset))
    study = study or study_from_args(args, described.study, file=described.path)
    with study_lock(study.folder, wait=getattr(args, "wait", False)):  # one run per folder
        if args.report_only:  # a page of what the study asks, never of another's rows
            study.check_done(study.jobs())
        else:
            start = time.monotonic()
            counts = run_study(study, retry_failed=args.retry_failed, cluster=cluster)
            record_wall_clock(study, time.monotonic() - start, counts)
        summary = report(
            study,
            page=places.page,
            preset=args.preset,
            tables=places.tables,
            readings=places.readings,
            sections=sections,
        )
    if places.tabulated:
        remake_tabulating_page(described, {**places.readings, places.doc_name: places.tables})
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
