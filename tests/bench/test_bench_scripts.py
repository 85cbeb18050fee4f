"""Every benchmark script starts, and refuses options that do not go together.

The benchmarks are not run by the tests (they time things), so a script
whose imports broke would otherwise go unnoticed until someone ran it. Each
answers --help; every bad combination of options exits 2 with one line on
stderr that names the option, before anything is written into docs/ or
runs/. Bad values of single options: tests/runner/cli/test_bad_input.py, which covers
the benchmarks with every other entry point.
"""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

from ground.paths import ROOT
from tests.helpers import RUNS

# reads the committed pages' bytes or times, which the pages made again
# rewrite: after them (Makefile)
pytestmark = pytest.mark.last

SCRIPTS = sorted(
    p for p in (ROOT / "bench").glob("*.py") if p.name not in ("common.py", "__init__.py")
)
# A bad combination per script that has one, with the option the line must name.
COMBINATIONS = [
    (
        "drift_tail.py",
        ["--impacts", "docs/studies/results/impacts.csv", "--dts", "0.002", "0.002"],
        "--dts",
    ),
    (
        "drift_tail.py",
        ["--impacts", "docs/studies/results/impacts.csv", "--worst", "10000"],
        "--worst",
    ),
    ("drift_tail.py", ["--impacts", "README.md"], "--impacts"),
    ("large_disk.py", ["--ranks", "1", "1"], "--ranks"),
    ("resolution_cost.py", ["--sizes", "800", "1600", "800"], "--sizes"),
    ("resolution_cost.py", ["--ranks", "2", "2"], "--ranks"),
    ("roughness.py", ["--docs"], "--docs"),
    ("roughness.py", ["--first-seed", str(2**32 - 1), "--seeds", "2"], "--first-seed"),
    ("spring_cost.py", ["--docs", "--no-write"], "--no-write"),
    ("time_vs_error.py", ["--summarise", "--only", "verlet"], "--only"),
    ("time_vs_error.py", ["--summarise", "--out", "{tmp}"], "--summarise"),
]
# What an option needs besides the one under test.
REQUIRED = {"drift_tail.py": ["--impacts", "docs/studies/results/impacts.csv"]}
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
    """The script as a fresh module of its own (the package's stays as it is);
    ``guarded``: with its WORK replaced by a stop."""
    spec = importlib.util.spec_from_file_location(f"bench_{script.stem}", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for name in WORK if guarded else ():
        if hasattr(module, name):

            def stop(*args, name=name, **kwargs):
                raise Started(f"{script.name} reached {name}")

            setattr(module, name, stop)
    return module


def listing() -> dict[str, tuple[int, int]]:
    """Size and mtime of every file a benchmark could write: docs/, and the
    runs folder the tests give them (tests/helpers.RUNS, $IMPACT_RUNS)."""
    files = {}
    for folder in (ROOT / "docs", RUNS):
        for path in folder.rglob("*") if folder.is_dir() else ():
            stat = path.stat()
            files[str(path)] = (stat.st_size, stat.st_mtime_ns)
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
