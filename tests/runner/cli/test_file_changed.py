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


def test_extend_adds_angles_and_retries_never_removes_them():
    """The sliding branch's file, grown by an angle and a larger retry budget:
    --extend takes both (the done impacts stay valid); an angle dropped, or
    an option that changes how an impact runs, is refused either way."""
    said = json.loads(json.dumps(Study("probe", angles=2, cot_gamma=(1.0, 0.05)).grid()))
    grown = json.loads(json.dumps(Study("probe", angles=3, cot_gamma=(1.0, 0.05, 0.035)).grid()))
    grown["options"]["barrier_halvings"] = 4
    changed = file_changed(said, grown, True, "p", "p.toml")
    assert set(changed) == {"angles", "cot_gamma", "options"}
    with pytest.raises(InputError, match="--extend takes more samples, lattices or angles"):
        file_changed(said, grown, False, "p", "p.toml")
    dropped = {**grown, "cot_gamma": [1.0, 0.035]}
    with pytest.raises(InputError, match=r"cot_gamma \[1.0, 0.05\] then, \[1.0, 0.035\] now"):
        file_changed(said, dropped, True, "p", "p.toml")
    other_step = json.loads(json.dumps(grown))
    other_step["options"]["dt"] = 0.004
    with pytest.raises(InputError, match="options.dt"):
        file_changed(said, other_step, True, "p", "p.toml")
