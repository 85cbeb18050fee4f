"""Study files (studies/*.toml, runner/study/file.py): what they read as, round
trips, and one-line refusals of bad files."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace

import pytest

from ground.errors import InputError
from runner.options import RunOptions
from runner.study import Study
from runner.study.file import STUDIES, read_study_file, study_file_text, study_path
from runner.study.studies import built_in_pages, load_study
from tests.helpers import ROOT, RUNS


@pytest.mark.parametrize("path", sorted(STUDIES.glob("*.toml")), ids=lambda p: p.stem)
def test_every_study_file_reads_back_from_its_own_text(path, tmp_path):
    """A file written from a study reads back as that study, exactly."""
    described = read_study_file(path)
    again = tmp_path / path.name
    again.write_text(study_file_text(described))
    assert read_study_file(again) == described


def test_the_papers_grid():
    """docs/model.md section 7: four lattices, 16 angles, 100 samples at 0.1 c."""
    paper = load_study("paper")
    assert len(paper.jobs()) == 4 * 16 * 100 and paper.vn == 0.1
    pages = built_in_pages()[0]
    assert pages["paper"] == "results" and "demo" not in pages


def test_angles_in_degrees_are_cot_gamma_to_six_decimals(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text("[grid]\ngamma_deg = [45, 60]\n")
    study = read_study_file(path).study
    assert study.cot_gamma == (1.0, 0.57735) and study.angles == 2
    assert study.gammas() == [45.0, 60.0]


def test_a_file_sets_scene_and_run_options(tmp_path):
    path = tmp_path / "walls.toml"
    path.write_text('[scene]\nwall_ka = 1.0\nn_wall = "density"\n[run]\ndt = 0.004\n')
    described = read_study_file(path)
    study, page = described.study, described.page
    assert described.axes == {} and described.readings == ()
    assert study == Study(
        "walls", wall_ka=1.0, n_wall="density", options=RunOptions(route="python", dt=0.004)
    )
    assert page == ""


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[grid]\nfoo = 1\n", "[grid] has no option 'foo'"),
        ("[scene]\nsamples = 3\n", "[scene] has no option 'samples'"),
        ("[walls]\n", "'walls' is not a section"),
        ("[grid]\nsamples = [1, 2]\n", "[grid] samples as a list gives the seeds of each "),
        ("[grid]\nsamples = []\n", "[grid] samples must be a count or a list of counts, got"),
        (
            'kind = "resolution"\n[grid]\nsamples = [8, 4, 2]\n[scene]\nn_disk = [800, 1600]\n'
            'limit = ["profile-floor"]\n',
            "as many as n_disk has \\(2\\), got [8, 4, 2]",
        ),
        (
            'kind = "resolution"\n[grid]\nsamples = [8, 0]\n[scene]\nn_disk = [800, 1600]\n',
            "[grid] samples must be .*got 0",
        ),
        ("[scene]\nwall_ka = [1.0, 1.0]\n", "an axis needs values distinct"),
        ("[scene]\nwall_ka = [1, 1.0]\n", "distinct in their folder names \\(1, 1\\)"),
        ("[scene]\nwall_ka = []\n", "an axis needs values distinct"),
        ("[grid]\ngamma_deg = [0, 45]\n", "gamma_deg must be .*each a number in \\(0, 90\\)"),
        ('[grid]\ngamma_deg = ["a"]\n', "gamma_deg must be .*each a number in .*got 'a'"),
        ('[grid]\nlattices = "random"\n', "[grid] lattices must be a list"),
        ("[grid]\ngamma_deg = [45]\ncot_gamma = [1.0]\n", "both gamma_deg and cot_gamma"),
        ("[grid\n", "not a study file"),
        # a resolution page fits every level: too few angles or seeds refused before any run
        (
            'kind = "resolution"\n[grid]\nangles = 2\nsamples = [2, 1]\n'
            "[scene]\nn_disk = [800, 1600]\n",
            "needs at least 3 angles and 2 samples at each; got 2 angles, 1 samples",
        ),
        (
            'kind = "resolution"\n[grid]\nangles = 16\nsamples = 1\n'
            "[scene]\nn_disk = [800, 1600]\n",
            "needs at least 3 angles and 2 samples at each; got 16 angles, 1 samples",
        ),
        # nested past any study's need: a short line, never a RecursionError's 3,000
        ("a = " + "[" * 12 + "]" * 12 + "\n", "nests at most 8 deep; this one deeper"),
        ("a = " + "[" * 5000 + "]" * 5000 + "\n", "nests at most 8 deep; this one deeper"),
        ("page = 3\n", "page must be a plain name"),
        ('readings = ["x"]\n', "readings are tabulated on the study's page"),
        ('page = "p"\nreadings = "x"\n', "readings must be a list"),
        (
            'sections = ["fits", "no-such-section"]\n',
            "sections must be a list of distinct names among",
        ),
        ('sections = ["fits"]\n[grid]\nspeeds = [0.1, 0.2]\n', "a study of speeds has its own"),
        ('sweep = "diagonal"\n[scene]\nwall_ka = [1.0, 2.0]\n', "sweep must be one of cross, one-"),
        ("sweep = 1\n", "sweep must be one of cross, one-at-a-time, got 1"),
        ('sweep = "one-at-a-time"\n', "sweep 'one-at-a-time' needs axes"),
        ('kind = "poster"\n', "kind must be one of results, scene_readings"),
        ('kind = "scene_readings"\nsections = ["fits"]\n', "sections and readings are a results"),
        ("[rerun]\nbest = 2\nsamples = 30\n", "[rerun] ranks a readings study's readings"),
        ('kind = "model_readings"\n[rerun]\nbest = 2\n', "[rerun] best needs samples"),
        ('kind = "model_readings"\n[rerun]\ntop = 2\n', "[rerun] has no option 'top'"),
        ('kind = "model_readings"\n[rerun]\nbest = -1\n', "[rerun] best must be a count"),
        ('kind = "model_readings"\n[rerun]\ndefault = 1\n', "[rerun] default must be bool"),
        (
            'kind = "model_readings"\n[grid]\nsamples = 12\n[rerun]\nbest = 2\nsamples = 12\n',
            "[rerun] samples must be more than [grid] samples \\(12\\), got 12",
        ),
        (
            'kind = "scene_readings"\n[rerun]\nthen_lattices = ["triangular"]\n',
            "then_lattices and then_best go together",
        ),
        (
            'kind = "scene_readings"\n[rerun]\nthen_lattices = ["hexagonal"]\nthen_best = 1\n',
            "[rerun] then_lattices must be among random, ",
        ),
        ('[scene]\nwall = "hard"\n', "[scene] wall must be among 800_1ka_sides, "),
        ('[scene]\nmodel = ["first-read", "x"]\n', "[scene] model must be among first-read"),
        ('[scene]\nwall = "800_1ka_sides"\nn_wall = 1600\n', "gives wall and n_wall"),
        ("[grid]\nvn = []\n", "an axis needs values distinct"),
    ],
)
def test_a_bad_file_is_refused_naming_it(tmp_path, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(InputError, match="bad.toml: .*" + message.replace("[", r"\[")):
        read_study_file(path)


def test_one_at_a_time_sweeps_each_axis_around_the_base(tmp_path):
    """sweep = "one-at-a-time": the base (each axis's first value) once, then
    each axis's other values with the others at the base; not the cross."""
    from runner.study.file import axis_studies

    path = tmp_path / "line.toml"
    path.write_text(
        'sweep = "one-at-a-time"\n[grid]\nvn = [0.1, 0.05, 0.2]\n'
        "[scene]\nroughness = [0.03, 0.06]\n[run]\ndt = [0.008, 0.004]\n"
    )
    described = read_study_file(path)
    assert described.sweep == "one-at-a-time"
    subs = axis_studies(described.study, described.axes, sweep=described.sweep)
    found = [(s.vn, s.roughness, s.options.dt) for s in subs]
    assert found == [
        (0.1, 0.03, 0.008),
        (0.05, 0.03, 0.008),
        (0.2, 0.03, 0.008),
        (0.1, 0.06, 0.008),
        (0.1, 0.03, 0.004),
    ]
    assert subs[1].name == "line_vn-0.05_roughness-0.03_dt-0.008"
    crossed = axis_studies(described.study, described.axes)
    assert len(crossed) == 3 * 2 * 2


def test_a_named_reading_is_its_options(tmp_path):
    """wall = and model = name the readings of analysis.kinds.readings: the study
    has their options, and a list of names is an axis."""
    from analysis.kinds.readings import MODELS, WALLS
    from runner.study.file import axis_studies

    path = tmp_path / "named.toml"
    path.write_text(
        '[scene]\nwall = "density_same-c_sides-bottom"\nmodel = ["first-read", "disk-mass"]\n'
    )
    described = read_study_file(path)
    assert described.named == {"wall": "density_same-c_sides-bottom"}
    assert described.axes == {"model": ("first-read", "disk-mass")}
    subs = axis_studies(described.study, described.axes)
    for sub, model in zip(subs, ("first-read", "disk-mass"), strict=True):
        assert (sub.n_wall, sub.wall_ka, sub.wall_fixed) == ("density", "same-c", "sides+bottom")
        assert sub.contact_mass == MODELS[model]["contact_mass"]
    assert WALLS["density_same-c_sides-bottom"]["wall_fixed"] == "sides+bottom"


def test_a_bad_sweep_is_refused_on_the_command_line_in_one_line(tmp_path):
    bad = tmp_path / "bad_sweep.toml"
    bad.write_text('sweep = "diagonal"\n[scene]\nwall_ka = [1.0, 2.0]\n')
    proc = run_study_command(str(bad))
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1, proc.stderr
    assert "bad_sweep.toml: sweep must be one of cross, one-at-a-time, got 'diagonal'" in lines[0]
    assert not (RUNS / "bad_sweep").exists()


def test_a_name_is_a_file_in_studies():
    assert study_path("paper") == STUDIES / "paper.toml"
    names = ", ".join(sorted(path.stem for path in STUDIES.glob("*.toml")))
    with pytest.raises(InputError, match=f"one of {names} "):
        study_path("no_such_study")


def run_study_command(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "runner", "study", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )


def test_the_command_takes_a_file_and_refuses_a_bad_one_in_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[grid]\nangles = 1.5\n")
    proc = run_study_command(str(bad))
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
    clash = tmp_path / "paper.toml"
    clash.write_text("[grid]\nsamples = 2\n")
    proc = run_study_command(str(clash), "--report-only")
    assert proc.returncode == 2 and "has the name 'paper' already" in proc.stderr


def test_command_line_options_override_the_file(tmp_path, monkeypatch):
    from runner.__main__ import parser
    from runner.cli.study_args import study_from_args

    mine = tmp_path / "mine.toml"
    mine.write_text(
        '[grid]\nlattices = ["random"]\nsamples = 5\nangles = 4\n[scene]\nwall_ka = 1.0\n'
    )
    args = parser().parse_args(["study", str(mine), "--samples", "2", "--name", "mine_probe"])
    study = study_from_args(args, args.preset.study)
    assert (study.samples, study.angles, study.wall_ka) == (2, 4, 1.0)
    assert replace(study, name="mine", samples=5) == read_study_file(mine).study


def test_a_list_of_values_is_an_axis_crossed_with_the_others(tmp_path):
    from runner.study.file import axis_studies

    path = tmp_path / "cross.toml"
    path.write_text(
        '[grid]\nsamples = 2\n[scene]\nwall_ka = [1.0, 10.0]\nwall_fixed = ["sides", "all"]\n'
        "[run]\ndt = [0.008, 0.004]\n"
    )
    described = read_study_file(path)
    study, axes = described.study, described.axes
    assert axes == {"wall_ka": (1.0, 10.0), "wall_fixed": ("sides", "all"), "dt": (0.008, 0.004)}
    subs = axis_studies(study, axes)
    assert len(subs) == 8 and len({s.name for s in subs}) == 8
    assert subs[0].name == "cross_wall_ka-1_wall_fixed-sides_dt-0.008"
    assert {(s.wall_ka, s.wall_fixed, s.options.dt) for s in subs} == {
        (k, f, d) for k in (1.0, 10.0) for f in ("sides", "all") for d in (0.008, 0.004)
    }
    assert all(s.samples == 2 for s in subs)


@pytest.mark.lammps
@pytest.mark.slow
def test_a_study_with_an_axis_runs_each_value_and_puts_the_rows_together(tmp_path):
    """Two walls, one sample at two angles each: four impacts in one table,
    whose wall_ka column tells them apart."""
    import csv

    from ground.gate import runs_folder

    path = tmp_path / "axis_probe.toml"
    path.write_text(
        '[grid]\nlattices = ["random"]\ncot_gamma = [3.0, 1.0]\nsamples = 1\n'
        "[scene]\nn_disk = 200\nwall_ka = [1.0, 10.0]\n"
    )
    proc = run_study_command(str(path), "--workers", "1")
    assert proc.returncode == 0, proc.stderr
    with (runs_folder() / "axis_probe" / "impacts.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    found = sorted((float(r["wall_ka"]), round(float(r["cot_gamma"]), 4)) for r in rows)
    assert found == [(1.0, 1.0), (1.0, 3.0), (10.0, 1.0), (10.0, 3.0)]
    proc = run_study_command(str(path), "--docs")
    assert proc.returncode == 2 and "has axes (wall_ka)" in proc.stderr
    proc = run_study_command(str(path), "--wall-ka", "5")  # would run one wall twice
    assert proc.returncode == 2 and "--wall-ka: wall_ka is an axis" in proc.stderr


@pytest.mark.slow
def test_a_page_has_the_sections_its_file_names(tmp_path):
    """sections = [...]: the page has those, in that order, and no other
    (a synthetic study of 8 seeds: the sections, not the numbers, are asked)."""
    from analysis.theory.tangential import walton_beta
    from pages.report import report_from_tables
    from tests.synthetic import impact_rows, write_tables

    path = tmp_path / "short.toml"
    path.write_text('page = "short"\nsections = ["fits", "claims"]\n')
    sections = read_study_file(path).sections
    page = tmp_path / "short.md"
    rows = impact_rows("random", lambda psi: walton_beta(psi, 0.8, 0.18, 0.56), seeds=8)
    tables = write_tables(tmp_path / "tables", rows, ["random"])
    report_from_tables(tables, page, out=tmp_path / "t", sections=sections)
    headings = [x for x in page.read_text().splitlines() if x.startswith("## ")]
    assert headings[:2] == ["## Fits", "## The paper's claims"]
    assert "## What the errors are" not in headings and "## Model-free measures" not in headings


def test_a_resolution_file_gives_seeds_per_level(tmp_path):
    """[grid] samples as a list: the seeds of each n_disk, in order; the
    study's samples the largest (its checks); the file written back reads
    the same; each level's study runs its own count, unthinned."""
    from analysis.kinds.resolution import plan
    from runner.study.file import axis_studies, combinations, study_file_text

    path = tmp_path / "levels.toml"
    path.write_text(
        'kind = "resolution"\n[grid]\nlattices = ["random"]\nsamples = [40, 8, 3]\n'
        '[scene]\nn_disk = [800, 1600, 3200]\nlimit = ["profile-floor"]\n'
    )
    described = read_study_file(path)
    assert described.level_samples == {800: 40, 1600: 8, 3200: 3}
    assert described.study.samples == 40
    path.write_text(study_file_text(described))
    assert read_study_file(path) == described
    choices = combinations(described.axes, described.sweep)
    studies = axis_studies(described.study, described.axes, "levels", described.sweep)
    seeds = [
        plan(c, replace(s, samples=described.level_samples[c["n_disk"]]), thin=False).samples
        for c, s in zip(choices, studies, strict=True)
    ]
    assert seeds == [40, 8, 3]
