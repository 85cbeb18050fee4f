"""The tests' tiny study: the command, its table, the columns compared
(tests/runner/study/test_study.py, test_study_folder.py; conftest.py runs it once)."""

from __future__ import annotations

import csv
import subprocess
import sys

from tests.helpers import ROOT, RUNS

# SMALL's scene (tests/helpers.py): the 200-point disk on the 1,600-point wall, the paper's contact
# and roughness
TINY = ["--lattices", "random", "--angles", "3", "--samples", "2", "--n-disk", "200"]
TINY += ["--n-wall", "1600", "--contact-scaling", "fixed", "--roughness-length", "0"]
TINY += ["--roughness-profile", "sampled", "--area-floor", "0"]
COMPARED = (
    "study_lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "e",
    "beta",
    "omega",
    "steps",
    "contact_time",
)


def study(name: str, *extra: str, wait: bool = True):
    command = [sys.executable, "-m", "runner", "study", "demo", "--name", name, *TINY, *extra]
    if wait:
        return subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    return subprocess.Popen(
        command,
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )


def table(name: str) -> list[tuple]:
    with (RUNS / name / "impacts.csv").open() as handle:
        return [tuple(row[c] for c in COMPARED) for row in csv.DictReader(handle)]
