"""Each option declared once (builder/declared.py): SceneSpec's and
RunOptions's fields and checks, the command lines, a study file's keys and
the "made by" command line all follow from builder.scene.SCENE_OPTIONS and
builder.run_options.RUN_OPTIONS; studies are data read on demand."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from dataclasses import fields

import pytest

from builder.__main__ import parser as builder_parser
from builder.run_options import RUN_OPTIONS
from builder.scene import SCENE_OPTIONS, SceneSpec
from ground.errors import InputError
from pages.command import made_by
from runner.__main__ import parser as runner_parser
from runner.options import RunOptions
from runner.study import STUDY_SCENE, Study
from runner.values import VALUES
from tests.helpers import ROOT


def outside(option) -> float:
    """A number just outside the option's range (above it, or below it)."""
    numbers = option.scene_numbers or option.numbers
    if numbers.high is not None:
        return numbers.high * 2 + 1
    return numbers.low - 1


def test_the_dataclasses_fields_are_the_declarations():
    assert [f.name for f in fields(SceneSpec)] == [o.name for o in SCENE_OPTIONS]
    assert [f.name for f in fields(RunOptions)] == [o.name for o in RUN_OPTIONS]
    assert SceneSpec() == SceneSpec(**{o.name: o.default for o in SCENE_OPTIONS})
    scene = {f.name for f in fields(Study)} - {"name", "options", "source"}
    assert {o.name for o in STUDY_SCENE} <= scene and set(VALUES["scene"]) == {
        o.name for o in STUDY_SCENE
    }


@pytest.mark.parametrize(
    "option", [o for o in SCENE_OPTIONS if o.numbers is not None], ids=lambda o: o.name
)
def test_a_scene_number_outside_its_range_is_refused_by_the_scene_and_the_command_line(option):
    bad = outside(option)
    with pytest.raises(InputError, match=rf"^{option.name} must be"):
        SceneSpec(**{option.name: bad}).validate()
    if option.cli:
        with pytest.raises(SystemExit) as stop:
            builder_parser().parse_args(["scene", "--out", "x", option.option, str(bad)])
        assert stop.value.code == 2
    if option.study:
        with pytest.raises(InputError, match=rf"^{option.name} must be"):
            VALUES["scene"][option.name].check(option.name, bad)


@pytest.mark.parametrize(
    "option", [o for o in RUN_OPTIONS if o.numbers is not None], ids=lambda o: o.name
)
def test_a_run_number_outside_its_range_is_refused_by_the_options_and_the_command_line(option):
    bad = outside(option)
    with pytest.raises(InputError, match=rf"^{option.name} must be"):
        RunOptions(**{option.name: bad}).validate()
    if option.cli:
        with pytest.raises(SystemExit) as stop:
            runner_parser().parse_args(["impact", option.option, str(bad)])
        assert stop.value.code == 2


def test_made_by_gives_each_committed_pages_command():
    """The "made by" line that pages.command derives from the declarations
    is, for every committed results page, the line the page states."""
    checked = 0
    for page in sorted((ROOT / "docs" / "studies").glob("*/*.md")):
        said = re.search(r"Made by `(python -m runner study (\S+) [^`]*)`", page.read_text())
        record = page.parent / "study.json"
        if said and record.is_file():
            assert made_by(json.loads(record.read_text()), said[2]) == said[1], page.name
            checked += 1
    assert checked >= 4


def test_reading_a_study_file_imports_nothing_of_analysis_and_fills_no_registry():
    code = (
        "import sys\n"
        "import runner.study\n"
        "from runner.study.studies import all_studies, load_study\n"
        "files = all_studies()\n"
        "assert load_study('paper') == files['paper'].study\n"
        "assert load_study('paper') is not load_study('paper')\n"
        "assert not hasattr(runner.study, 'PRESETS')\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'analysis'))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert done.stdout.strip() == "[]"


@pytest.mark.parametrize("module", ["runner.study.file", "runner.study", "runner.study.studies"])
def test_each_study_module_imports_first_without_a_circle(module):
    """Imported first in a fresh interpreter: a circle would fail on a name
    of the half-made module."""
    subprocess.run([sys.executable, "-c", f"import {module}"], cwd=ROOT, check=True)
