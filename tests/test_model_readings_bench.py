"""bench/model_readings.py: what it runs, what it skips, and how it ranks."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pytest

import bench.model_readings as bench


def rows_of(reading, lattice, seeds, angles=(5.7, 45.0)):
    return [
        {"reading": bench.label(reading), "study_lattice": lattice, "seed": s, "gamma_deg": g}
        for s in seeds
        for g in angles
    ]


def test_a_run_goes_on_after_the_last_whole_seed():
    reading = ("1600_10ka_sides", "first-read")
    rows = rows_of(reading, "random", [1, 2, 3]) + rows_of(reading, "random", [4], (5.7,))
    rows += rows_of(reading, "random", [6])  # past a gap: not counted
    rows += rows_of(("1600_10ka_sides", "disk-mass"), "random", [1, 2, 3, 4, 5])
    assert bench.seeds_done(rows, bench.label(reading), "random", 2) == 3
    assert bench.seeds_done(rows, bench.label(reading), "triangular", 2) == 0
    args = argparse.Namespace(angles=2)
    study = bench.study_for(reading, "random", 27, args, first_seed=4)
    assert [j["seed"] for j in study.jobs()][::2] == list(range(4, 31))


def test_the_random_disk_shares_the_study_that_only_changes_regular_disks():
    args = argparse.Namespace(angles=8)
    wall = "density_1ka_sides-bottom"
    same = bench.study_for((wall, "lattice-surface"), "random", 12, args)
    assert same.name == bench.study_for((wall, "first-read"), "random", 12, args).name
    assert same.regular_surface == "band"
    tri = bench.study_for((wall, "lattice-surface"), "triangular", 12, args)
    assert tri.regular_surface == "lattice" and tri.name != same.name
    mass = bench.study_for((wall, "disk-mass+lattice-surface"), "random", 12, args)
    assert mass.contact_mass == "disk" and mass.regular_surface == "band"
    for reading in bench.readings():  # every study is one the runner accepts
        for lattice in bench.LATTICES:
            bench.study_for(reading, lattice, 12, args).validate()


@pytest.mark.parametrize(
    ("reading", "away"),
    [
        (("density_1ka_sides-bottom", "first-read"), 2),  # its points, its bottom held
        (("1600_10ka_sides", "first-read"), 2),
        (("1600_10ka_sides", "disk-mass"), 2),  # "the mass of the particle": either
        (("1600_10ka_sides", "spring-speed"), 3),
        (("density_10ka_sides", "disk-mass+lattice-surface"), 3),
    ],
)
def test_choices_away_from_the_text(reading, away):
    assert bench.distance_from_text(reading) == away


def test_the_rule_prefers_the_text_among_readings_as_good():
    a, b, c = (
        ("density_10ka_sides", "spring-speed"),  # 3 away
        ("1600_10ka_sides", "first-read"),  # 2 away
        ("density_1ka_sides-bottom", "both-directions"),  # 3 away
    )
    summaries = {
        a: {"total": 3.0, "total_se": 0.3},
        b: {"total": 3.3, "total_se": 0.2},  # within hypot(0.3, 0.2) of the least
        c: {"total": 5.0, "total_se": 0.1},
        ("1600_1ka_sides-bottom", "first-read"): {"impacts": 0, "failed": 0},  # no facts
    }
    assert bench.rank(summaries) == [b, a, c]
    summaries[b]["total"] = 3.4  # beyond one combined error: the least wins
    assert bench.rank(summaries) == [a, b, c]


def test_the_committed_rows_hold_what_the_facts_are_made_from():
    from analysis.seeds import QUANTITIES

    # the seed bootstrap's quantities and the lattice's constants (estimates)
    needed = {*QUANTITIES, "nu", "disk_inertia_ratio", "seed", "gamma_deg", "study_lattice"}
    assert needed <= set(bench.KEEP_COLUMNS)


@pytest.mark.parametrize(
    ("script", "page", "rows"),
    [
        ("model_readings.py", "model_readings.md", 35),  # every reading a row of the table
        ("fact_sensitivity.py", "fact_sensitivity.md", 5),  # every (v_n, roughness)
    ],
)
def test_the_committed_page_comes_from_its_rows(tmp_path, script, page, rows):
    """The committed page, rebuilt from the committed rows alone (the machine
    and date aside), is the committed page: the same command, table and pick."""
    import subprocess

    root = Path(__file__).resolve().parents[1]
    subprocess.run(
        [sys.executable, f"bench/{script}", "--from-csv", "--out", str(tmp_path)],
        cwd=root,
        check=True,
        capture_output=True,
        timeout=600,
    )
    committed = (root / "docs" / "benchmarks" / page).read_text().splitlines()
    rebuilt = (tmp_path / page).read_text().splitlines()
    assert committed[0] == rebuilt[0] and committed[3:] == rebuilt[3:]
    assert committed[2].split(" on ")[0] == rebuilt[2].split(" on ")[0]
    table = [line for line in rebuilt if line.startswith("| ") and "---" not in line]
    assert len(table) == rows + 1  # and the header
    if script == "model_readings.py":
        # the default scene is the reading the rule picks from the committed rows
        pick = next(line for line in rebuilt if line.startswith("The rule's pick"))
        wall, model = pick.split("`")[1], pick.split("`")[3]
        assert (wall, model) == bench.current_default()
