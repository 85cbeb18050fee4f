"""The grazing section (analysis/grazing.py): the peak finder and e > 1."""

from __future__ import annotations

import json

import numpy as np
import pytest

from analysis.grazing import grazing_numbers, peak
from tests.synthetic import impact_rows, write_tables


def test_the_peak_of_a_parabola_is_found_exactly():
    x = np.linspace(1.0, 12.0, 12)
    assert peak(x, 1.1 - 0.01 * (x - 6.3) ** 2) == (pytest.approx(6.3), pytest.approx(1.1))
    # uneven spacing: the three points around the top still fix the parabola
    x = np.array([1.0, 2.0, 4.0, 5.0, 5.5, 7.0, 10.0])
    assert peak(x, 1.1 - 0.02 * (x - 5.2) ** 2) == (pytest.approx(5.2), pytest.approx(1.1))


@pytest.mark.parametrize("y", [np.linspace(0.5, 0.9, 6), np.linspace(0.9, 0.5, 6)])
def test_no_peak_where_the_largest_is_at_an_end(y):
    assert peak(np.arange(6.0), y) is None


@pytest.mark.slow
def test_e_above_one_is_significant_only_beyond_its_errors(tmp_path):
    """Synthetic e(tan gamma) with a known peak, seeds sharing an offset: the
    peak comes back within its bootstrap error, and e > 1 is called
    significant for a peak at 1.1 and not for one at 1.0."""
    from pages.report import report_from_tables

    def e_of(top):
        return lambda psi: top - 0.004 * (1.0 / psi - 4.0) ** 2

    for top, significant in ((1.1, "yes"), (1.0, "no")):
        rows = impact_rows("random", lambda psi: -0.5, e_of=e_of(top), seeds=30, rng_seed=3)
        rng = np.random.default_rng(5)
        offsets = {s: 0.01 * rng.standard_normal() for s in range(1, 31)}
        for r in rows:
            r.update(e=r["e"] + offsets[r["seed"]] + 0.005 * rng.standard_normal())
        numbers = grazing_numbers(rows, resamples=100)["random"]
        assert numbers["peak_tan_gamma"] == pytest.approx(
            4.0, abs=3 * numbers["peak_tan_gamma_error"] + 0.05
        )
        assert numbers["peak_e"] == pytest.approx(top, abs=3 * numbers["peak_e_error"])
        folder = tmp_path / f"top{top}"
        write_tables(folder, rows, ["random"])
        page = folder / "results.md"
        report_from_tables(folder, page, resamples=20)
        section = page.read_text().split("## Grazing incidence")[1]
        line = next(x for x in section.splitlines() if x.startswith("| random | "))
        assert line.rstrip(" |").endswith(significant)
        assert "grazing" in json.loads((folder / "fits.json").read_text())
        again = folder / "again.md"  # the page comes back from its tables alone
        report_from_tables(folder, again, resamples=20)
        assert again.read_text() == page.read_text()


def test_a_reading_is_a_row_of_the_page_with_what_differs(tmp_path):
    """Two readings of one synthetic study (another wall stiffness, a 0.1
    speed): one row each, naming what differs, with its own peak."""
    from pages.report import report_from_tables
    from pages.text import reading_differences

    def rows_peaking_at(top: float) -> list[dict]:
        return impact_rows(
            "random", lambda psi: -0.5, e_of=lambda psi: top - 0.004 * (1.0 / psi - 4.0) ** 2,
            seeds=12, rng_seed=4,
        )  # fmt: skip

    study = write_tables(tmp_path / "main", rows_peaking_at(1.05), ["random"])
    stiff = write_tables(tmp_path / "stiff", rows_peaking_at(1.2), ["random"], wall_ka=10.0)
    fast = write_tables(
        tmp_path / "fast", rows_peaking_at(0.9), ["random"],
        options={"dt": 0.004, "stop_rule": "predict", "max_drift": 0.05},
    )  # fmt: skip
    page = tmp_path / "page.md"
    report_from_tables(study, page, resamples=20, readings={"stiff": stiff, "fast": fast})
    section = page.read_text().split("## The same study under other readings")[1]
    rows = {x.split(" | ")[0].lstrip("| "): x for x in section.splitlines() if x.startswith("| ")}
    assert " wall_ka 10.0 " in rows["stiff"] and " dt 0.004 " in rows["fast"]
    assert rows["stiff"].split(" | ")[6].startswith("1.2")  # its own peak e
    info = json.loads((study / "study.json").read_text())
    assert reading_differences(info, info) == "none"
    first = page.read_text()  # the same page again from the same tables
    report_from_tables(study, page, resamples=20, readings={"stiff": stiff, "fast": fast})
    assert page.read_text() == first


def independent_angles(angles: int, seeds: int, rng_seed: int):
    from analysis.statistics.seeds import SeedTable

    rng = np.random.default_rng(rng_seed)
    e = 1.0 + 0.1 * rng.standard_normal((seeds, angles))
    return SeedTable(np.arange(seeds), np.linspace(30.0, 86.0, angles), {"e": e, "beta": e})


def test_the_look_elsewhere_test_agrees_with_sidak_for_independent_angles():
    """Independent angles: the chance that the largest of A standardised means
    reaches z is 1 - (1 - p)^A with p the one-sided normal tail (Sidak)."""
    from scipy.stats import norm

    from analysis.grazing import look_elsewhere

    for z in (2.0, 2.5, 3.0):
        expected = 1.0 - (1.0 - norm.sf(z)) ** 14
        found = look_elsewhere(independent_angles(14, 400, 1), z)
        assert found["angles"] == 14
        assert found["p"] == pytest.approx(expected, abs=0.25 * expected + 0.003)
        assert found["z"] < z  # the largest of 14 is less surprising than one


def test_one_angle_alone_needs_no_correction():
    """With one angle the global p is the normal tail of its z."""
    from scipy.stats import norm

    from analysis.grazing import look_elsewhere

    found = look_elsewhere(independent_angles(1, 400, 2), 2.0)
    assert found["p"] == pytest.approx(norm.sf(2.0), abs=0.008)


def test_e_above_one_counts_only_where_the_normals_agree():
    """A peak of e at 1.3 where the normals disagree is withheld; the verdict
    falls to the largest mean they agree on (1.0 here: not above 1)."""
    from analysis.grazing import grazing_numbers, significant

    def e_of(psi):
        return 1.0 + 0.3 * np.exp(-(((1.0 / psi) - 4.0) ** 2))

    rows = impact_rows("random", lambda psi: -0.5, e_of=e_of, seeds=20, noise_sd=0.01)
    rng = np.random.default_rng(2)
    for r in rows:
        r["e"] = r["e"] + 0.01 * rng.standard_normal()
    plain = grazing_numbers(rows, resamples=50)["random"]
    assert significant(plain)  # without the check the peak counts
    gammas = plain["gamma_deg"]
    top = plain["largest"]["gamma_deg"]
    near_top = [abs(np.tan(np.radians(g)) - 4.0) < 1.5 for g in gammas]
    check = {
        "normals": ["apse", "first_touch", "impulse"],
        "lattices": {
            "random": {
                "gamma_deg": gammas,
                "e_robust": [not n for n in near_top],
                "e_spread": [0.5 if n else 0.0 for n in near_top],
            }
        },
    }
    checked = grazing_numbers(rows, resamples=50, check=check)["random"]
    assert checked["largest"]["gamma_deg"] == top and not checked["largest"]["robust"]
    kept = checked["largest_robust"]
    assert kept["gamma_deg"] != top and kept["e"] < plain["largest"]["e"]
    assert significant(checked) == (kept["global"]["z"] > 2.0)
    assert not significant(checked)
