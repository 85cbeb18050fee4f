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


# make test runs the tests on two processes (pytest-xdist, --dist loadgroup):
# each module whole on one of them, so that its module fixtures (LAMMPS runs)
# are made once, and the modules that read the committed docs while the
# pages are made again (the docs group) on the pages' own process, one after
# another. The tests that watch the whole tree (marked tree) run after them,
# and those that put files into studies/ (marked writes_tree) last (Makefile).
DOCS_GROUP = {
    "tests/docs/test_pages_reproducible.py",  # makes every page again, in place
    "tests/runner/study/test_readings_studies.py",  # reads those pages' bytes
    "tests/analysis/test_speed_study.py",  # docs' times before and after
    "tests/runner/study/test_study_folder.py",
    "tests/bench/test_bench_scripts.py",
}


@pytest.hookimpl(tryfirst=True)  # before xdist's own, which reads the groups
def pytest_collection_modifyitems(config, items):
    for item in items:
        # the refusals (marked tree) share no costly fixture: one by one
        if item.get_closest_marker("xdist_group") is None and not item.get_closest_marker("tree"):
            module = item.nodeid.split("::")[0]
            group = "docs" if module in DOCS_GROUP else module
            item.add_marker(pytest.mark.xdist_group(group))


@pytest.fixture(scope="session")
def small_scene():
    return build_scene(SceneSpec(gamma_deg=30.0, **SMALL))


@pytest.fixture(scope="session")
def small_scene_dir(tmp_path_factory, small_scene):
    # class2: the tests that read it name that bond style in their decks
    return write_scene(small_scene, tmp_path_factory.mktemp("scene"), "class2")
