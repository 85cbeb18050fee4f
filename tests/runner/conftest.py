"""The tiny study, run once for the tests of this folder that read it."""

from __future__ import annotations

import subprocess

import pytest

from tests.helpers import RUNS
from tests.runner.tiny_study import study, table


@pytest.fixture(scope="package")
def uninterrupted():
    name = "test_study_whole"
    subprocess.run(["rm", "-rf", str(RUNS / name)])
    proc = study(name)
    assert proc.returncode == 0, proc.stderr
    return table(name)


def pytest_collection_modifyitems(items):
    # a test that takes the tiny study waits for its LAMMPS runs, alone or first
    for item in items:
        if "uninterrupted" in item.fixturenames:
            item.add_marker(pytest.mark.lammps)
            item.add_marker(pytest.mark.slow)
