"""The readings studies (studies/scene_readings.toml, model_readings.toml,
fact_sensitivity.toml; analysis/kinds/__init__.py): their files are the studies that
made the committed tables, their pages come from those tables byte for byte,
their rules rank as docs/model.md section 8 says, and a small one runs."""

from __future__ import annotations

import csv
import itertools
import subprocess
import sys

import pytest

from analysis.kinds import model_readings, scene_readings
from analysis.kinds.readings import MODELS, WALLS, distance_from_text, named_reading, read_record
from builder.scene import FIRST_READING, SceneSpec
from runner.options import RunOptions
from runner.study.file import axis_studies, read_study_file
from runner.study.readings import setup_of
from runner.study.studies import study_file
from tests.helpers import ROOT, RUNS

# reads the committed pages' bytes or times, which the pages made again
# rewrite: after them (Makefile)
pytestmark = pytest.mark.last

DOCS = ROOT / "docs" / "studies"  # each study's folder: page, tables, figures


def rows_of(name: str) -> list[dict]:
    with (DOCS / name / "rows.csv").open() as handle:
        return list(csv.DictReader(handle))


def studies_of(name: str) -> list:
    described = study_file(name)
    return axis_studies(described.study, described.axes, name, described.sweep)


def most_seeds(rows: list[dict], lattice: str = "random") -> dict[str, int]:
    """The last seed of each reading's rows of ``lattice``."""
    out: dict[str, int] = {}
    for r in rows:
        if r["study_lattice"] == lattice:
            out[r["reading"]] = max(out.get(r["reading"], 0), int(r["seed"]))
    return out


def test_the_scene_readings_file_is_the_study_of_its_table():
    """Every wall of points x ka x held on the random disk at the model's first
    reading, 8 angles, 12 seeds, the five best to 30, the triangular disk on
    three; the run settings of the time."""
    described = study_file("scene_readings")
    subs = studies_of("scene_readings")
    held = ("sides", "sides+bottom")
    walls = list(itertools.product((800, 1600, "density"), (1.0, 10.0, "same-c"), held))
    assert [(s.n_wall, s.wall_ka, s.wall_fixed) for s in subs] == walls
    run = RunOptions(dt=0.004, every=25, check=100, springs="class2", route="python")
    for sub in subs:
        assert sub.options == run and sub.lattices == ("random",)
        assert (sub.angles, sub.samples, sub.vn, sub.n_disk) == (8, 12, 0.1, 800)
        assert {k: getattr(sub, k) for k in FIRST_READING} == FIRST_READING
    rerun = described.rerun
    assert (rerun["best"], rerun["samples"], rerun["then_lattices"], rerun["then_best"]) == (
        5,
        30,
        ["triangular"],
        3,
    )
    rows = rows_of("scene_readings")
    labels = [scene_readings.label(c) for c in setup_of("scene_readings", described).choices]
    seeds = most_seeds(rows)
    assert sorted(seeds) == sorted(labels) and len(labels) == 18
    assert sorted(seeds.values()) == [12] * 13 + [30] * 5
    assert len(most_seeds(rows, "triangular")) == 3
    assert len({r["gamma_deg"] for r in rows}) == 8


@pytest.mark.slow
def test_the_model_readings_file_is_the_study_of_its_table():
    """Five walls x seven readings of the model (relative to the first
    reading), random and triangular disks, 8 angles, 12 seeds, the five best
    and the default of the time to 30."""
    described = study_file("model_readings")
    subs = studies_of("model_readings")
    assert len(subs) == 35
    setup = setup_of("model_readings", described)
    for choice, sub in zip(setup.choices, subs, strict=True):
        wall, model = WALLS[choice["wall"]], MODELS[choice["model"]]
        assert {k: getattr(sub, k) for k in wall} == wall
        assert {k: getattr(sub, k) for k in FIRST_READING} == model
        assert sub.lattices == ("random", "triangular")
        assert (sub.angles, sub.samples, sub.options) == (
            8,
            12,
            RunOptions(dt=0.002, route="python"),
        )
    assert described.rerun["best"] == 5 and described.rerun["samples"] == 30
    assert described.rerun["default"] is True
    rows = rows_of("model_readings")
    labels = [model_readings.label(c) for c in setup.choices]
    seeds = most_seeds(rows)
    assert sorted(seeds) == sorted(labels)
    # the five best and the default of the time (not among them) to 30
    assert sorted(seeds.values()) == [12] * 29 + [30] * 6
    default = read_record(DOCS / "model_readings")["default"]
    assert seeds[default] == 30 and default not in model_readings.rank(rows, setup)[:5]


def test_the_fact_sensitivity_file_is_the_study_of_its_table():
    """The random disk on the default scene's reading, v_n and roughness one
    at a time around (0.1, 0.03): five studies, not the nine of a cross."""
    described = study_file("fact_sensitivity")
    assert described.sweep == "one-at-a-time"
    subs = studies_of("fact_sensitivity")
    points = [(s.vn, s.roughness) for s in subs]
    assert points == [(0.1, 0.03), (0.05, 0.03), (0.2, 0.03), (0.1, 0.015), (0.1, 0.06)]
    wall, model = WALLS["1600_10ka_sides"], MODELS["disk-mass"]
    for sub in subs:
        assert {k: getattr(sub, k) for k in wall} == wall
        assert {k: getattr(sub, k) for k in FIRST_READING} == model
        assert (sub.lattices, sub.angles, sub.samples) == (("random",), 8, 12)
        assert sub.options == RunOptions(dt=0.002, route="python")
    rows = rows_of("fact_sensitivity")
    assert {r["study_reading"] for r in rows} == {"1600_10ka_sides/disk-mass"}
    assert {(float(r["vn"]), float(r["roughness"])) for r in rows} == set(points)
    assert max(int(r["seed"]) for r in rows) == 12


def test_the_wall_width_file_is_the_study_of_its_table():
    """Each seed and angle on the 8 R and the 16 R wall, whose points scale
    with its width (the disk's density): the 16 R wall has twice the 8 R's."""
    subs = studies_of("wall_width")
    assert [(s.wall_width, s.n_wall) for s in subs] == [(8.0, "density"), (16.0, "density")]
    for sub in subs:
        assert sub.gammas() == [63.52, 73.9, 80.5] and sub.samples == 12
    rows = rows_of("wall_width")
    assert len(rows) == 2 * 3 * 12 and not any(r["error"] for r in rows)
    points = {float(r["wall_width"]): int(r["n_wall_points"]) for r in rows if r["seed"] == "1"}
    assert points[16.0] == pytest.approx(2 * points[8.0], rel=0.02)


@pytest.mark.parametrize(
    ("name", "table_rows"),
    [
        ("scene_readings", 18 + 3),
        # model_readings (35 rows): tests/docs/test_pages_reproducible.py makes it
        # again byte for byte, a 40 s page, once is enough
        ("fact_sensitivity", 5),
        ("wall_width", 3 * 2),
    ],
)
def test_the_committed_page_is_made_again_from_its_table(tmp_path, name, table_rows):
    """runner page: the committed page, byte for byte, from the committed table."""
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "page", name, "--out", str(tmp_path)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    rebuilt = (tmp_path / f"{name}.md").read_text()
    assert rebuilt == (DOCS / name / f"{name}.md").read_text()
    table = [x for x in rebuilt.splitlines() if x.startswith("| ") and "---" not in x]
    assert len(table) == table_rows + 1  # and the header
    for figure in (DOCS / name / "figures").glob("*.png"):
        assert (tmp_path / "figures" / figure.name).stat().st_size > 10_000


def test_a_results_page_is_made_again_by_the_same_command(tmp_path):
    """runner page takes a results study too (its tables in docs/studies/<page>/): the
    speed study's committed page, byte for byte, and its tables left as they were."""

    def files() -> dict:  # the study's folder: page, tables, figures
        return {p: p.read_bytes() for p in (DOCS / "speed").rglob("*") if p.is_file()}

    before = files()
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "page", "speed", "--out", str(tmp_path)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "speed.md").read_text() == (DOCS / "speed" / "speed.md").read_text()
    assert files() == before


@pytest.mark.slow
def test_the_default_scene_is_the_pick_of_the_committed_model_readings():
    """The rule's pick from the committed rows, every seed of each reading (the
    page's), is today's default reading."""
    setup = setup_of("model_readings", study_file("model_readings"))
    summaries = model_readings.summaries_of(rows_of("model_readings"), setup)
    pick = model_readings.rank_summaries(summaries)[0]
    assert pick == model_readings.label(model_readings.current_default())
    default = SceneSpec()  # the 800-point disk's: its wall has 1,600 points
    spec = {k: getattr(default, k) for k in (*WALLS["1600_10ka_sides"], *FIRST_READING)}
    assert named_reading(spec) == dict(zip(("wall", "model"), pick.split("/")))


@pytest.mark.parametrize(
    ("reading", "away"),
    [
        ("density_1ka_sides-bottom/first-read", 2),  # its points, its bottom held
        ("1600_10ka_sides/first-read", 2),
        ("1600_10ka_sides/disk-mass", 2),  # "the mass of the particle": either
        ("1600_10ka_sides/spring-speed", 3),
        ("density_10ka_sides/disk-mass+lattice-surface", 3),
        ("800_1ka_sides/first-read", 0),  # the paper's sentence
    ],
)
def test_choices_away_from_the_text(reading, away):
    assert model_readings.away(reading) == away
    assert distance_from_text(*reading.split("/")) == away


def test_the_rule_prefers_the_text_among_readings_as_good():
    a, b, c = (
        "density_10ka_sides/spring-speed",  # 3 away
        "1600_10ka_sides/first-read",  # 2 away
        "density_1ka_sides-bottom/both-directions",  # 3 away
    )
    summaries = {
        a: {"total": 3.0, "total_se": 0.3},
        b: {"total": 3.3, "total_se": 0.2},  # within hypot(0.3, 0.2) of the least
        c: {"total": 5.0, "total_se": 0.1},
        "1600_1ka_sides-bottom/first-read": {"impacts": 0, "failed": 0},  # no facts
    }
    assert model_readings.rank_summaries(summaries) == [b, a, c]
    summaries[b]["total"] = 3.4  # beyond one combined error: the least wins
    assert model_readings.rank_summaries(summaries) == [a, b, c]


def test_the_tables_hold_what_the_facts_are_made_from():
    from analysis.statistics.seeds import QUANTITIES

    # the seed bootstrap's quantities and the lattice's constants (estimates)
    needed = {*QUANTITIES, "nu", "disk_inertia_ratio", "seed", "gamma_deg", "study_lattice"}
    assert needed <= set(model_readings.COLUMNS)
    for name in ("model_readings", "fact_sensitivity"):
        with (DOCS / name / "rows.csv").open() as handle:
            assert needed <= set(next(csv.reader(handle)))


@pytest.mark.lammps
@pytest.mark.slow
def test_a_small_readings_study_runs_and_makes_its_page(tmp_path):
    """One sample at three angles of a 200-point disk, v_n and the roughness
    one at a time: three studies, their rows in one table, and the page."""
    path = tmp_path / "sweep_probe.toml"
    path.write_text(
        'kind = "fact_sensitivity"\nsweep = "one-at-a-time"\n'
        '[grid]\nlattices = ["random"]\ncot_gamma = [3.0, 1.0, 0.5]\nsamples = 1\n'
        "vn = [0.1, 0.2]\n"
        '[scene]\nn_disk = 200\nwall = "1600_10ka_sides"\nmodel = "disk-mass"\n'
        "roughness = [0.03, 0.06]\n"
    )
    assert len(read_study_file(path).axes) == 2
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "study", str(path), "--workers", "1"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    with (RUNS / "sweep_probe" / "rows.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    found = sorted({(r["reading"], float(r["vn"]), float(r["roughness"])) for r in rows})
    assert found == [
        ("vn0.1_roughness0.03", 0.1, 0.03),
        ("vn0.1_roughness0.06", 0.1, 0.06),
        ("vn0.2_roughness0.03", 0.2, 0.03),
    ]
    assert len(rows) == 9 and {r["study_lattice"] for r in rows} == {"random"}
    page = (RUNS / "sweep_probe" / "sweep_probe.md").read_text()
    assert page.startswith("# How the facts move with speed and roughness\n")
    assert "`python -m runner study sweep_probe`" in page
    assert "| 0.1 | 0.06 | 3 |" in page and "| 0.2 | 0.03 | 3 |" in page
    # an option the file gives is not taken from the command line
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "study", str(path), "--samples", "2"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
    assert "--samples does not apply to the sweep_probe study" in proc.stderr
    # more samples in the file: refused as a changed file, taken with --extend,
    # which runs only the new seeds and keeps every row already done
    path.write_text(path.read_text().replace("samples = 1", "samples = 2"))
    command = [sys.executable, "-m", "runner", "study", str(path), "--workers", "1"]
    proc = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 2 and "--extend takes more samples" in proc.stderr
    proc = subprocess.run(
        [*command, "--extend"], cwd=ROOT, capture_output=True, text=True, timeout=600
    )
    assert proc.returncode == 0, proc.stderr
    assert "3 already done or failed, 3 to run" in proc.stdout
    with (RUNS / "sweep_probe" / "rows.csv").open() as handle:
        extended = list(csv.DictReader(handle))
    assert len(extended) == 18 and {r["seed"] for r in extended} == {"1", "2"}
    first = {(r["reading"], r["gamma_deg"]): r["e"] for r in rows}
    assert {(r["reading"], r["gamma_deg"]): r["e"] for r in extended if r["seed"] == "1"} == first
