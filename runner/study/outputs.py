"""Where a study's tables and page go: runs/<name>/, or with --docs its
folder docs/studies/<page>/ (or, with --name, a reading its page
tabulates: docs/studies/<name>/); and a page made again from its committed
tables."""

from __future__ import annotations

import csv
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from ground.checks import require_out_folder
from ground.errors import InputError
from ground.gate import runs_folder
from ground.paths import study_docs, study_page

from .file import READINGS_KINDS, StudyFile
from .studies import all_studies, built_in_pages, require_page


def shown(path: Path | str) -> Path:
    """A path as the user would type it: from the current folder where it is inside."""
    path = Path(path)
    return path.relative_to(Path.cwd()) if path.is_relative_to(Path.cwd()) else path


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
            f"--docs writes the {args.preset} study's page, docs/studies/{described.page}/"
            f"{readings if described.readings else ''}; --name {name} is not one: leave out "
            f"--docs (its page goes into runs/{name}/)"
        )
    # every file, in studies/ or not: the page must be its own (runner.study.studies)
    require_page(described, page, *([described.page] if page != described.page else []))
    return page


@dataclass
class Places:
    """Where one study's outputs go (``study_places``): its tables' folder and
    its page (None: the study's own folder's), the readings its page
    tabulates, and whether its tables are one of those readings
    (``tabulated``: the tabulating page is made again with them)."""

    doc_name: str | None = None
    tables: Path | None = None
    page: Path | None = None
    readings: dict[str, Path] = field(default_factory=dict)
    tabulated: bool = False


def study_places(args, described: StudyFile | None) -> Places:
    """Where a `runner study` command's tables and page go.

    Without --docs, runs/<name>/ (the study's own folder); with --docs, the
    study's folder docs/studies/<page>/ (page, tables, figures), or with
    --name one of the readings its page tabulates: docs/studies/<name>/, the
    page in runs/<name>/. --from-tables writes into runs/<name>/ (default name
    <preset>_from_tables), or with --docs into docs/.

    Raises
    ------
    ground.errors.InputError
        For a folder the command may not write (``docs_page``, and a folder
        of runs/ that holds a study the tables would replace).
    """
    doc_name = docs_page(args, described)  # None: an axis' combination
    wanted = described.readings if described else ()
    tabulated = bool(args.docs) and doc_name in wanted
    readings = {n: study_docs(n) for n in wanted if (study_docs(n) / "impacts.csv").is_file()}
    if args.docs and not tabulated:
        for name in sorted(set(wanted) - set(readings)):
            print(
                f"warning: the page has no row for {name}: docs/studies/{name}/ holds no tables "
                f"(python -m runner study {args.preset} --name {name} --docs makes them)",
                file=sys.stderr,
                flush=True,
            )
    tables = study_docs(doc_name) if args.docs else None
    page = study_page(doc_name) if args.docs and not tabulated else None
    if args.from_tables:
        name = args.name or f"{args.preset}_from_tables"
        tables = tables or runs_folder() / name
        page = study_page(doc_name) if args.docs else tables / "results.md"
        if tabulated:
            page = require_out_folder("--name", runs_folder() / name) / "results.md"
            page.parent.mkdir(parents=True, exist_ok=True)
        if not args.docs:
            require_out_folder("--name", tables)
        if (tables / "study.json").exists() and tables.resolve() != args.from_tables.resolve():
            raise InputError(
                f"--name {name}: {tables} holds a study, which the tables would replace; "
                "give another --name"
            )
    return Places(doc_name, tables, page, readings, tabulated)


def remake_page(args) -> int:
    """runner page: a study's page from its committed tables in
    docs/studies/<page>/ (--all: every study's that has them)."""
    if args.all == (args.preset is not None):
        raise InputError("page: give a STUDY or --all, not both or neither")
    if args.out is not None and (args.out / "study.json").exists():  # a study's own folder
        raise InputError(
            f"--out: {args.out} holds a study (study.json), whose page and tables this would "
            "replace; give a folder of its own"
        )
    if not args.all:
        print(f"wrote {shown(remake_one_page(args.described, args.out))}")
        return 0
    with_page = [d for d in all_studies().values() if d.page]
    for count, described in enumerate(with_page, start=1):
        tables = study_docs(described.page)
        name = described.study.name
        if (tables / "study.json").is_file() or (tables / "rows.csv").is_file():
            # a page takes seconds to minutes (its fits' resamples): say which one
            print(f"page {count} of {len(with_page)}: {name}...", flush=True)
            start = time.monotonic()
            page = remake_one_page(described, args.out)
            print(f"wrote {shown(page)} ({time.monotonic() - start:.0f} s)", flush=True)
        else:
            print(f"page {count} of {len(with_page)}: {name} has no tables in {shown(tables)}; "
                  "its page is made by its run", flush=True)  # fmt: skip
    return 0


def remake_one_page(described: StudyFile, out: Path | None) -> Path:
    """A study's page (and its tables and figures, with ``out``: into ``out``) from its
    committed tables; the tables of the readings it tabulates are brought to
    this version's format from themselves first. Returns the page."""
    from analysis.study_tables import tidy_tables
    from pages.report import report_from_tables

    from .readings import remake_page as remake_readings_page

    preset = described.study.name
    if not described.page:
        raise InputError(f"the {preset} study has no page in docs/ (its file's page)")
    own = [described.page, *described.readings]
    if out is None:
        own = require_page(described, described.page, *described.readings)
    if described.kind in READINGS_KINDS:
        return remake_readings_page(preset, described, out)
    tables = study_docs(described.page)
    if not (tables / "study.json").is_file():
        raise InputError(f"{preset}: {tables} holds no study's tables")
    readings = {n: study_docs(n) for n in described.readings}
    for name, folder in readings.items():  # the page would lose its row
        if not (folder / "impacts.csv").is_file():
            raise InputError(
                f"{described.path}: readings names {name}, but {folder} holds no tables "
                f"(python -m runner study {preset} --name {name} --docs makes them)"
            )
    if out is None:
        for name, folder in readings.items():
            if name in own:  # another study's own tables are its to tidy
                tidy_tables(folder)
    page = out / f"{described.page}.md" if out else study_page(described.page)
    report_from_tables(
        tables,
        page,
        preset=preset,
        out=out or tables,
        readings=readings,
        sections=described.sections or None,
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


def remake_tabulating_page(described: StudyFile, readings: dict[str, Path]) -> None:
    """The study's page in docs/studies/ again from its committed tables,
    with the table of its readings."""
    from pages.report import report_from_tables

    page = study_page(described.page)
    report_from_tables(
        page.parent,
        page,
        preset=described.study.name,
        readings=readings,
        sections=described.sections or None,
    )
    print(f"its row is on {shown(page)}")
