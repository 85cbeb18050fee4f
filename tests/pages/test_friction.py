"""Friction against the rms slope (pages/friction.py): each slope's levels
chained, the slope from the profile's record, the table and the figure."""

from __future__ import annotations

import csv

import pytest

from analysis.branch.limit import main as limit_main
from analysis.theory.tangential import walton_beta
from ground.errors import InputError
from pages.friction import PAGE, by_slope, main, rms_slope, table
from tests.helpers import ROOT
from tests.perturbed_page import perturbing_reader
from tests.synthetic import GAMMA_DEG, impact_rows, write_tables

ANGLES = [str(g) for g in GAMMA_DEG[-3:]]


def level(folder, mu: float, n_disk: int, length: float, profile: str = "continuous"):
    rows = impact_rows(
        "random",
        lambda psi: walton_beta(psi, 0.8, mu, -0.3, 3.0),
        seeds=16,
        offset_sd=0.02,
        noise_sd=0.005,
        rng_seed=n_disk,
    )
    study = {"n_disk": n_disk, "roughness": 0.03, "roughness_length": length}
    return write_tables(folder, rows, ["random"], roughness_profile=profile, **study)


def test_each_slope_is_a_chain_of_its_levels(tmp_path, capsys):
    folders = [
        level(tmp_path / "b1600", 0.28, 1600, 0.06),
        level(tmp_path / "a", 0.20, 800, 0.1),
        level(tmp_path / "b800", 0.30, 800, 0.06),
    ]
    figure = tmp_path / "figure" / "friction.png"
    figure.parent.mkdir()
    assert main([*map(str, folders), "--angles", *ANGLES, "--figure", str(figure)]) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.startswith("| 0.")]
    # by slope, then by the disk points; slopes h / L = 0.03 / 0.1 and 0.03 / 0.06
    assert [r.split(" | ")[:2] for r in rows] == [
        ["| 0.3", "800"],
        ["| 0.5", "800"],
        ["| 0.5", "1,600"],
    ]
    # mu on the branch is the synthetic rows' mu (Walton's sliding branch)
    assert [float(r.split(" | ")[2].split(" +- ")[0]) for r in rows] == pytest.approx(
        [0.20, 0.30, 0.28], abs=0.01
    )
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_sampled_profile_has_no_slope_h_over_l(tmp_path):
    folder = level(tmp_path / "s", 0.2, 800, 0.1, profile="sampled")
    with pytest.raises(InputError, match="not a continuous profile"):
        rms_slope(folder)


LEVELS = ["sliding_branch_slope015", "sliding_branch_slope03", "sliding_branch"]
LEVELS += ["sliding_branch_1600", "sliding_branch_3200", "sliding_branch_6400"]
LEVELS += ["sliding_branch_12800"]


@pytest.mark.last  # reads the committed tables, which the pages made again rewrite
def test_the_committed_friction_page_is_the_same_from_tables_moved_in_the_last_bits(
    monkeypatch, capsys
):
    """As another CPU would read them: the committed page's table again, and
    the chain's printed numbers (docs/model.md quotes them) unchanged."""
    folders = [ROOT / "docs" / "studies" / name for name in LEVELS]
    paper_slope = [*map(str, folders[2:]), "--angles", "85.4", "86.3", "87"]
    committed = (ROOT / "docs" / "friction" / PAGE).read_text()
    assert table(by_slope(folders, [85.4, 86.3, 87.0])) in committed
    assert limit_main(paper_slope) == 0
    before = capsys.readouterr().out

    reader = perturbing_reader(4)
    monkeypatch.setattr(csv, "DictReader", reader)
    assert table(by_slope(folders, [85.4, 86.3, 87.0])) in committed
    assert limit_main(paper_slope) == 0
    assert capsys.readouterr().out == before
    # every impact of both commands was read moved
    rows = {f: len((f / "impacts.csv").read_text().splitlines()) - 1 for f in folders}
    assert reader.count == sum(rows.values()) + sum(rows[f] for f in folders[2:])
