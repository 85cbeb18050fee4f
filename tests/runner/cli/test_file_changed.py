"""A study file against what its study was first run with
(runner.cli.study_args.file_changed): a run option added since is read as
its record from before, not as a change."""

from __future__ import annotations

import json

import pytest

from ground.errors import InputError
from runner.cli.study_args import file_changed
from runner.study import Study


def recorded_before_the_option(name: str) -> tuple[dict, dict]:
    """(the source as a study.json from before ``name`` existed records it,
    what the same file says today)."""
    said = json.loads(json.dumps(Study("probe").grid()))  # as study.json holds it
    source = {**said, "options": {k: v for k, v in said["options"].items() if k != name}}
    return source, said


def test_an_option_added_since_is_no_change():
    source, said = recorded_before_the_option("barrier_halvings")
    assert file_changed(source, said, False, "probe", "probe.toml") == {}


def test_an_option_added_since_and_given_otherwise_is_refused():
    source, said = recorded_before_the_option("barrier_halvings")
    said["options"]["barrier_halvings"] = 0
    with pytest.raises(InputError, match=r"options.barrier_halvings 2 then, 0 now"):
        file_changed(source, said, False, "probe", "probe.toml")


def test_extend_never_takes_a_level_below_what_the_file_said_or_what_ran():
    """A resolution level whose file said 80 seeds and which ran 48 (thinned):
    --extend takes 80 -> 100, a listed 48 -> 60 where 48 is what it said,
    never 80 -> 60 (its thinned plan would run fewer than ran)."""
    said = json.loads(json.dumps(Study("probe", samples=80).grid()))
    assert file_changed(said, {**said, "samples": 100}, True, "p", "p.toml", 48) == {"samples": 100}
    listed = {**said, "samples": 48}
    assert file_changed(listed, {**said, "samples": 60}, True, "p", "p.toml", 48) == {"samples": 60}
    with pytest.raises(InputError, match="samples 80 then, 60 now"):
        file_changed(said, {**said, "samples": 60}, True, "p", "p.toml", 48)
