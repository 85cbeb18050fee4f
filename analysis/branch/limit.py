"""The sliding branch's levels as one chain: each level's friction, the
covariance its errors share through the seeds, and the limit N -> infinity.

The levels (studies/sliding_branch*.toml) run the same seeds, each with the
same surface at every resolution, the finest on the first of them only. A
level's numbers are

- ``mu_eff_mean``: the mean mu_eff over fixed angles (``--angles``; the
  model-free friction where the disk slides), from the per-angle means;
- ``mu_eff_<angle>``: mu_eff at the most grazing angle and at 80.5 degrees;
- ``mu_gls``, ``beta0_gls``: Walton fitted with the seeds' covariance
  (``walton_gls``, e measured per angle, the measured K), at a level with
  at least 8 seeds that have every angle (NaN below: no fit);
- ``mu_paper``, ``beta0_paper``: Walton the paper's way (unweighted means,
  e 0.8, K 3);
- ``mu_compliant``: the compliant model of Maw, Barber and Fawcett the
  measured way (e per angle, the calibration's nu, alpha the measured K,
  each angle weighted by its mean's standard error);
- ``chi2_gls``, ``chi2_paper``, ``chi2_compliant``: each fit's chi^2/dof
  at the level (the GLS fit's with the seeds' covariance, the others' over
  the means' standard errors), which says whether it describes the level.

Their errors and covariances come from the delete-one-seed jackknife
through the whole chain: leaving out one seed at every level that holds it
(seeds 1 to 8 are at every level, 9 to 16 below the finest), each level's
numbers and fits are made again; a level's variance is (n - 1) / n times
the sum of its squared deviations, two levels' covariance the same sum
over the seeds they share with the geometric mean of their factors. For a
mean this is exactly the seeds' variance over n at every level, which a
bootstrap of 8 seeds underestimates by (n - 1) / n; it needs no random
numbers, so it is the same on every machine. The limit is
``extrapolation.limit`` with that covariance: each form fitted with the
levels weighted by their own errors, its errors and chi^2 with the full
covariance (``extrapolation.fit_form``'s sandwich: the inverse of a
covariance that 16 seeds estimate is too noisy to weight by), and the
steps between successive levels from the same covariance.

    python -m analysis.branch.limit docs/studies/sliding_branch \\
        docs/studies/sliding_branch_1600 ... --angles 85.4 86.3 87
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..statistics import extrapolation, walton_gls
from ..statistics.claims import NEAR, verdict
from ..statistics.estimates import CHI2_LIMIT, PAPER
from ..statistics.fits import compliant_curve, fit_compliant, fit_walton, means, reduced_chi2
from ..statistics.measures import mu_eff
from ..theory.tangential import walton_beta
from .steps import Level, add_level_arguments, level

MID_ANGLE = 80.5  # the paper's most grazing angle
ANGLES_HELP = "the angles (degrees) whose mean mu_eff is the friction on the branch"
# The paper's facts judged in the limit: number -> (fact, the paper's value,
# what counts as near, the fit's chi^2 key or None for a model-free number).
CLAIMS = {
    "mu_eff_mean": ("mu near 0.18 (the mean mu_eff over the angles)", 0.18, NEAR["mu"], None),
    "mu_gls": ("Walton's mu near 0.18 (seeds' covariance)", 0.18, NEAR["mu"], "chi2_gls"),
    "mu_paper": ("Walton's mu near 0.18 (the paper's way)", 0.18, NEAR["mu"], "chi2_paper"),
    "mu_compliant": ("the compliant model's mu near 0.18", 0.18, NEAR["mu"], "chi2_compliant"),
    "beta0_gls": ("Walton's beta0 near 0.56 (seeds' covariance)", 0.56, NEAR["beta0"], "chi2_gls"),
    "beta0_paper": (
        "Walton's beta0 near 0.56 (the paper's way)",
        0.56,
        NEAR["beta0"],
        "chi2_paper",
    ),
}
FIT_QUALITY = "chi2_"  # a level's chi^2/dof of a fit: shown, never extrapolated


def level_numbers(x: Level) -> dict[str, float]:
    """One level's numbers (module docstring) from its table."""
    table, K = x.table, x.K
    cot, e, beta = (table.mean(k) for k in ("cot_gamma", "e", "beta"))
    each = mu_eff(cot, e, beta, K)
    out = {"mu_eff_mean": float(np.mean(each[x.chosen]))}
    gamma = np.round(table.gamma_deg, 4)
    out[f"mu_eff_{gamma.max():g}"] = float(each[np.argmax(gamma)])
    if MID_ANGLE in gamma:
        out[f"mu_eff_{MID_ANGLE:g}"] = float(each[gamma == MID_ANGLE][0])
    # the fit with the seeds' covariance from FIT_FROM_SEEDS complete seeds,
    # counted before any is left out (walton_gls: fewer say little)
    data = walton_gls.correlated_means(table)
    nan = {"mu": np.nan, "beta0": np.nan, "chi2": np.nan, "dof": 1}
    enough = data is not None and x.complete >= walton_gls.FIT_FROM_SEEDS
    fit = walton_gls.fit(data, K) if enough else nan
    out.update(mu_gls=float(fit["mu"]), beta0_gls=float(fit["beta0"]))
    per_angle = means(table)
    paper = fit_walton(per_angle, PAPER["K"], PAPER["e"], weighted=False)
    out.update(mu_paper=float(paper[0]), beta0_paper=float(paper[1]))
    # the compliant model (Maw, Barber and Fawcett) the measured way: e per
    # angle, the calibration's nu, alpha the measured K, weighted by the means' errors
    compliant = float(fit_compliant(per_angle, x.nu, K)[0])
    out["mu_compliant"] = compliant
    # how well each fit describes the level (not carried to a limit)
    out["chi2_gls"] = fit["chi2"] / fit["dof"]
    model = walton_beta(per_angle.psi, PAPER["e"], paper[0], paper[1], PAPER["K"])
    out["chi2_paper"] = reduced_chi2(per_angle, model, 2)
    curve = compliant_curve(per_angle, compliant, x.nu, K)
    out["chi2_compliant"] = reduced_chi2(per_angle, curve, 1)
    return out


def jackknife_covariance(
    seed_sets: list[np.ndarray], left_out: dict[int, np.ndarray]
) -> np.ndarray:
    """The levels' covariance (module docstring) from each level's number
    with each seed left out (``left_out``: seed -> per level, ignored where
    the level lacks the seed)."""
    seeds = sorted(left_out)
    values = np.array([left_out[s] for s in seeds])  # (seeds, levels)
    holds = np.array([[np.isin(s, level) for level in seed_sets] for s in seeds])
    n = holds.sum(axis=0)
    centre = np.array([values[holds[:, j], j].mean() for j in range(len(seed_sets))])
    deviation = np.where(holds, values - centre, 0.0)
    factor = np.sqrt((n - 1) / n)
    return np.outer(factor, factor) * (deviation.T @ deviation)


Numbers = Callable[[Level], dict[str, float]]


def chain(
    folders: list[Path],
    angles: list[float],
    numbers: Numbers = level_numbers,
) -> dict:
    """Each level's ``numbers`` (default ``level_numbers``) with their seed
    errors, and each number's limit.

    Returns
    -------
    dict
        ``levels`` (N per folder), ``seeds`` (per level), ``values`` and
        ``sd`` (number -> per level), ``covariance`` (number -> matrix over
        the levels) and ``limits`` (number -> ``extrapolation.limit``).

    Raises
    ------
    ValueError
        If a level lacks one of ``angles`` or has fewer than two seeds.
    """
    loaded = [level(f, angles) for f in folders]
    seed_sets = [x.table.seeds for x in loaded]
    if any(len(seeds) < 2 for seeds in seed_sets):
        raise ValueError("a level with fewer than 2 seeds has no error")
    n = [n_disk(f) for f in folders]
    best = [numbers(x) for x in loaded]
    keys = [k for k in best[0] if not k.startswith(FIT_QUALITY)]
    left_out = {}
    for seed in np.unique(np.concatenate(seed_sets)):
        left_out[int(seed)] = [
            numbers(x.without(seed)) if seed in x.table.seeds else None for x in loaded
        ]
    out: dict = {"levels": n, "seeds": [len(s) for s in seed_sets], "folders": folders}
    out.update(values={}, sd={}, covariance={}, limits={})
    out["chi2"] = {k: [b[k] for b in best] for k in best[0] if k.startswith(FIT_QUALITY)}
    for key in keys:
        values = np.array([b[key] for b in best])
        cov = jackknife_covariance(
            seed_sets,
            {
                s: np.array([np.nan if r is None else r[key] for r in rows])
                for s, rows in left_out.items()
            },
        )
        sd = np.sqrt(np.diag(cov))
        steps = {
            n[i]: (
                values[i] - values[i - 1],
                float(np.sqrt(cov[i, i] + cov[i - 1, i - 1] - 2 * cov[i, i - 1])),
            )
            for i in range(1, len(n))
            if n[i] == 2 * n[i - 1]
        }
        covariance = {(n[a], n[b]): cov[a, b] for a in range(len(n)) for b in range(len(n))}
        out["values"][key], out["sd"][key], out["covariance"][key] = values, sd, cov
        out["limits"][key] = extrapolation.limit(
            list(zip(n, values, sd, strict=True)),
            steps=steps,
            seeds=dict(zip(n, out["seeds"], strict=True)),
            covariance=covariance,
            sandwich=True,  # 16 seeds estimate 5 levels' covariance: fit by their own errors
        )
    return out


def n_disk(folder: Path) -> int:
    """The level's disk points, from its study.json."""
    study = json.loads((folder / "study.json").read_text())
    return int(study["n_disk"])


def judged(out: dict) -> list[str]:
    """Each of the paper's facts (CLAIMS) judged on its number's limit by
    ``claims.verdict``: the error the limit's statistical one and its form's
    band in quadrature; no limit, no verdict but "undecided". A fit whose
    chi^2/dof at the finest level is above CHI2_LIMIT does not describe the
    rows, which the line says: its parameter is the fit's, not the friction's."""
    lines = []
    for key, (fact, paper, near, fit) in CLAIMS.items():
        limit = out["limits"][key]
        if limit["status"] != "limit":
            lines.append(f"{fact}: undecided (no limit: {limit['status']})")
            continue
        error = float(np.hypot(limit["stat"], limit["systematic"]))
        line = f"{fact}: {verdict(limit['value'], error, paper, near)} "
        line += f"({limit['value']:.3f} +- {error:.3f})"
        fitted = [c for c in out["chi2"].get(fit, []) if np.isfinite(c)]
        if fitted and fitted[-1] > CHI2_LIMIT:  # the finest level the fit was made at
            line += f"; the fit fails, chi2/dof {fitted[-1]:.1f} at the finest level fitted"
        lines.append(line)
    return lines


def describe(limit: dict) -> str:
    """A limit in one line: value, errors and band, or why there is none."""
    if limit["status"] != "limit":
        halving = limit.get("halvings") or {}
        if limit["status"] == "not converged":
            (d, s), (d0, s0) = halving["last"], halving["before"]
            return (
                f"not converged: last step {d:+.4f} +- {s:.4f}, "
                f"the one before {d0:+.4f} +- {s0:.4f}"
            )
        tried = {
            f: f"p {fit['p_value']:.3f}" for f, fit in limit["forms"].items() if fit is not None
        }
        return f"{limit['status']} ({', '.join(f'{f} {p}' for f, p in tried.items())})"
    low, high = limit["band"]
    forms = ", ".join(f"{f} p {limit['forms'][f]['p_value']:.2f}" for f in limit["described_by"])
    return (
        f"{limit['value']:.3f} +- {limit['stat']:.3f} (stat) +- {limit['systematic']:.3f} "
        f"(form: {low:.3f} to {high:.3f}; {forms})"
    )


def main(argv: list[str] | None = None) -> int:
    """Print each level's friction and Walton's fits with seed errors, and their limits."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    add_level_arguments(parser, ANGLES_HELP)
    args = parser.parse_args(argv)
    try:
        out = chain(args.folders, args.angles)
    except (ValueError, OSError) as error:
        parser.error(str(error))
    print(
        f"levels {out['levels']} points, seeds {out['seeds']}; "
        "errors: each seed left out at every level, through the whole chain"
    )
    for key, per_level in out["chi2"].items():
        print(f"{key}/dof: " + "  ".join(f"{v:.1f}" for v in per_level))
    for key in out["values"]:
        cells = "  ".join(
            f"{v:.3f} +- {s:.3f}" for v, s in zip(out["values"][key], out["sd"][key], strict=True)
        )
        print(f"{key}: {cells}")
        print(f"  limit: {describe(out['limits'][key])}")
    print("the paper's facts in the limit (analysis.statistics.claims's rule):")
    for line in judged(out):
        print(f"  {line}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
