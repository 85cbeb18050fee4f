"""A readings study (a study file whose ``kind`` is a readings page,
analysis.kinds): its combinations as studies, the best of them again, one
table of rows, and its page.

Each combination of the file's axes (crossed, or one at a time) is a study of
its own, runs/<name>_<option>-<value>.../, resumable like any; its impacts,
finished and failed, become rows of the study's table marked with the
combination's reading. ``[rerun]`` then takes the best readings by the
page's rule to more samples (the same studies, more seeds) and runs other
disks on the best. The table (rows.csv) and the record of the run (run.json)
go into runs/<name>/, with --docs into docs/studies/<page>/, and the page is made
from them, as ``python -m runner page <name>`` makes it again.
"""

from __future__ import annotations

import argparse
from dataclasses import asdict, replace
from pathlib import Path

from analysis.impact.failures import impact_state
from analysis.kinds import kind_module
from analysis.kinds.readings import (
    RECORD,
    ROWS,
    Setup,
    read_rows,
    study_rows,
    write_record,
    write_tables,
)
from analysis.table import TIMINGS
from ground.checks import require_out_folder
from ground.errors import InputError
from ground.gate import make_folder, write_text
from ground.paths import study_docs
from ground.provenance import git_revision
from pages.kinds import readings_page

from ..cli.study_args import check_environment, check_source
from . import runs_folder
from .file import StudyFile, axis_studies, combinations
from .provenance import machine

# runner study's options that a readings study takes (its file says the rest).
TAKES = ("preset", "described", "command", "docs", "cluster", "workers", "scheduler")
TAKES += ("retry_failed", "extend")
TAKES += ("jobs", "cores_per_job", "walltime", "queue", "account", "memory")
TAKES += ("partitions", "batch_size")


def check_labels(described: StudyFile) -> None:
    """Refuse a readings study whose page could not name each combination
    (its kind's ``label`` needs an option the file gives no axis, or reads
    two combinations alike); checked where the page's module is at hand,
    before any work.

    Raises
    ------
    ground.errors.InputError
        One line naming the file and the kind.
    """
    path, kind = described.path, described.kind
    labels = []
    for choice in combinations(described.axes, described.sweep):
        try:
            labels.append(kind_module(kind).label(choice))
        except KeyError as missing:
            raise InputError(
                f"{path}: kind {kind} compares readings by {missing.args[0]}: give it a "
                f"list of values (an axis)"
            ) from None
    if len(set(labels)) != len(labels):
        raise InputError(f"{path}: kind {kind}: two combinations read alike ({labels})")


def setup_of(name: str, described: StudyFile) -> Setup:
    """What the page is made from besides its rows, from the study file."""
    study = asdict(replace(described.study, name=name))
    choices = tuple(combinations(described.axes, described.sweep))
    return Setup(study, choices, dict(described.named), dict(described.rerun))


def tables_folder(name: str, described: StudyFile, docs: bool) -> Path:
    """docs/studies/<page>/ with --docs, else runs/<name>/."""
    if docs:
        return study_docs(described.page)
    return require_out_folder("the study's folder", runs_folder() / name)


def refuse_options(args: argparse.Namespace) -> None:
    """An option a readings study does not take is refused, not ignored."""
    given = [
        key for key, value in vars(args).items() if key not in TAKES and value not in (None, False)
    ]
    if given:
        raise InputError(
            f"--{given[0].replace('_', '-')} does not apply to the {args.preset} study, "
            "whose file gives its grid (a readings study); change it there"
        )


def again(study, **changes):
    """A combination's study run again: to more samples (the same study), or
    on other lattices (a study of its own, <name>_<lattices>)."""
    if "lattices" in changes:
        changes["name"] = f"{study.name}_{'_'.join(changes['lattices'])}"
    return replace(study, **changes)


def run_readings_study(args: argparse.Namespace, described: StudyFile, cluster) -> int:
    """Run every combination, the re-run of the best, write the table and the page."""
    from ..cluster.driver import run_study

    refuse_options(args)
    check_labels(described)
    name = args.preset
    if args.docs and not described.page:
        raise InputError(f"--docs: the {name} study has no page in docs/ (its file's page)")
    module = kind_module(described.kind)
    setup = setup_of(name, described)
    out = tables_folder(name, described, args.docs)
    studies = axis_studies(described.study, described.axes, name, described.sweep)
    levels = described.level_samples  # seeds per n_disk, where the file lists them
    if levels:
        studies = [
            replace(s, samples=levels[c["n_disk"]])
            for c, s in zip(setup.choices, studies, strict=True)
        ]
    # each combination's grid as the file gives it, which its study.json keeps
    studies = [replace(study, source=study.grid()) for study in studies]
    pairs = list(zip(setup.choices, studies, strict=True))
    if hasattr(module, "plan"):  # the kind thins its grid (fewer seeds where impacts cost more)
        thin = {"thin": False} if levels else {}  # the file's seeds per level, as given
        pairs = [(c, p) for c, s in pairs if (p := module.plan(c, s, **thin)) is not None]
    by_label = {module.label(c): (c, s) for c, s in pairs}
    rerun = described.rerun
    for _, study in by_label.values():  # every study the run may make, before the first starts
        others = [again(study, lattices=(x,)) for x in rerun.get("then_lattices", ())]
        if rerun.get("best"):
            others.append(again(study, samples=rerun["samples"]))
        for each in (study, *others):
            try:
                each.validate()
                check_source(each, described.path, args.extend)
                check_environment(each)
            except InputError as error:
                told = str(error).removeprefix(f"{described.path}: ")
                raise InputError(f"{described.path}: combination {each.name}: {told}") from None

    def run(label: str, **changes) -> list[dict]:
        choice, study = by_label[label]
        study = again(study, **changes)
        study.validate()
        run_study(study, retry_failed=args.retry_failed, cluster=cluster)
        rows = study_rows(study, label)
        extra = module.row_fields(choice, setup) if hasattr(module, "row_fields") else {}
        return [{**row, **extra} for row in rows]

    rows = [row for label in by_label for row in run(label)]
    record = {"command": f"python -m runner study {name}" + (" --docs" if args.docs else "")}
    if rerun.get("best"):
        best = module.rank(rows, setup)[: rerun["best"]]
        if rerun.get("default"):
            # the default of the day goes as far as the best: the comparison
            # that would change it is then made at the same precision
            default = module.label(module.current_default())
            record["default"] = default
            if default in by_label and default not in best:
                best.append(default)
        for label in best:
            rows = [r for r in rows if r["reading"] != label]
            rows += run(label, samples=rerun["samples"])
    if rerun.get("then_best"):
        for label in module.rank(rows, setup)[: rerun["then_best"]]:
            for lattice in rerun["then_lattices"]:
                rows += run(label, lattices=(lattice,))
    make_folder(out)
    before = {n: (out / n).read_bytes() for n in (ROWS, RECORD, TIMINGS) if (out / n).is_file()}
    write_tables(rows, out, module.COLUMNS)
    write_record({**record, "git_revision": git_revision(), "machine": machine()}, out)
    if before.get(ROWS) == (out / ROWS).read_bytes():
        # every impact as the table had it: the provenance stays that of the run that made it
        for name in (RECORD, TIMINGS):
            if name in before:
                write_text(out / name, before[name].decode())
    page = out / f"{described.page or name}.md" if args.docs else out / f"{name}.md"
    readings_page(described.kind, out, page, setup)
    failed = sum(bool(r.get("error")) and impact_state(r["error"]) == "failed" for r in rows)
    stuck = sum(bool(r.get("error")) for r in rows) - failed
    said = f", in {stuck} the disk had not left the wall by tmax" if stuck else ""
    print(f"{len(rows)} impacts, {failed} failed{said}; the table in {out / ROWS}, page {page}")
    return 1 if failed else 0  # a disk that stayed on the wall is physics, not a failed run


def remake_page(name: str, described: StudyFile, out: Path | None = None) -> Path:
    """The page of a readings study again from its committed table in
    docs/studies/<page>/, beside it (or into ``out``)."""
    check_labels(described)
    tables = study_docs(described.page)
    if not (tables / ROWS).is_file():
        raise InputError(f"{name}: {tables} holds no table (rows.csv): run the study with --docs")
    if out is None:  # tables from before timings.csv: their seconds move out of rows.csv
        write_tables(read_rows(tables), tables, kind_module(described.kind).COLUMNS)
    page = (out or tables) / f"{described.page}.md"
    return readings_page(described.kind, tables, page, setup_of(name, described))
