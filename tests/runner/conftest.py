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
