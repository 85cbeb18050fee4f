"""The grazing wall study (analysis/kinds/grazing_wall.py): its walls, the
summary per angle and wall, the paired steps between widths and each
holding's verdict, on synthetic rows whose truth is known (no LAMMPS)."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np
import pytest

from analysis.kinds.grazing_wall import (
    label,
    paired_step,
    plan,
    row_fields,
    summary,
    verdict,
    wall_points,
)
from analysis.kinds.readings import Setup
from runner.study import Study
from runner.study.file import combinations
from runner.study.studies import study_file

WIDTHS = (8.0, 16.0, 32.0, 64.0)
HELD = ("sides", "sides+bottom")
GAMMAS = (45.0, 85.0)
SEEDS = range(1, 17)
CHOICES = tuple(combinations({"wall_fixed": HELD, "wall_width": WIDTHS}))
SLID = "the disk slid off the end of the wall before it rebounded"


def disk(seed: int) -> float:
    """The seed's own disk: a scatter every wall shares (what pairing removes)."""
    return 0.05 * np.sin(3.7 * seed)


def wall_noise(seed: int, width: float) -> float:
    """Each width's own random wall: +-0.004, of opposite signs on consecutive
    widths, exactly zero mean over the 16 seeds."""
    return 0.004 * (-1) ** (seed + int(np.log2(width)))


def row(fixed, width, gamma, seed, e, beta, **more) -> dict:
    return {
        "reading": label({"wall_fixed": fixed, "wall_width": width}),
        "study_lattice": "random",
        "seed": str(seed),
        "gamma_deg": f"{gamma:g}",
        "wall_fixed": fixed,
        "wall_width": str(width),
        "n_wall": str(wall_points(width)),
        "n_wall_points": str(wall_points(width) - 10),
        "e": e if e == "" else repr(float(e)),
        "beta": beta if beta == "" else repr(float(beta)),
        "contact_time": "8.0",
        "side_clearance": "2.0",
        "dt": "0.008",
        "error": "",
        "wall_seconds": repr(width / 8.0),
        **more,
    }


def synthetic(fail_narrow: tuple[int, ...] = ()) -> list[dict]:
    """The beam (sides) whose e falls by 0.1 and beta rises by 0.05 per
    doubling of its width at every width; the layer (sides+bottom) whose 8 R
    wall is off by 0.1 in e and whose 16, 32 and 64 R walls differ by their
    own walls' scatter only (zero mean). ``fail_narrow``: seeds that slide off
    the 8 R layer at the largest angle."""
    rows = []
    for gamma in GAMMAS:
        for seed in SEEDS:
            for width in WIDTHS:
                doublings = np.log2(width / 8.0)
                e = 0.8 - 0.1 * doublings + disk(seed) + wall_noise(seed, width)
                beta = -0.6 + 0.05 * doublings + disk(seed) + wall_noise(seed, width)
                rows.append(row("sides", width, gamma, seed, e, beta))
                e = 0.8 - (0.1 if width == 8.0 else 0.0) + disk(seed) + wall_noise(seed, width)
                beta = -0.6 + disk(seed) + wall_noise(seed, width)
                if width == 8.0 and gamma == GAMMAS[-1] and seed in fail_narrow:
                    rows.append(
                        row("sides+bottom", width, gamma, seed, "", "", error=SLID, wall_seconds="")
                    )
                else:
                    rows.append(row("sides+bottom", width, gamma, seed, e, beta))
    return rows


def test_each_wall_keeps_the_default_walls_spacing():
    """200 points per R of width: the default wall's 1,600 at 8 R."""
    study = Study("g", wall_width=8.0)
    for width in WIDTHS:
        choice = {"wall_fixed": "sides+bottom", "wall_width": width}
        planned = plan(choice, study)
        assert planned.n_wall == wall_points(width) == int(200 * width)
        assert row_fields(choice, Setup({}, CHOICES))["n_wall"] == planned.n_wall
    assert label(CHOICES[-1]) == "sides+bottom_width64"


def test_the_study_file_is_the_cross_of_holdings_and_widths():
    described = study_file("grazing_wall")
    assert described.kind == "grazing_wall" and described.sweep == "cross"
    assert described.axes == {"wall_fixed": HELD, "wall_width": WIDTHS}
    study = described.study
    assert study.gammas() == [45.0, 85.0, 87.0] and study.samples == 16
    assert (study.vn, study.n_disk, study.lattices) == (0.1, 800, ("random",))


def test_the_summary_gives_each_walls_mean_and_standard_error():
    rows = synthetic()
    s = summary(rows, CHOICES)
    assert len(s["table"]) == len(GAMMAS) * len(CHOICES)
    first = s["table"][0]
    assert (first["gamma"], first["fixed"], first["width"]) == (45.0, "sides", 8.0)
    e = [0.8 + disk(k) + wall_noise(k, 8.0) for k in SEEDS]
    assert first["e"][0] == pytest.approx(np.mean(e))
    assert first["e"][1] == pytest.approx(np.std(e, ddof=1) / 4.0)
    assert first["impacts"] == 16 and first["failed"] == 0 and first["ratio"] == 1.0
    widest = [t for t in s["table"] if t["width"] == 64.0]
    assert all(t["ratio"] == pytest.approx(8.0) for t in widest)
    assert s["impacts"] == len(rows) and s["without_result"] == 0
    assert s["points"] == {8.0: 1600, 16.0: 3200, 32.0: 6400, 64.0: 12800}


def test_pairing_by_seed_removes_the_disks_scatter():
    """Each width of the beam is 0.1 lower in e on every seed, up to its own
    walls' +-0.004: the paired difference is -0.1 with a standard error near
    0.002, though each wall's e scatters by 0.035 over the seeds."""
    rows = synthetic()
    step = paired_step(rows, "sides", 8.0, 16.0, 45.0)
    assert step["pairs"] == 16 and step["one_sided"] == []
    assert step["e"][0] == pytest.approx(-0.1)
    assert step["beta"][0] == pytest.approx(0.05)
    assert step["e"][1] == pytest.approx(0.008 / 4.0, rel=0.1)  # +-0.004 on each wall
    assert not step["same"]
    level = paired_step(rows, "sides+bottom", 16.0, 32.0, 85.0)
    assert level["e"][0] == pytest.approx(0.0, abs=1e-12) and level["same"]


def test_the_verdicts_find_the_width_from_which_the_wall_stays_the_same():
    s = summary(synthetic(), CHOICES)
    verdicts = {v["fixed"]: v for v in s["verdicts"]}
    assert verdicts["sides"]["from"] is None
    assert verdicts["sides"]["text"] == "changes with its width at every width measured"
    assert verdicts["sides+bottom"]["from"] == 16.0
    assert verdicts["sides+bottom"]["text"] == "width-independent from 16 R"
    (changed,) = verdicts["sides+bottom"]["changed"]
    assert (changed["narrow"], changed["wide"]) == (8.0, 16.0)
    assert changed["why"].startswith("e moving by +0.100")


def test_a_seed_failing_on_one_wall_only_is_a_change_of_the_wall():
    """The 8 R layer's e made the same as its 16 R's: only the two seeds that
    slide off it at 85 degrees tell them apart, and that is enough."""
    rows = synthetic(fail_narrow=(3, 7))
    for r in rows:
        if r["reading"] == "sides+bottom_width8" and not r["error"]:
            r["e"] = repr(float(r["e"]) + 0.1)
    s = summary(rows, CHOICES)
    step = s["steps"]["sides+bottom"][0][-1]
    assert (step["gamma"], step["pairs"], step["one_sided"]) == (85.0, 14, [3, 7])
    assert not step["same"] and s["steps"]["sides+bottom"][0][0]["same"]
    verdicts = {v["fixed"]: v for v in s["verdicts"]}
    assert verdicts["sides+bottom"]["from"] == 16.0
    assert (
        "2 seeds failing on one of the two walls only at 85 degrees"
        in (verdicts["sides+bottom"]["changed"][0]["why"])
    )
    (cause,) = s["causes"]
    assert (cause["fixed"], cause["width"], cause["seeds"], cause["state"]) == (
        "sides+bottom",
        8.0,
        [3, 7],
        "failed",
    )
    narrow = [
        t for t in s["table"] if (t["fixed"], t["width"], t["gamma"]) == ("sides+bottom", 8, 85)
    ]
    assert narrow[0]["failed"] == 2 and narrow[0]["impacts"] == 14


def test_a_wall_that_changes_only_past_a_width_has_no_width_of_its_own():
    """Same from 8 to 16 R, then different: no width from which it stays the same."""
    same = [{"gamma": 45.0, "same": True}]
    moved = [
        {"gamma": 45.0, "same": False, "one_sided": [], "pairs": 16, "e": (0.05, 0.01),
         "beta": (0.0, 0.01)}
    ]  # fmt: skip
    v = verdict("sides", [8.0, 16.0, 32.0], [same, moved])
    assert v["from"] is None
    assert v["text"] == (
        "changes with its width up to the widest measured: from 16 to 32 R, "
        "e moving by +0.050 +- 0.010 at 45 degrees"
    )
    assert verdict("sides", [8.0, 16.0, 32.0], [moved, same])["from"] == 16.0


def test_the_page_states_the_verdicts_and_the_continuum(tmp_path):
    from pages.grazing_wall import page

    study = {**asdict(Study("grazing_wall")), "options": {"dt": "auto", "route": "lmp"}}
    text = page(synthetic(fail_narrow=(3,)), Setup(study, CHOICES), tmp_path)
    assert (
        "- **sides** (a clamped beam of span W and thickness 2 R): changes with its width" in text
    )
    assert "an elastic layer of thickness 2 R on a rigid base" in text
    assert f"sides+bottom, 8 R, 85 degrees: 1 impact, {SLID} (seed 3)" in text
    assert text.count("| sides+bottom | 8 to 16 |") == len(GAMMAS)
