"""`oblique-impact`, the one command (runner/cli/console.py): each subcommand is its
`python -m` entry point, and a bad one is refused in one line."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from runner.cli.console import COMMANDS, benchmarks
from tests.helpers import ROOT

SCRIPT = Path(sys.executable).with_name("oblique-impact")

# (the console's words, the python -m form they stand for): both must give
# the same one-line refusal of the same bad value
SAME = [
    (["scene", "--gamma", "95"], ["-m", "builder", "scene", "--gamma", "95"]),
    (["impact", "--dt", "0"], ["-m", "runner", "impact", "--dt", "0"]),
    (["study", "no-such-study"], ["-m", "runner", "study", "no-such-study"]),
    (["page", "demo"], ["-m", "runner", "page", "demo"]),
    (["calibrate", "--seeds", "0"], ["-m", "calibration", "run", "--seeds", "0"]),
    (["validate", "--out", "/proc/x"], ["-m", "bench.validation", "--out", "/proc/x"]),
    (["bench", "loop_floor", "--repeats", "0"], ["-m", "bench.loop_floor", "--repeats", "0"]),
]


def run(command: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run(command, cwd=ROOT, capture_output=True, text=True)


def test_the_command_is_installed():
    assert SCRIPT.is_file() or shutil.which("oblique-impact"), "make setup installs it"


@pytest.mark.parametrize(("words", "module_form"), SAME, ids=lambda x: " ".join(x))
def test_a_subcommand_is_its_entry_point(words, module_form):
    ours, theirs = run([str(SCRIPT), *words]), run([sys.executable, *module_form])
    assert ours.returncode == theirs.returncode == 2
    # the same message, whatever program name each prints first
    assert ours.stderr.split("error:", 1)[1] == theirs.stderr.split("error:", 1)[1]
    assert len(ours.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("words", [["nope"], ["bench", "nope"]])
def test_a_bad_command_is_one_line(words):
    proc = run([str(SCRIPT), *words])
    assert proc.returncode == 2 and proc.stderr.startswith("oblique-impact: error: ")
    assert len(proc.stderr.strip().splitlines()) == 1 and not proc.stdout


def test_help_names_every_command_and_benchmark():
    proc = run([str(SCRIPT), "--help"])
    assert proc.returncode == 0
    assert all(name in proc.stdout for name in COMMANDS)
    assert all(name in proc.stdout for name in benchmarks()) and "common" not in benchmarks()


@pytest.mark.parametrize("command", ["impact", "run", "study"])
def test_help_fits_a_screen_and_help_all_shows_every_option(command):
    short = run([str(SCRIPT), command, "--help"])
    full = run([str(SCRIPT), command, "--help-all"])
    assert short.returncode == full.returncode == 0
    # named as typed, opening with what the command does, on one screen
    assert short.stdout.startswith(f"usage: oblique-impact {command} ")
    assert len(short.stdout.splitlines()) <= 60
    more = short.stdout.strip().splitlines()[-1]
    assert more.endswith(f"oblique-impact {command} --help-all")
    options, shown = (
        set(re.findall(r"^  (?:-\w, )?(--[\w-]+)", p.stdout, re.M)) for p in (full, short)
    )
    # every option is in the full help; the short one says how many it leaves out
    hidden = options - shown
    assert hidden and int(more.split()[0]) == len(hidden)
    assert ("--np" in options) == (command != "study")  # a study's impacts take --ranks
    assert ("--wall-fixed" in options) == (command != "run")


def test_bench_lists_each_benchmark_with_what_it_measures():
    proc = run([str(SCRIPT), "bench"])
    assert proc.returncode == 2  # no NAME: the list, and a usage error's status
    rows = {line.split()[0]: line for line in proc.stdout.splitlines()[2:]}
    assert sorted(rows) == benchmarks()
    assert all(len(line.split(maxsplit=1)) == 2 for line in rows.values())  # a line each
    assert "the contact costs" in rows["contact_cost"]
