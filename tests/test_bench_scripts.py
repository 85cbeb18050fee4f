"""Every benchmark script starts, and refuses bad input as the entry points do.

The benchmarks are not run by the tests (they time things), so a script
whose imports broke would otherwise go unnoticed until someone ran it. Each
answers --help; every option it has checks its value (a Range, a list of
choices, a path that must exist or can be written, or a flag); and every
bad value, or bad combination, exits 2 with one line on stderr that names
the option, before anything is written into docs/ or runs/.
"""

import argparse
import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

from builder.checks import InPath, OutFolder, Range

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted(p for p in (ROOT / "bench").glob("*.py") if p.name != "common.py")
# Text a number option is fed; those its Range takes are left out per option.
NUMBERS = ("nan", "inf", "1e300", "-1", "0", "1.5", "x", "")
# A bad combination per script that has one, with the option the line must name.
COMBINATIONS = [
    (
        "drift_tail.py",
        ["--impacts", "docs/results/impacts.csv", "--dts", "0.002", "0.002"],
        "--dts",
    ),
    ("drift_tail.py", ["--impacts", "docs/results/impacts.csv", "--worst", "10000"], "--worst"),
    ("drift_tail.py", ["--impacts", "README.md"], "--impacts"),
    ("inside_wall.py", ["--docs"], "--docs"),
    ("large_disk.py", ["--ranks", "1", "1"], "--ranks"),
    ("roughness.py", ["--docs"], "--docs"),
    ("roughness.py", ["--first-seed", str(2**32 - 1), "--seeds", "2"], "--first-seed"),
    ("scene_readings.py", ["--from-csv", "--samples", "3"], "--samples"),
    ("scene_readings.py", ["--from-csv", "--top", "2"], "--top"),
    ("scene_readings.py", ["--docs", "--out", "{tmp}"], "--out"),
    ("scene_readings.py", ["--top-samples", "40"], "--top-samples"),
    ("scene_readings.py", ["--top", "2", "--top-samples", "6"], "--top-samples"),
    ("spring_cost.py", ["--docs", "--no-write"], "--no-write"),
    ("time_vs_error.py", ["--summarise", "--only", "verlet"], "--only"),
    ("time_vs_error.py", ["--summarise", "--out", "{tmp}"], "--summarise"),
    ("wall_width.py", ["--angles", "60", "60"], "--angles"),
    ("wall_width.py", ["--widths", "8", "8"], "--widths"),
]
# What an option needs besides the one under test.
REQUIRED = {"drift_tail.py": ["--impacts", "docs/results/impacts.csv"]}
# What starts the work of a benchmark or writes its page: a case that reached
# one of them was not refused, and stops there rather than running for hours.
WORK = (
    "build_scene",
    "run_study",
    "run_scene",
    "run_impact",
    "run_lmp",
    "run",
    "survey",
    "measure",
    "write_report",
    "write_table",
    "write_csv",
    "draw",
    "plot",
    "write_scene",
    "ProcessPoolExecutor",
)


class Started(BaseException):
    """A benchmark got past its checks (BaseException: no script catches it)."""


def load(script: Path, guarded: bool = False):
    """The script as a module (its `from common import ...` needs bench/ on the
    path); ``guarded``: with its WORK replaced by a stop."""
    if str(ROOT / "bench") not in sys.path:
        sys.path.insert(0, str(ROOT / "bench"))
    spec = importlib.util.spec_from_file_location(f"bench_{script.stem}", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name in WORK if guarded else ():
        if hasattr(module, name):

            def stop(*args, name=name, **kwargs):
                raise Started(f"{script.name} reached {name}")

            setattr(module, name, stop)
    return module


def options(script: Path) -> list[argparse.Action]:
    return [a for a in load(script).parser()._actions if not isinstance(a, argparse._HelpAction)]


def bad_values(action: argparse.Action, tmp: Path) -> list[str]:
    """Values the option must refuse."""
    if action.choices is not None:
        return ["no-such-choice", ""]
    if isinstance(action.type, Range):
        return [text for text in NUMBERS if not _takes(action.type, text)]
    if isinstance(action.type, InPath):
        (tmp / "a_file").write_text("")
        return [str(tmp / "missing"), str(tmp / "a_file" / "below")]
    if isinstance(action.type, OutFolder):
        (tmp / "a_file").write_text("")
        # a space only where LAMMPS takes the path
        spaced = [str(tmp / "a b")] if action.type.lammps else []
        return ["/proc/x", str(tmp / "a_file" / "below"), *spaced, ""]
    # a checking function of the script's own (--n-wall, --name, --only, ...)
    return [text for text in (*NUMBERS, "../x", "a b") if not _takes(action.type, text)]


def _takes(check, text: str) -> bool:
    try:
        check(text)
    except (argparse.ArgumentTypeError, ValueError):
        return False
    return True


def listing() -> dict[str, tuple[int, int]]:
    """Size and mtime of every file a benchmark could write: docs/, runs/bench/
    and runs/'s own entries (the study benchmarks' folders)."""
    files = {}
    for folder in (ROOT / "docs", ROOT / "runs" / "bench"):
        for path in folder.rglob("*") if folder.is_dir() else ():
            stat = path.stat()
            files[str(path)] = (stat.st_size, stat.st_mtime_ns)
    runs = ROOT / "runs"
    for path in runs.iterdir() if runs.is_dir() else ():
        files[str(path)] = (0, path.stat().st_mtime_ns)
    return files


def refused(script: Path, argv: list[str], capsys) -> list[str]:
    """The lines on stderr of a run that must stop with exit status 2."""
    module = load(script, guarded=True)
    capsys.readouterr()
    try:
        status = module.main(argv)
    except SystemExit as stop:
        status = stop.code
    except Started as started:
        pytest.fail(f"{argv} was not refused: {started}")
    captured = capsys.readouterr()
    assert status == 2, (argv, captured.out[-300:], captured.err[-300:])
    return captured.err.strip().splitlines()


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_bench_script_answers_help(script):
    proc = subprocess.run(
        [sys.executable, str(script), "--help"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr[-500:]
    assert proc.stdout.startswith("usage:")
    assert "--docs" in proc.stdout


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_every_option_checks_its_value(script):
    """A flag, a list of choices, or a type that refuses (no bare int, float, str)."""
    for action in options(script):
        flag = isinstance(action, (argparse._StoreTrueAction, argparse._StoreFalseAction))
        assert flag or action.choices is not None or action.type not in (None, int, float, str), (
            f"{script.name} {action.option_strings} takes any value"
        )
        if isinstance(action.type, Range):  # 1e300 refused too
            assert action.type.high is not None, f"{script.name} {action.option_strings}"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_bad_values_are_refused_before_anything_is_written(script, tmp_path, capsys):
    before = listing()
    cases = 0
    for action in options(script):
        name = action.option_strings[-1]
        for value in bad_values(action, tmp_path) if action.nargs != 0 else ():
            lines = refused(script, [*REQUIRED.get(script.name, []), name, value], capsys)
            assert len(lines) == 1 and name in lines[0], (name, value, lines)
            cases += 1
    assert listing() == before
    assert not (tmp_path / "a b").exists()
    if script.name != "stability.py":  # its only option is --docs
        assert cases >= 4


@pytest.mark.parametrize(
    "name, argv, option", COMBINATIONS, ids=lambda x: x if isinstance(x, str) else None
)
def test_options_that_do_not_go_together_are_refused(name, argv, option, tmp_path, capsys):
    before = listing()
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    lines = refused(ROOT / "bench" / name, argv, capsys)
    assert len(lines) == 1 and option in lines[0], lines
    assert listing() == before
    assert list(tmp_path.iterdir()) == []
