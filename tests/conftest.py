"""Shared fixtures: small scenes. Helpers that are not fixtures are in
tests/helpers.py."""

from __future__ import annotations

import shutil

import pytest

from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from tests.helpers import RUNS, SMALL


def pytest_sessionfinish(session, exitstatus):
    shutil.rmtree(RUNS, ignore_errors=True)


@pytest.fixture(scope="session")
def small_scene():
    return build_scene(SceneSpec(gamma_deg=30.0, **SMALL))


@pytest.fixture(scope="session")
def small_scene_dir(tmp_path_factory, small_scene):
    # class2: the tests that read it name that bond style in their decks
    return write_scene(small_scene, tmp_path_factory.mktemp("scene"), "class2")
