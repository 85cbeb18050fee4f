"""The study's tables: contacts that reached the wall's ends are counted and
their angles left out of the fits that must not see them."""

from analysis.report import clear_of_the_ends
from analysis.table import mean_rows


def fake_rows(clearances_by_angle: dict[float, list[float]]) -> list[dict]:
    rows = []
    for gamma, clearances in clearances_by_angle.items():
        for seed, clearance in enumerate(clearances, start=1):
            rows.append({"study_lattice": "random", "gamma_deg": gamma, "seed": seed,
                         "cot_gamma": 1.0, "e": 0.5, "beta": 0.1 * seed, "omega": 0.0,
                         "contact_time": 9.0, "vibration_disk": 0.1, "vibration_wall": 0.4,
                         "disk_inertia_ratio": 0.5, "side_clearance": clearance})
    return rows


def test_near_side_counts_and_clear_angles():
    rows = fake_rows({30.0: [3.0] * 10,
                      70.0: [0.99] + [2.0] * 9,          # 1 of 10 near a side: kept
                      80.0: [0.5, -0.2] + [1.5] * 8})    # 2 of 10, one past the side: left out
    means = mean_rows(rows)
    assert {m["gamma_deg"]: m["near_side"] for m in means} == {30.0: 0, 70.0: 1, 80.0: 2}
    kept = clear_of_the_ends(rows, means)
    assert sorted({r["gamma_deg"] for r in kept}) == [30.0, 70.0]
    assert len(kept) == 20
