"""The study's tables: contacts that reached the wall's ends are counted and
their angles left out of the fits that must not see them; failures grouped."""

import pytest

from analysis.statistics.estimates import clear_angles
from analysis.statistics.seeds import seed_tables
from analysis.table import mean_rows
from pages.results import angle_span


def fake_rows(clearances_by_angle: dict[float, list[float]]) -> list[dict]:
    rows = []
    for gamma, clearances in clearances_by_angle.items():
        for seed, clearance in enumerate(clearances, start=1):
            rows.append(
                {
                    "study_lattice": "random",
                    "gamma_deg": gamma,
                    "seed": seed,
                    "cot_gamma": 1.0,
                    "e": 0.5,
                    "beta": 0.1 * seed,
                    "omega": 0.0,
                    "contact_time": 9.0,
                    "vibration_disk": 0.1,
                    "vibration_wall": 0.4,
                    "disk_inertia_ratio": 0.5,
                    "side_clearance": clearance,
                }
            )
    return rows


def test_near_side_counts_and_clear_angles():
    rows = fake_rows(
        {
            30.0: [3.0] * 10,
            70.0: [0.99] + [2.0] * 9,  # 1 of 10 near a side: kept
            80.0: [0.5, -0.2] + [1.5] * 8,
        }
    )  # 2 of 10, one past the side: left out
    means = mean_rows(rows)
    assert {m["gamma_deg"]: m["near_side"] for m in means} == {30.0: 0, 70.0: 1, 80.0: 2}
    table = seed_tables(rows)["random"]
    assert table.gamma_deg[clear_angles(table)].tolist() == [30.0, 70.0]


def test_failures_are_grouped_by_cause_with_their_angles_and_seeds():
    from analysis.impact.failures import failure_causes
    from pages.sections import failure_section

    slid = (
        "ERROR: the disk slid off the end of the wall before it rebounded, at time {}: the "
        "contact is longer than the wall (wall_width) allows at this angle"
    )
    failed = [
        {"lattice": "random", "seed": s, "gamma": 80.5, "error": slid.format(10 + s)}
        for s in range(1, 41)
    ]
    failed += [
        {"lattice": "random", "seed": 7, "gamma": 76.2, "error": slid.format(3.25)},
        {
            "lattice": "square_nu0.1",
            "seed": 3,
            "gamma": 5.7106,
            "error": "ERROR on proc 0: "
            "Pair polyline/exp: segment 56-57 is 0.2493 long, more than reach 0.22",
        },
        {
            "lattice": "square_nu0.1",
            "seed": 9,
            "gamma": 5.7106,
            "error": "ERROR on proc 0: "
            "Pair polyline/exp: segment 12-13 is 0.31 long, more than reach 0.22",
        },
    ]
    assert failure_causes(failed) == {
        "the disk slid off the end of the wall before it rebounded": 41,
        "Pair polyline/exp: segment #-# is # long": 2,
    }
    rows = [
        line for line in failure_section(failed) if line.startswith("| ") and "---" not in line
    ][1:]
    assert len(rows) == 2  # one row per cause, not per impact
    assert rows[0].startswith(
        "| the disk slid off the end of the wall before it rebounded | 41 "
        "| random 76.2 deg: seed 7; random 80.5 deg: 40 seeds |"
    )
    assert "| 2 | square_nu0.1 5.7106 deg: seeds 3, 9 |" in rows[1]
    assert failure_section([]) == []


def test_an_unreadable_result_is_named_and_left_out(tmp_path, capsys):
    import json

    from analysis.table import collect

    good = dict(
        fake_rows({30.0: [3.0]})[0],
        lattice="random",
        nu=0.3,
        steps=100,
        wall_seconds=1.0,
        energy_drift=0.1,
        wall_width=8.0,
    )  # an old result: no drift flag yet
    folders = []
    for name, text in (
        ("good", json.dumps(good)),
        ("truncated", '{"e": 0.3, "bet'),
        ("empty", "{}"),
        ("list", "[1]"),
    ):
        (tmp_path / name).mkdir()
        (tmp_path / name / "result.json").write_text(text)
        folders.append(("random", tmp_path / name))
    rows = collect(folders)
    assert len(rows) == 1 and rows[0]["drift_exceeded"] is True
    warnings = capsys.readouterr().err.strip().splitlines()
    assert len(warnings) == 3
    for name, line in zip(("truncated", "empty", "list"), warnings):
        assert line.startswith(f"warning: {tmp_path / name / 'result.json'}:")


def test_a_study_whose_impacts_all_failed_names_their_angles():
    failed = [{"gamma": "80.5"}, {"gamma": "45.0"}]
    assert angle_span([], failed) == (45.0, 80.5)  # never "from nan to nan degrees"
    assert angle_span([{"gamma_deg": "30.0"}], failed) == (30.0, 30.0)
    with pytest.raises(ValueError, match="at least one impact"):
        angle_span([], [])
