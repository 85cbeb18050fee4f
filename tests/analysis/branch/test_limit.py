"""The sliding branch's levels as one chain (analysis/branch/limit.py):
a synthetic chain whose limit is known, the seeds shared across levels
counted in its error, the groups of seeds it resamples."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.branch.limit import chain, jackknife_covariance, main
from analysis.branch.steps import Level
from analysis.statistics.measures import mu_eff
from analysis.theory.tangential import walton_beta
from tests.synthetic import GAMMA_DEG, impact_rows, write_tables

LIMIT, RISE = 0.25, 0.06  # mu(h) = LIMIT + RISE h, h = sqrt(800 / N)
LEVELS = {800: 16, 1600: 16, 3200: 16, 6400: 16, 12800: 8}
ANGLES = [float(g) for g in GAMMA_DEG[-3:]]  # past Walton's kink (cot gamma 0.43 at mu 0.3)


def levels(folder, rng_seed: int, offset_sd: float = 0.03, noise_sd: float = 0.01) -> list:
    """One chain: every level's seed s has the same surface (the same offset
    of beta at every angle and every level), the finest level the first 8;
    each impact's own noise is the level's."""
    out = []
    noise = np.random.default_rng([rng_seed, 1])
    for n, seeds in LEVELS.items():
        mu = LIMIT + RISE * np.sqrt(800 / n)
        rows = impact_rows(
            "random",
            lambda psi, mu=mu: walton_beta(psi, 0.8, mu, -0.3, 3.0),
            seeds=seeds,
            offset_sd=offset_sd,
            noise_sd=0.0,
            rng_seed=rng_seed,
        )
        for row in rows:
            row["beta"] += noise_sd * noise.standard_normal()
        out.append(write_tables(folder / f"n{n}", rows, ["random"], n_disk=n))
    return out


def branch_mean(x: Level) -> dict[str, float]:
    """The mean mu_eff over the chosen angles alone (the chain's first number)."""
    means = (x.table.mean(k) for k in ("cot_gamma", "e", "beta"))
    return {"mu_eff_mean": float(np.mean(mu_eff(*means, x.K)[x.chosen]))}


def test_a_chain_with_a_known_limit_finds_it_within_its_errors(tmp_path):
    fits = []
    for rng_seed in range(40):
        out = chain(levels(tmp_path / str(rng_seed), rng_seed), ANGLES, numbers=branch_mean)
        fits.append(out["limits"]["mu_eff_mean"]["forms"]["h"])  # the true form
    found = np.array([f["limit"] for f in fits])
    errors = np.array([f["limit_sd"] for f in fits])
    # unbiased: the chains' mean limit within three of its standard errors
    assert abs(found.mean() - LIMIT) < 3 * found.std(ddof=1) / np.sqrt(len(found))
    # the errors are the limits' true spread (0.98 of it): every level shares
    # the seeds' shift, and a covariance of 5 levels from 16 seeds inverted
    # for the weights (plain GLS) would shrink them to 0.79 of it
    assert 0.85 < np.median(errors) / found.std(ddof=1) < 1.3
    assert np.mean(np.abs(found - LIMIT) < 2 * errors) >= 0.85
    # the true form describes most chains (its chi^2 with the estimated covariance)
    assert np.mean([f["describes"] for f in fits]) >= 0.75


def test_the_levels_share_their_seeds_errors(tmp_path):
    out = chain(levels(tmp_path, 3), ANGLES, numbers=branch_mean)
    cov = out["covariance"]["mu_eff_mean"]
    correlation = cov / np.sqrt(np.outer(np.diag(cov), np.diag(cov)))
    # one surface per seed at every level: the levels' errors move together
    assert correlation[0, 3] > 0.9
    assert correlation[3, 4] > 0.5  # the finest level shares half the seeds
    assert out["seeds"] == list(LEVELS.values())


def test_the_jackknife_of_a_mean_is_the_seeds_covariance_over_n():
    rng = np.random.default_rng(2)
    x = rng.standard_normal(16)
    y = x + 0.5 * rng.standard_normal(16)  # a finer level: the same seeds' surfaces
    sets = [np.arange(1, 17), np.arange(1, 9)]
    left_out = {
        s: np.array([np.delete(x, s - 1).mean(), np.delete(y[:8], s - 1).mean() if s <= 8 else 0.0])
        for s in range(1, 17)
    }
    cov = jackknife_covariance(sets, left_out)
    assert cov[0, 0] == pytest.approx(x.var(ddof=1) / 16, rel=1e-12)
    assert cov[1, 1] == pytest.approx(y[:8].var(ddof=1) / 8, rel=1e-12)
    # the shared seeds' covariance, from 8 of the 16 (with the factors' means)
    shared = np.sum((x[:8] - x.mean()) * (y[:8] - y[:8].mean()))
    assert cov[0, 1] == pytest.approx(shared / np.sqrt(16 * 15 * 8 * 7), rel=1e-12)


def test_the_command_prints_each_level_and_the_limit(tmp_path, capsys):
    folders = [str(f) for f in levels(tmp_path, 5)]
    assert main([*folders, "--angles", *map(str, ANGLES)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("levels [800, 1600, 3200, 6400, 12800] points, seeds [16, 16, 16, 16, 8]")
    for fit in ("gls", "paper", "compliant"):
        assert f"chi2_{fit}/dof:" in out
    numbers = [line.split(":")[0] for line in out.splitlines() if "+-" in line and line[0] != " "]
    assert numbers == ["mu_eff_mean", f"mu_eff_{max(GAMMA_DEG):g}", "mu_gls", "beta0_gls"] + [
        "mu_paper",
        "beta0_paper",
        "mu_compliant",
    ]
    assert out.count("  limit: ") == len(numbers)
    # six facts, each judged; the synthetic chain's beta0 (-0.3) misses 0.56
    facts = out.split("the paper's facts in the limit")[1].splitlines()[1:]
    assert len(facts) == 6
    assert facts[0].startswith("  mu near 0.18 (the mean mu_eff over the angles): ")
    assert "Walton's beta0 near 0.56 (seeds' covariance): misses" in out


def test_a_level_missing_an_angle_is_one_line(tmp_path, capsys):
    folders = [str(f) for f in levels(tmp_path, 5)]
    with pytest.raises(SystemExit) as exit_:
        main([*folders, "--angles", "88.5"])
    assert exit_.value.code == 2
    assert "does not have every angle of [88.5]" in capsys.readouterr().err


def test_walton_with_the_seeds_covariance_needs_8_complete_seeds(tmp_path):
    folders = levels(tmp_path, 5)
    finest = folders[-1] / "impacts.csv"
    lines = finest.read_text().splitlines(keepends=True)
    finest.write_text("".join(lines[:-1]))  # seed 8's most grazing impact failed
    out = chain(folders, ANGLES)
    # 7 seeds with every angle at the finest level: no fit there, the others kept
    assert np.isnan(out["values"]["mu_gls"][-1]) and np.isfinite(out["values"]["mu_gls"][:-1]).all()
    assert np.isfinite(out["values"]["mu_eff_mean"]).all()
