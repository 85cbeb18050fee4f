"""Bad input, second round (issue 36), of a run: its axes, what an earlier run
of the same name recorded, the run's options and the cluster's, each refused
before any work, as tests/runner/cli/test_refusals.py checks its cases (its
docstring says how)."""

from __future__ import annotations

import pytest

from tests.runner.cli import test_refusals as refusals
from tests.runner.cli.test_refusals import SMALL, Case, command, ran, study

# the whole tree watched: after the others, which write into it (Makefile)
pytestmark = pytest.mark.tree

# the module's fixtures, for these cases too
places, clean_tree = refusals.places, refusals.clean_tree

AXIS_CASES = [
    study(
        SMALL + "contact_a = [300.0, 400.0, 2.0]\n",
        "f.toml: combination f_contact_a-2: contact_a must make a R >= ",
        case="axis: the third value refused with the others",
    ),
    study(
        SMALL + "[run]\ncheck = [100, 3]\n",
        "combination f_check-3: check must be a multiple",
        case="axis: the second value refused with the first",
    ),  # fmt: skip
    study(
        'sweep = "one-at-a-time"\n' + SMALL + "roughness = [0.03, 0.06]\n[run]\ncheck = [100, 7]\n",
        "combination f_roughness-0.03_check-7: check must be a multiple of every",
        case="one at a time: the last combination refused before the first runs",
    ),
    study(
        SMALL + "wall_ka = [1.0, 2.0]\n",
        "f.toml: combination f_wall_ka-2: differs from what runs/f_wall_ka-2/ was first run with: "
        "wall_ka 3.0 then, 2.0 now",
        case="axis: a combination's folder holds another study",
        before={"f_wall_ka-2": ran("f_wall_ka-2", wall_ka=3.0)},
    ),
    study(
        SMALL + "wall_ka = [1.0, 2.0]\n",
        "--name f: ",
        case="axis: runs/<name>/ holds a study",
        before={"f": ran("f", source=False)},
    ),  # fmt: skip
    study(
        'kind = "wall_width"\n'
        + SMALL.replace("n_disk = 200\n", 'n_wall = "density"\n')
        + "wall_width = [8.0, 16.0]\n[run]\ncheck = 3\n",
        "f.toml: combination f_wall_width-8: check must be a multiple of every",
        case="readings study: a combination refused before the first runs",
    ),
]

RECORD_CASES = [
    study(
        SMALL + "wall_ka = 2.0\n",
        "f.toml: differs from what runs/f/ was first run with: "
        "wall_ka 1.0 then, 2.0 now; put the file back",
        case="file edited after its run",
        before={"f": ran("f", wall_ka=1.0)},
    ),  # fmt: skip
    study(
        SMALL.replace("samples = 1", "samples = 3"),
        "samples 1 then, 3 now; --extend takes more",
        case="file with more samples, no --extend",
        before={"f": ran("f")},
    ),  # fmt: skip
    study(
        SMALL,
        "samples 1 there, 40 asked; leave the option out",
        "--samples",
        "40",
        case="--samples 40 without --extend",
        before={"f": ran("f")},
    ),  # fmt: skip
    study(SMALL, "--extend: no study in", "--extend", case="--extend of no study"),
]

OPTION_CASES = [
    command("study demo --vn 0.5", "argument --vn: must be a number in (0, 0.3] (units of c)"),
    command("study demo --samples 2.0", "argument --samples: must be an integer in [1, 10000]"),
    command("study demo --name dup --lattices random random", "--lattices names a value twice"),
    command("study demo --name dup --cot-gamma 1 1.0000001", "cot_gamma names an impact's folder"),
    command("study demo --walltime 00:99:99", "argument --walltime: must be HH:MM:SS (MM and SS"),
    command("study demo --walltime 1-24:00:00", "argument --walltime: must be HH:MM:SS"),
    command("study demo --walltime 00:00:00", "longer than 00:00:00, got '00:00:00'"),
    command(
        "study demo --scheduler {tmp}/bad.json",
        "is not a Dask scheduler file",
        files={"bad.json": "{"},
    ),  # fmt: skip
    command(
        "study demo --scheduler {tmp}/empty.json",
        "is not a Dask scheduler file",
        files={"empty.json": "{}"},
    ),  # fmt: skip
    command(
        "study demo --scheduler {tmp}/n.json",
        "is not a Dask scheduler file",
        files={"n.json": '{"address": 3}'},
    ),  # fmt: skip
    command("study demo --scheduler tcp://host:99999", "argument --scheduler: must be a Dask"),
    command("study demo --scheduler tcp://h:1 --cluster slurm", "--scheduler joins a running"),
    command("study demo --jobs 2", "--jobs applies to --cluster slurm only"),
]

TINY = "study demo --samples 1 --angles 2 --n-disk 200 --name {name}"
CLUSTER_CASES = [
    Case(
        "sbatch missing",
        (TINY + " --cluster slurm").split(),
        "sbatch is not on PATH",
        env={"PATH": "{empty}"},
        subprocess=True,
        name="c_missing",
    ),  # fmt: skip
    Case(
        "sbatch failing",
        (TINY + " --cluster slurm").split(),
        "sbatch refuses the job: sbatch: error: Batch job submission failed: Invalid account",
        env={"PATH": "{fake_sbatch}"},
        subprocess=True,
        name="c_failing",
    ),  # fmt: skip
    Case(
        "scheduler answers garbage",
        (TINY + " --scheduler {garbage}").split(),
        "cannot join it",
        subprocess=True,
        name="c_garbage",
    ),  # fmt: skip
    Case(
        "scheduler unreachable",
        (TINY + " --scheduler tcp://127.0.0.1:{closed_port}").split(),
        "cannot join it (Timed out trying to connect",
        name="c_unreachable",
    ),  # fmt: skip
    Case(
        "scheduler file unreachable",
        (TINY + " --scheduler {tmp}/s.json").split(),
        "cannot join it",
        {"s.json": '{"address": "tcp://127.0.0.1:{closed_port}"}'},
        name="c_unreachable_file",
    ),  # fmt: skip
]

CASES = AXIS_CASES + RECORD_CASES + OPTION_CASES + CLUSTER_CASES


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_refused_before_any_work(case, places, clean_tree, tmp_path, monkeypatch, capsys):
    refusals.refused_before_any_work(case, places, clean_tree, tmp_path, monkeypatch, capsys)
