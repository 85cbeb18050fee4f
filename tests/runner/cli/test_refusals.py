"""Bad input, second round (issue 36): study files, axes, pages, paths and the
cluster options, each refused before any work.

Every case is a command with the files it names; it must exit with status 2,
say one line naming the file and key or the option, write nothing (the
clone's ``git status``, the runs' folder and the case's own folder as they
were, no runs/<name>/), and start no work. The cases run in this process
(``main``), but those of the cluster, whose Dask and Slurm messages go to the
real stderr, which run as the user runs them.
"""

from __future__ import annotations

import importlib
import json
import os
import shutil
import socket
import subprocess
import sys
import threading
from dataclasses import asdict, dataclass, field
from pathlib import Path

import pytest

from tests.helpers import ROOT, RUNS
from tests.runner.cli.test_bad_input import WorkStarted, listing, no_work

# the whole tree watched: after the others, which write into it (Makefile)
pytestmark = pytest.mark.tree

DOCS = ROOT / "docs"
SMALL = '[grid]\nlattices = ["random"]\nangles = 2\nsamples = 1\n[scene]\nn_disk = 200\n'


@dataclass
class Case:
    id: str
    argv: list[str]  # {tmp}, {docs_link}, ... filled in from the case's folder
    says: str  # a fragment of the one line
    files: dict = field(default_factory=dict)  # name in the case's folder -> text (or bytes)
    env: dict = field(default_factory=dict)  # environment for the command
    module: str = "runner.__main__"
    subprocess: bool = False  # run as the user does (the cluster's cases)
    name: str = ""  # runs/<name>/ that must not exist afterwards
    before: dict = field(default_factory=dict)  # runs/<name>/ a run before left: record or link


def study(text: str, say: str, *options: str, name: str = "f", case: str = "", before=None) -> Case:
    """`runner study` of a file f.toml holding ``text``."""
    return Case(
        case or f"file {' '.join(text.split())[:70]}",
        ["study", f"{{tmp}}/{name}.toml", *options],
        say,
        {f"{name}.toml": text},
        name=name,
        before=before or {},
    )


def ran(name: str, source: bool = True, **grid) -> dict:
    """The study.json a run of a small study leaves (``source``: with what its
    file said, as this version records it)."""
    from runner.study import Study

    done = Study(name, lattices=("random",), angles=2, samples=1, n_disk=200, **grid)
    return {**asdict(done), "source": done.grid() if source else None}


def command(argv: str, say: str, case: str = "", **kwargs) -> Case:
    return Case(case or argv, argv.split(), say, **kwargs)


FILE_CASES = [
    # types, nesting, duplicates and ranges, as the command line's (runner/values.py)
    study('[grid]\nlattices = [["random"]]\n', "f.toml: [grid] lattices must be a list"),
    study('[grid]\nlattices = "random"\n', "[grid] lattices must be a list of distinct values"),
    study("[grid]\nlattices = []\n", "[grid] lattices must be a list of distinct values"),
    study('[grid]\nlattices = ["random", "random"]\n', "[grid] lattices names a value twice"),
    study('[grid]\nlattices = ["hexagonal"]\n', "got 'hexagonal'"),
    study("[grid]\nsamples = 2.0\n", "[grid] samples must be an integer in [1, 10000], got 2.0"),
    study('[grid]\nsamples = "2"\n', "[grid] samples must be an integer in [1, 10000], got '2'"),
    study("[grid]\nsamples = true\n", "[grid] samples must be an integer in [1, 10000], got True"),
    study("[grid]\nsamples = 0\n", "[grid] samples must be an integer in [1, 10000], got 0"),
    study("[grid]\nsamples = 100000\n", "[grid] samples must be an integer in [1, 10000]"),
    study(
        "[grid]\nsamples = [1, 2]\n",
        "[grid] samples as a list gives the seeds of each [scene] n_disk",
    ),
    study("[grid]\nangles = 1\n", "[grid] angles must be an integer in [2, 1000], got 1"),
    study("[grid]\nangles = 2.5\n", "[grid] angles must be an integer in [2, 1000], got 2.5"),
    study("[grid]\nfirst_seed = -1\n", "[grid] first_seed must be an integer in [0, 4294967295]"),
    study("[grid]\nfirst_seed = 1.0\n", "[grid] first_seed must be an integer in [0, 4294967295]"),
    study(
        "[grid]\nfirst_seed = 4294967290\nsamples = 10\n",
        "f.toml: first_seed + samples - 1 must be at most 4294967295 (the last seed), "
        "got 4294967290 + 10 - 1 = 4294967299",
    ),
    study("[grid]\nvn = 0.5\n", "[grid] vn must be a number in (0, 0.3] (units of c), got 0.5"),
    study("[grid]\nvn = 0\n", "[grid] vn must be a number in (0, 0.3]"),
    study(
        "[grid]\nvn = [0.1, 0.5]\n", "[grid] vn must be a number in (0, 0.3] (units of c), got 0.5"
    ),
    study("[grid]\nvn = [0.1, 0.1]\n", "[grid] vn: an axis needs values distinct"),
    study("[grid]\ngamma_deg = [30, 30]\n", "[grid] gamma_deg names a value twice"),
    study("[grid]\ngamma_deg = [0, 45]\n", "each a number in (0, 90) (degrees from the wall's"),
    study("[grid]\ngamma_deg = [45, 90]\n", "got 90 in [45, 90]"),
    study("[grid]\ngamma_deg = [[45]]\n", "[grid] gamma_deg must be a list of distinct values"),
    study('[grid]\ngamma_deg = ["a", 45]\n', "got 'a' in ['a', 45]"),
    study(
        "[grid]\ncot_gamma = [1.0, 1.0000001]\n",
        "f.toml: cot_gamma names an impact's folder twice (g45.0000)",
    ),
    study("[grid]\ncot_gamma = [1.0]\n", "f.toml: angles must be an integer in [2, 1000], got 1"),
    study("[grid]\ncot_gamma = [1000.0, 1.0]\n", "[grid] cot_gamma must be a list of distinct"),
    study("[grid]\nspeeds = [0.1, 0.1]\n", "[grid] speeds names a value twice"),
    study("[grid]\nspeeds = [0.1, 0.4]\n", "[grid] speeds must be a list of distinct values"),
    study("[grid]\ngamma_deg = [45, 60]\ncot_gamma = [1.0, 2.0]\n", "both gamma_deg and cot_gamma"),
    study("[scene]\nwall_ka = [1.0, -5.0]\n", "[scene] wall_ka must be a number in [0.01, 1000]"),
    study("[scene]\nwall_ka = -1.0\n", "or 'same-c', got -1.0"),
    study('[scene]\nwall_ka = "soft"\n', "or 'same-c', got 'soft'"),
    study("[scene]\nwall_ka = [1.0, 1]\n", "distinct in their folder names (1, 1)"),
    study("[scene]\nn_wall = 1600.0\n", "[scene] n_wall must be an integer in [50, 400000]"),
    study('[scene]\nn_wall = "dense"\n', "or 'density', got 'dense'"),
    study("[scene]\nn_disk = 10\n", "[scene] n_disk must be an integer in [50, 100000], got 10"),
    study("[scene]\nn_disk = 800.5\n", "[scene] n_disk must be an integer in [50, 100000]"),
    study("[scene]\nroughness = 0.5\n", "[scene] roughness must be a number in [0, 0.1] (R)"),
    study("[scene]\nradius = 0\n", "[scene] radius must be a number in [0.1, 10]"),
    study("[scene]\nwall_width = 1.0\n", "[scene] wall_width must be a number in [4, 100]"),
    study('[scene]\nwall_fixed = "top"\n', "wall_fixed must be one of sides, sides+bottom, all"),
    study('[scene]\ncontact_mass = "atom"\n', "[scene] contact_mass must be one of point, disk"),
    study('[scene]\ntarget = "moon"\n', "[scene] target must be one of wall, disk"),
    study('[scene]\nwall = [["x"]]\n', "[scene] wall must be among 800_1ka_sides"),
    study("[scene]\nwall = 3\n", "[scene] wall must be among"),
    study('[scene]\nmodel = ["first-read", "first-read"]\n', "[scene] model: an axis needs values"),
    study("[scene]\nsamples = 3\n", "[scene] has no option 'samples'"),
    study("[scene]\nsource = 3\n", "[scene] has no option 'source'"),
    study("[run]\nname = 3\n", "[run] has no option 'name'"),
    study(
        '[run]\ndt = [0.008, "x"]\n',
        "[run] dt must be a number in [1e-05, 0.05] (R/c) or 'auto', got 'x'",
    ),
    study(
        "[run]\ndt = 0.2\n", "[run] dt must be a number in [1e-05, 0.05] (R/c) or 'auto', got 0.2"
    ),
    study(
        "[run]\nevery = 10.0\n", "[run] every must be an integer in [1, 10000000] or 0, got 10.0"
    ),
    study("[run]\nevery = -1\n", "[run] every must be an integer in [1, 10000000] or 0"),
    study("[run]\ncheck = 3\n", "f.toml: check must be a multiple of every (10), got 3"),
    study("[run]\nnrespa = 0\n", "[run] nrespa must be an integer in [1, 100], got 0"),
    study('[run]\nintegrator = "euler"\n', "[run] integrator must be one of verlet, respa"),
    study("[run]\ntmax = 0\n", "[run] tmax must be a number in (0, 10000] (R/c), got 0"),
    study("[run]\nnprocs = 2.0\n", "[run] nprocs must be an integer in [1, 4096], got 2.0"),
    study('[run]\nroute = "mpi"\n', "[run] route must be one of lmp, python"),
    study("[run]\nmax_drift = 2.0\n", "[run] max_drift must be a number in (0, 1]"),
    study("[run]\ndump_every = 7\n", "f.toml: dump_every must divide check (100)"),
    study("[run]\ndt = 1e-05\ntmax = 10000\n", "f.toml: tmax / dt must be at most 1e+07 steps"),
    # what the file is
    study('page = "../../elsewhere/x"\n', "f.toml: page must be a plain name (letters, digits"),
    study('page = "/tmp/x"\n', "f.toml: page must be a plain name"),
    study('page = "a/b"\n', "f.toml: page must be a plain name"),
    study('page = ".."\n', "f.toml: page must be a plain name"),
    study("page = 3\n", "f.toml: page must be a plain name"),
    study('page = ["results"]\n', "f.toml: page must be a plain name"),
    study('page = "p"\nreadings = ["../x"]\n', "f.toml: readings must be a list of plain names"),
    study('page = "p"\nreadings = ["a", "a"]\n', "f.toml: readings names a table twice"),
    study('sections = ["fits", "fits"]\n', "f.toml: sections must be a list of distinct names"),
    study("kind = 3\n", "f.toml: kind must be one of results"),
    study('sweep = ["cross"]\n', "f.toml: sweep must be one of cross, one-at-a-time"),
    study("[[grid]]\nsamples = 1\n", "f.toml: [grid] must be a table of options"),
    study("[grid\n", "f.toml: not a study file"),
    study("[walls]\n", "f.toml: 'walls' is not a section"),
    Case(
        "file not UTF-8",
        ["study", "{tmp}/f.toml"],
        "f.toml: not a study file (not UTF-8",
        {"f.toml": b'page = "\xff"\n'},
        name="f",
    ),  # fmt: skip
    study(
        'kind = "scene_readings"\n[rerun]\nthen_lattices = [["random"]]\nthen_best = 1\n',
        "f.toml: [rerun] then_lattices must be among random",
    ),
    study(
        'kind = "wall_width"\n[scene]\nwall_width = [8.0, 2.0]\n',
        "[scene] wall_width must be a number in [4, 100] (R), got 2.0",
    ),
    study(
        'kind = "wall_width"\n[grid]\nsamples = 2\n[rerun]\nbest = 1\nsamples = 3\n',
        "f.toml: kind wall_width compares readings by wall_width: give it a list of values",
    ),
]

PAGE_CASES = [
    # a page that another study's, or committed, is not a file of one's own
    study('page = "results"\n' + SMALL, "f.toml: page 'results' is the paper study's", "--docs"),
    study('page = "wall_tilt"\n' + SMALL, "page 'wall_tilt' is committed in docs/", "--docs"),
    study('page = "studies"\n' + SMALL, "page 'studies' is committed in docs/", "--docs"),
    study('page = "model"\n' + SMALL, "page 'model' is committed in docs/", "--docs"),
    study('page = "benchmarks"\n' + SMALL, "page 'benchmarks' is committed", "--docs"),
    study('page = "grazing_literal"\n' + SMALL, "is the grazing study's", "--docs"),
    study(
        'page = "mine"\nreadings = ["speed"]\n' + SMALL,
        "page 'speed' is the speed study's",
        "--name",
        "speed",
        "--docs",
        case="own file --name speed --docs (another's page)",
    ),
    Case(
        "page of own file, page results",
        ["page", "{tmp}/f.toml"],
        "f.toml: page 'results' is the paper study's",
        {"f.toml": 'page = "results"\n'},
    ),  # fmt: skip
    Case(
        "page of own file, page wall_tilt",
        ["page", "{tmp}/f.toml"],
        "page 'wall_tilt' is committed in docs/",
        {"f.toml": 'page = "wall_tilt"\n'},
    ),  # fmt: skip
    command("study paper --name other --docs", "--name other is not one", name="other"),
    command("study grazing --name paper_x --docs", "--name paper_x is not one", name="paper_x"),
    command("study demo --docs", "--docs: the demo study has no page in docs/"),
    study(SMALL, "has the name 'paper' already", name="paper", case="own file named paper"),
    command("page", "page: give a STUDY or --all, not both or neither"),
    command("page speed --all", "page: give a STUDY or --all, not both or neither"),
]

PATH_CASES = [
    command(
        "impact --out docs/studies/wall_width",
        "docs/studies/wall_width is inside docs/, the committed",
    ),
    command("impact --out studies/x", "studies/x is inside studies/"),
    command("impact --out runner/x", "runner/x is inside runner/, the project's own"),
    command("impact --out {docs_link}/x", "(it leads to " + str(DOCS / "x") + ")"),
    command("impact --out runs/../docs/x", "runs/../docs/x is inside docs/"),
    command("impact --out /proc/x", "/proc/x cannot be made"),
    command("impact --out .", ". is the project's root"),
    command("impact --out " + str(ROOT / "analysis"), "is inside analysis/"),
    command("page speed --out docs", "argument --out: docs is inside docs/"),
    command("page speed --out {docs_link}", "is inside docs/"),
    command(
        "scene --out docs/studies/results",
        "docs/studies/results is inside docs/",
        module="builder.__main__",
    ),
    command(
        "--out docs/x", "docs/x is inside docs/", "validate --out docs/x", module="bench.validation"
    ),
    command("run --out studies/x", "studies/x is inside studies/", module="calibration.__main__"),
    command("tilt --out decks/x", "decks/x is inside decks/"),
    command("study demo --name " + "n" * 300, "argument --name: must be a folder name of at most"),
    command("study demo --name ../x", "must be one folder under runs/"),
    command(
        "study demo --name evil",
        "evil is inside docs/, the committed record (it leads to",
        before={"evil": DOCS / "studies" / "results"},
    ),  # fmt: skip
    command(
        "study demo",
        "IMPACT_RUNS: docs is inside docs/",
        "IMPACT_RUNS=docs",
        env={"IMPACT_RUNS": "docs"},
    ),
    command(
        "impact",
        "IMPACT_RUNS: {docs_link} is inside docs/",
        "IMPACT_RUNS=a link to docs/",
        env={"IMPACT_RUNS": "{docs_link}"},
    ),
    command(
        "study demo",
        "is inside studies/",
        "IMPACT_RUNS=studies",
        env={"IMPACT_RUNS": str(ROOT / "studies")},
    ),
]

# the run's axes, records, options and cluster: test_refusals_run.py
CASES = FILE_CASES + PAGE_CASES + PATH_CASES


def test_the_table_has_the_issues_cases_and_more():
    from tests.runner.cli.test_refusals_run import CASES as RUN_CASES

    every = CASES + RUN_CASES
    assert len(every) >= 100 and len({case.id for case in every}) == len(every)


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture(scope="module")
def places(tmp_path_factory):
    """What the cases name: a link to docs/, a folder without sbatch, one whose
    sbatch fails, a server that answers garbage, a port nobody listens on."""
    base = tmp_path_factory.mktemp("refusals")
    (base / "docs_link").symlink_to(DOCS)
    (base / "empty").mkdir()
    fake = base / "fake_sbatch"
    fake.mkdir()
    (fake / "sbatch").write_text(
        "#!/bin/sh\necho 'sbatch: error: Batch job submission failed: Invalid account' >&2\n"
        "exit 1\n"
    )
    (fake / "sbatch").chmod(0o755)
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)

    def answer():
        while True:
            try:
                client, _ = server.accept()
            except OSError:
                return
            with client:
                client.sendall(b"\xff" * 64 + b"garbage" * 64)

    threading.Thread(target=answer, daemon=True).start()
    yield {
        "docs_link": str(base / "docs_link"),
        "empty": str(base / "empty"),
        "fake_sbatch": f"{fake}:{os.environ['PATH']}",
        "garbage": f"tcp://127.0.0.1:{server.getsockname()[1]}",
        "closed_port": str(free_port()),
    }
    server.close()


@pytest.fixture(scope="module")
def clean_tree():
    """git status of the clone before the cases (they must leave it so)."""
    return git_status()


def git_status() -> str:
    return subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=all"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    ).stdout


def leave_before(case: Case) -> None:
    """What a run before the case left under runs/: a record, or a link."""
    for name, what in case.before.items():
        if isinstance(what, Path):
            (RUNS / name).symlink_to(what)
        else:
            (RUNS / name).mkdir()
            (RUNS / name / "study.json").write_text(json.dumps(what, indent=1))


def remove_before(case: Case) -> None:
    for name in case.before:
        path = RUNS / name
        path.unlink() if path.is_symlink() else shutil.rmtree(path)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_refused_before_any_work(case, places, clean_tree, tmp_path, monkeypatch, capsys):
    refused_before_any_work(case, places, clean_tree, tmp_path, monkeypatch, capsys)


def refused_before_any_work(case, places, clean_tree, tmp_path, monkeypatch, capsys) -> None:
    """Run ``case``; it must be refused in one line, with exit 2, before any work."""

    fill = {**places, "tmp": str(tmp_path), "name": case.name}
    for name, text in case.files.items():
        path = tmp_path / name
        if isinstance(text, bytes):
            path.write_bytes(text)
        else:
            path.write_text(text.replace("{closed_port}", places["closed_port"]))
    argv = [a.format(**fill) for a in case.argv]
    env = {k: v.format(**fill) for k, v in case.env.items()}
    leave_before(case)
    try:
        before_runs, before_tmp = listing(RUNS), listing(tmp_path)
        if case.subprocess:
            proc = subprocess.run(
                [sys.executable, "-m", case.module.removesuffix(".__main__"), *argv],
                cwd=ROOT,
                env={**os.environ, **env},
                capture_output=True,
                text=True,
                timeout=120,
            )
            status, errors = proc.returncode, proc.stderr.strip()
        else:
            for key, value in env.items():
                monkeypatch.setenv(key, value)
            monkeypatch.chdir(ROOT)
            monkeypatch.setattr("runner.cluster.workers.JOIN_SECONDS", 3)
            # a command runs alone in its process: what an earlier case was
            # granted (a study's docs folder) is not this one's
            monkeypatch.setattr("ground.gate._granted", set())
            module = importlib.import_module(case.module)
            if "scheduler" in case.id:  # joining comes first: the sweep must not
                monkeypatch.setattr("runner.cluster.driver.drive", refuse_work)
            else:
                no_work(monkeypatch, module)
            try:
                status = module.main(argv)
            except SystemExit as stop:
                status = stop.code
            except WorkStarted:
                pytest.fail(f"{' '.join(argv)}: accepted, work started")
            errors = capsys.readouterr().err.strip()
        assert status == 2, f"{' '.join(argv)}: exit {status}, stderr {errors!r}"
        assert len(errors.splitlines()) == 1, errors
        assert case.says.format(**fill) in errors, errors
        assert git_status() == clean_tree, "the clone's tree changed"
        assert listing(RUNS) == before_runs, "the runs' folder changed"
        assert listing(tmp_path) == before_tmp, "the case's folder changed"
        if case.name and case.name not in case.before:
            assert not (RUNS / case.name).exists()
    finally:
        remove_before(case)


def refuse_work(*args, **kwargs):
    raise WorkStarted


def test_every_option_of_a_study_file_has_its_range():
    """runner/values.py has a line for every option a study file takes, so
    that an option added to the study or its run is checked before any work."""
    from dataclasses import fields

    from runner.options import RunOptions
    from runner.study import Study
    from runner.study.file import GRID
    from runner.values import VALUES

    study = {f.name for f in fields(Study)} - {"name", "options", "source"}
    assert set(VALUES["grid"]) == set(GRID)
    assert set(VALUES["scene"]) == study - set(GRID)
    assert set(VALUES["run"]) == {f.name for f in fields(RunOptions)}


@pytest.mark.parametrize(
    "section, key, good",
    [("grid", "samples", 3), ("scene", "n_wall", "density"), ("scene", "wall_ka", 2.5),
     ("run", "every", 0), ("run", "dt", 0.004), ("grid", "lattices", ["random", "triangular"])],
)  # fmt: skip
def test_the_table_takes_what_the_command_line_takes(section, key, good):
    """A value the table refuses is not merely anything: it takes the good ones."""
    from runner.values import VALUES

    assert VALUES[section][key].check(key, good) == good
