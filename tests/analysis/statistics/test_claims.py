"""The paper's claims table (analysis/statistics/claims.py) and the results page's
statistics, from a small synthetic study whose answers are known."""

from __future__ import annotations

import json

import pytest

from analysis.poisson import common_wall
from analysis.statistics.claims import verdict
from analysis.theory.tangential import walton_beta
from pages.report import report_from_tables
from tests.synthetic import impact_rows, write_tables

LATTICES = ["random", "triangular", "square_nu0.1", "square_nu0.3"]


def study_rows(ka_ratios=(1.0, 1.0)) -> list[dict]:
    """The random disk as the paper saw it (e 0.8, K 3, mu 0.18, beta0 0.56);
    the triangular disk slipping at every angle (beta -0.5); two square disks
    whose beta0 differ by 0.3."""
    rows = impact_rows(
        "random", lambda psi: walton_beta(psi, 0.8, 0.18, 0.56, 3.0), seeds=30, rng_seed=1
    )
    rows += impact_rows("triangular", lambda psi: -0.5 + 0 * psi, seeds=30, rng_seed=2)
    for (name, beta0, nu), ratio in zip(
        (("square_nu0.1", 0.3, 0.1), ("square_nu0.3", 0.6, 0.3)), ka_ratios
    ):
        rows += impact_rows(
            name,
            lambda psi, b=beta0: walton_beta(psi, 0.8, 0.2, b, 3.0),
            seeds=30,
            nu=nu,
            ka_wall_over_disk=ratio,
            rng_seed=3,
        )
    return rows


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    folder = write_tables(tmp_path_factory.mktemp("tables"), study_rows(), LATTICES)
    page = folder.parent / "page" / "results.md"
    page.parent.mkdir()
    report_from_tables(folder, page, resamples=20)
    return json.loads((folder / "fits.json").read_text()), page.read_text(), folder


def find(fits: dict, text: str) -> dict:
    (claim,) = [c for c in fits["claims"] if text in c["fact"]]
    return claim


@pytest.mark.slow
def test_the_claims_have_the_known_numbers_and_verdicts(made):
    fits, _, _ = made
    e = find(fits, "e near 0.8")
    assert e["model_free"]["value"] == pytest.approx(0.8, abs=1e-12)
    assert e["model_free_verdict"] == "meets" and e["procedure_verdict"] == "-"
    mu = find(fits, "Walton's mu")
    assert mu["procedure"]["value"] == pytest.approx(0.18, abs=0.01)
    assert mu["procedure"]["systematic"] is None  # the fit describes the data
    # on the sliding line, with e 0.8 and K 3, mu_eff is mu
    assert mu["model_free"]["value"] == pytest.approx(0.18, abs=0.01)
    assert mu["procedure_verdict"] == mu["model_free_verdict"] == "meets"
    beta0 = find(fits, "beta0 near 0.56")
    assert beta0["procedure"]["value"] == pytest.approx(0.56, abs=0.02)
    assert beta0["model_free"]["value"] == pytest.approx(0.56, abs=0.02)
    assert beta0["procedure_verdict"] == beta0["model_free_verdict"] == "meets"
    triangular = find(fits, "triangular disk")
    assert triangular["model_free"]["value"] == 0.0
    assert triangular["model_free_verdict"] == "meets"
    ends = find(fits, "runs off the wall")
    assert ends["model_free"]["value"] == 0.0 and ends["model_free_verdict"] == "meets"
    same = find(fits, "the same for nu")
    assert same["procedure"]["value"] == pytest.approx(0.3, abs=0.03)
    assert same["model_free"]["value"] == pytest.approx(0.3, abs=0.03)
    assert same["procedure_verdict"] == same["model_free_verdict"] == "misses"
    compliant = find(fits, "compliant")
    number = compliant["procedure"]
    assert compliant["procedure_verdict"] == verdict(number["value"], number["error"], 0.3, 0.05)


@pytest.mark.slow
def test_the_page_shows_the_claims_both_fits_and_the_measures(made):
    fits, page, folder = made
    assert "## The paper's claims" in page and "## Model-free measures" in page
    for claim in fits["claims"]:
        assert f"| {claim['fact']} |" in page
    assert page.count("| Walton | the paper's way |") == 4
    assert page.count("| compliant | the measured way |") == 4
    assert "sd over 20 seed-bootstrap resamples" in page
    means = (folder / "means.csv").read_text().splitlines()
    assert "e_seed_sd" in means[0].split(",") and "e_se" not in means[0].split(",")
    assert (folder.parent / "page" / "figures" / "mu_eff.png").exists()


@pytest.mark.slow
def test_the_nu_verdict_names_what_else_differs(made):
    _, page, _ = made
    section = page.split("## Does beta depend on the Poisson ratio?")[1].split("\n## ")[0]
    assert "differ only" not in section
    assert "shear" in section and "vibrations" in section
    assert "each disk met a wall of its own stiffness" in section
    assert "**differ**" in section  # 0.3 apart with small errors


def test_one_wall_is_read_from_the_tables_or_study_json():
    pair = ("square_nu0.1", "square_nu0.3")
    # the wall's ka the same multiple of each disk's: two walls
    wall = common_wall({}, study_rows((1.0, 1.0)), pair)
    assert wall["common"] is False and wall["same_multiple"]
    # the wall's ka in its own terms (another multiple of each disk's), the same points
    wall = common_wall({}, study_rows((0.9, 1.1)), pair)
    assert wall["common"] is True and not wall["same_multiple"] and wall["same_points"]
    rows = study_rows((0.9, 1.1))
    first = next(i for i, r in enumerate(rows) if r["study_lattice"] == pair[0])
    rows[first] = dict(rows[first], n_wall_points=1)  # a seed whose walls differ
    assert common_wall({}, rows, pair)["common"] is False
    assert common_wall({"common_wall": True}, study_rows(), pair)["common"] is True


@pytest.mark.parametrize(
    "value, error, paper, near, expected",
    [
        (0.2, 0.01, 0.18, 0.05, "meets"),  # 0.18 to 0.22 inside 0.13 to 0.23
        (0.2, 0.03, 0.18, 0.05, "undecided"),  # 0.14 to 0.26 crosses 0.23
        (0.3, 0.01, 0.18, 0.05, "misses"),  # 0.28 to 0.32 above 0.23
        (0.3, 0.1, 0.0, None, "undecided"),  # 3 errors
        (0.15, 0.1, 0.0, None, "meets"),
        (0.35, 0.1, 0.0, None, "misses"),
        (None, 0.1, 0.0, 0.1, "-"),
        (0.0, 0.0, 0.0, 0.1, "meets"),
        (0.2, 0.0, 0.0, None, "misses"),
    ],
)
def test_the_verdict_rule(value, error, paper, near, expected):
    assert verdict(value, error, paper, near) == expected


def test_rows_without_a_sliding_branch_bound_mu_from_below_only():
    """No branch in the rows: the model-free mu is mu_eff at the most
    grazing angle, a lower bound, which misses only if it lies above the
    claim's range (0.18 +- 0.05) by two errors, never for lying below it."""
    from analysis.statistics.claims import _friction, lower_bound_verdict

    def fits(value: float) -> dict:
        mu_eff = {"gamma_deg": [45.0, 80.5], "cot_gamma": [1.0, 0.167],
                  "value": [0.05, value], "sd": [0.004, 0.01]}  # fmt: skip
        measures = {"mu_branch": {"value": float("nan"), "sd": float("nan")}, "mu_eff": mu_eff}
        return {"lattices": {"random": {"measures": measures}}}

    bound, said = _friction(fits(0.2), "random")
    assert bound["value"] == 0.2 and bound["lower_bound"]
    assert said.startswith("mu_eff at 80.5 degrees, a lower bound")
    assert lower_bound_verdict(0.2, 0.01, 0.18, 0.05) == "undecided"
    assert lower_bound_verdict(0.24, 0.01, 0.18, 0.05) == "undecided"  # 0.22: within reach
    assert lower_bound_verdict(0.26, 0.01, 0.18, 0.05) == "misses"
    assert lower_bound_verdict(0.05, 0.01, 0.18, 0.05) == "undecided"  # below: x may be 0.18
    assert verdict(0.05, 0.01, 0.18, 0.05) == "misses"
