"""Every option of every entry point refuses bad values the same way.

The entry points: python -m runner, builder, calibration and reference, and
every script under bench/.

The cases are made from the parsers themselves, so an option added later is
covered without a line here, and an option whose type this test cannot feed
bad values fails it (``test_every_option_is_validated``). Each case must exit
with status 2 and one line on stderr that names the option, start no work,
and leave the project's tree and the output folder as they were.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from ground.checks import InPath, OutFolder, Range
from ground.paths import ROOT
from tests.helpers import RUNS

# the whole tree watched: after the others, which write into it (Makefile)
pytestmark = pytest.mark.tree

BENCH = ROOT / "bench"

# The values of the table: the non-finite ones and a word are bad for
# every number; the others are cases where the option's stated bounds
# exclude them (read from its Range's bounds, not from its own check).
NEVER = ("nan", "inf", "-inf", "abc")
NUMBERS = ("-1", "0", "1e300")
# What an entry point calls to start its work: any call of these fails a case.
WORK = (
    "run_impact",
    "run_scene",
    "run_study",
    "dask_client",
    "build_scene",
    "write_scene",
    "run_lmp",
    "run_python",
    "calibrate",
    "run_stretch",
    "run_reference",
    "report",
    "report_from_tables",
    "table_text",
    # the benchmarks' own
    "run",
    "survey",
    "measure",
    "write_report",
    "write_table",
    "write_csv",
    "draw",
    "plot",
    "ProcessPoolExecutor",
)
# Folders that the tree's listing leaves out: git's, the environments', caches.
# The clone's runs/ is left out too: the tests' runs go to RUNS ($IMPACT_RUNS),
# listed on its own, and a study running beside the tests may write runs/.
UNLISTED = {".git", ".venv", ".venv-pypi", "__pycache__", ".pytest_cache", ".ruff_cache"}
UNLISTED_HERE = {"runs"}


class WorkStarted(Exception):
    pass


@dataclass
class EntryPoint:
    name: str  # as the user types it
    module: str  # the module with parser() and main()
    base: dict  # subcommand (or "") -> the arguments of a valid command

    def load(self):
        return importlib.import_module(self.module)


# What a benchmark needs besides the option under test.
BENCH_BASE = {
    "drift_tail": ["--impacts", str(ROOT / "docs" / "studies" / "results" / "impacts.csv")],
    "paper_ensemble": ["--before", "HEAD"],
}


def bench_entry_points() -> list[EntryPoint]:
    return [
        EntryPoint(f"bench/{p.name}", f"bench.{p.stem}", {"": BENCH_BASE.get(p.stem, [])})
        for p in sorted(BENCH.glob("*.py"))
        if p.name not in ("common.py", "__init__.py")
    ]


ENTRY_POINTS = [
    EntryPoint(
        "python -m runner",
        "runner.__main__",
        {
            "impact": ["impact", "--out", "{out}"],
            "run": ["run", "{scene}"],
            "study": ["study", "demo", "--name", "bad_input_probe"],
            "page": ["page", "speed", "--out", "{out}"],
            "tilt": ["tilt", "--out", "{out}"],
        },
    ),
    EntryPoint(
        "python -m builder",
        "builder.__main__",
        {"scene": ["scene", "--out", "{out}"], "table": ["table", "--out", "{out}"]},
    ),
    EntryPoint(
        "python -m calibration",
        "calibration.__main__",
        {"run": ["run", "--out", "{out}"], "strip": ["strip", "--out", "{out}"]},
    ),
    EntryPoint(
        "python -m reference",
        "reference.__main__",
        {"run": ["run", "{scene}"]},
    ),
    *bench_entry_points(),
]


def subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """{subcommand: its parser}, or {"": parser} for a parser without subcommands."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {"": parser}


def option_name(action: argparse.Action) -> str:
    return action.option_strings[-1] if action.option_strings else action.dest


def outside(numbers: Range, value: float) -> bool:
    low, high = numbers.low, numbers.high
    below = low is not None and (value <= low if numbers.low_open else value < low)
    above = high is not None and (value >= high if numbers.high_open else value > high)
    return below or above


def bad_numbers(numbers: Range) -> list[str]:
    values = list(NEVER) + [v for v in NUMBERS if outside(numbers, float(v))]
    return values + (["1.5"] if numbers.integer else [])


def bad_values(action: argparse.Action) -> list[str] | None:
    """The texts this option must refuse; None if the test cannot tell."""
    kind = action.type
    if action.choices is not None:
        return ["no-such-choice"]
    if isinstance(kind, Range):
        return bad_numbers(kind)
    if hasattr(kind, "numbers"):  # a number, or one of a few words
        return bad_numbers(kind.numbers)
    if hasattr(kind, "bad_values"):
        return list(kind.bad_values)
    if isinstance(kind, OutFolder):  # a space is bad only where LAMMPS reads the path
        return ["{unwritable}/x", "{file}/x", "/proc/x"] + (["{tmp}/a b"] if kind.lammps else [])
    if isinstance(kind, InPath):
        return ["{tmp}/missing", "{file}/x"]
    return None


def cases() -> list[tuple]:
    out = []
    for entry in ENTRY_POINTS:
        for command, sub in subparsers(entry.load().parser()).items():
            for action in sub._actions:
                if action.nargs == 0 or isinstance(action, argparse._SubParsersAction):
                    continue  # flags and --help take no value
                if action.dest == "preset":
                    continue  # a subcommand's choice of preset, fed below as a choice
                for value in bad_values(action) or []:
                    label = f"{entry.name} {command} {option_name(action)} {value}".strip()
                    out.append(pytest.param(entry, command, action, value, id=label))
    return out


def listing(folder: Path) -> dict[str, tuple]:
    """Every file and folder under ``folder`` with its size and modification time."""
    found = {}
    for base, dirs, files in os.walk(folder):
        dirs[:] = [
            d for d in dirs if d not in UNLISTED and not (Path(base) == ROOT and d in UNLISTED_HERE)
        ]
        for name in dirs + files:
            path = Path(base, name)
            stat = path.lstat()
            found[str(path.relative_to(folder))] = (stat.st_size, stat.st_mtime_ns)
    return found


@pytest.fixture
def places(tmp_path):
    """The folders and files the cases name: a scene folder (its files are
    never read: a bad option is refused first), a file, an unwritable folder."""
    scene = tmp_path / "scene"
    scene.mkdir()
    for name in ("scene.data", "scene.lmp", "scene.json"):
        (scene / name).write_text("")
    (tmp_path / "file").write_text("")
    # root may write into a folder without write permission: /sys is read-only
    # to it in a container, a folder without permission is to anyone else
    if os.geteuid() == 0:
        unwritable = Path("/sys")
    else:
        unwritable = tmp_path / "locked"
        unwritable.mkdir(mode=0o555)
    return {
        "tmp": str(tmp_path),
        "out": str(tmp_path / "out"),
        "scene": str(scene),
        "file": str(tmp_path / "file"),
        "unwritable": str(unwritable),
    }


def no_work(monkeypatch, module) -> None:
    """Make every function that starts work raise WorkStarted, wherever it was imported."""

    def refuse(*args, **kwargs):
        raise WorkStarted

    modules = [module] + [
        sys.modules[name]
        for name in (
            "runner.impact",
            "runner.cli.parser",
            "runner.study",
            "runner.cli.study_args",
            "runner.cli.study",
            "runner.study.outputs",
            "runner.study.readings",
            "runner.cluster.driver",
            "runner.cluster.workers",
            "ground.launch",
            "builder.assembly",
            "pages.report",
            "calibration.table",
            "calibration.stretch",
            "reference.run",
        )
        if name in sys.modules
    ]
    for each in modules:
        for name in WORK:
            if callable(getattr(each, name, None)):
                monkeypatch.setattr(each, name, refuse)


@pytest.mark.parametrize("entry, command, action, value", cases())
def test_bad_value_is_refused(entry, command, action, value, places, monkeypatch, capsys):
    module = entry.load()
    no_work(monkeypatch, module)
    argv = [a.format(**places) for a in entry.base[command]]
    option = option_name(action)
    value = value.format(**places)
    if action.option_strings:
        argv += [option, value]
    else:  # a positional: the bad value takes its place in the valid command
        argv = [value if a == places["scene"] else a for a in argv]
    tree, runs, out = listing(ROOT), listing(RUNS), listing(Path(places["tmp"]))
    try:
        status = module.main(argv)
    except SystemExit as stop:
        status = stop.code
    except WorkStarted:
        pytest.fail(f"{' '.join(argv)}: accepted, work started")
    errors = capsys.readouterr().err.strip()
    assert status == 2, f"{' '.join(argv)}: exit {status}, stderr {errors!r}"
    assert len(errors.splitlines()) == 1, errors
    assert option in errors, f"the message does not name {option}: {errors}"
    assert listing(ROOT) == tree, "the project's tree changed"
    assert listing(RUNS) == runs, "the runs' folder changed"
    assert listing(Path(places["tmp"])) == out, "the output folder changed"


def test_every_option_is_validated():
    """No option takes a value the test cannot check: each is a Range with
    both bounds, a choice, a folder, or a type that names its bad values."""
    unchecked = []
    for entry in ENTRY_POINTS:
        for command, sub in subparsers(entry.load().parser()).items():
            for action in sub._actions:
                if action.nargs == 0 or isinstance(action, argparse._SubParsersAction):
                    continue
                kind = getattr(action.type, "numbers", action.type)
                if bad_values(action) is None or (
                    isinstance(kind, Range) and (kind.low is None or kind.high is None)
                ):
                    unchecked.append(f"{entry.name} {command} {option_name(action)}")
    assert not unchecked, f"options without validation: {unchecked}"


def test_the_cases_cover_every_entry_point():
    """Every entry point with an option that takes a value has cases."""
    covered = {case.values[0].name for case in cases()}
    valued = {
        entry.name
        for entry in ENTRY_POINTS
        for sub in subparsers(entry.load().parser()).values()
        for action in sub._actions
        if action.nargs != 0 and not isinstance(action, argparse._SubParsersAction)
    }
    assert covered == valued
