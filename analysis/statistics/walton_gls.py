"""Walton's fit with the seeds' covariance: generalized least squares.

The per-angle means of beta share their seeds (one seed's surface serves
every angle), so their errors are correlated, about 0.9 between neighbouring
angles: a fit that weights each angle by its own error alone (``fits``'s
measured way) counts the same seeds again at every angle. Here the means'
covariance is estimated from the seeds that have every angle: the per-seed
betas standardised, their correlation shrunk toward the identity by Ledoit
and Wolf's rule (``sklearn.covariance.ledoit_wolf``: with fewer seeds than
angles the sample covariance is singular, and even with more its inverse is
noisy), scaled back by each angle's variance and divided by the number of
seeds. The residuals are whitened by its Cholesky factor, so the cost is
chi^2 = r^T C^-1 r.

Walton's model is piecewise linear in (mu, beta0) under any positive
definite weight as well, so the least is found exactly as ``fits.fit_walton``
finds it: every split of the angles into sliding and plateau solved in
closed form (a whitened linear least squares), every angle put exactly on
the kink, the least of those candidates. The profile over mu (beta0 fitted
at each mu) is exact the same way, and its rise of 4 over its least bounds
mu at two errors with the correlations counted (``mu_bounds``). The errors
of mu and beta0 resample whole seeds through the whole chain, the
covariance estimated anew on each resample.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import cho_factor, solve_triangular
from sklearn.covariance import ledoit_wolf

from ..theory.tangential import walton_beta
from .fits import BETA0_BOUNDS, MU_HIGH, _least_point, profile_bounds
from .seeds import SeedTable, seed_errors

MIN_SEEDS = 4  # fewer complete seeds: no covariance to speak of (a jackknife's resample)
FIT_FROM_SEEDS = 8  # a level's fit: a covariance of the angles from fewer says little


@dataclass(frozen=True)
class CorrelatedMeans:
    """Per-angle means of the seeds that have every angle, and the whitening
    of their covariance (``whiten.T @ whiten`` is its inverse)."""

    psi: np.ndarray
    e: np.ndarray
    beta: np.ndarray
    whiten: np.ndarray
    shrinkage: float
    seeds: int


def correlated_means(table: SeedTable) -> CorrelatedMeans | None:
    """The means of ``table``'s complete seeds (every angle finite) and the
    shrunk covariance of their beta (module docstring); None below
    MIN_SEEDS complete seeds or where an angle's beta does not vary."""
    cot, e, beta = (table.values[k] for k in ("cot_gamma", "e", "beta"))
    complete = np.all(np.isfinite(cot) & np.isfinite(e) & np.isfinite(beta), axis=1)
    n = int(complete.sum())
    if n < MIN_SEEDS:
        return None
    cot, e, beta = cot[complete], e[complete], beta[complete]
    sd = beta.std(axis=0, ddof=1)
    if not np.all(sd > 0):
        return None
    shrunk, shrinkage = ledoit_wolf((beta - beta.mean(axis=0)) / sd, assume_centered=True)
    scale = np.sqrt(np.diag(shrunk))
    correlation = shrunk / np.outer(scale, scale)
    covariance = correlation * np.outer(sd, sd) / n
    lower, _ = cho_factor(covariance, lower=True)
    whiten = solve_triangular(np.tril(lower), np.eye(len(sd)), lower=True)
    return CorrelatedMeans(
        cot.mean(axis=0), e.mean(axis=0), beta.mean(axis=0), whiten, float(shrinkage), n
    )


def _slopes(data: CorrelatedMeans, K: float, e: float | None) -> np.ndarray:
    return (1.0 + (data.e if e is None else np.full_like(data.psi, e))) * K * data.psi


def _chi2(data: CorrelatedMeans, model: np.ndarray) -> np.ndarray:
    """r^T C^-1 r of each row of ``model`` (..., A)."""
    return np.sum(((model - data.beta) @ data.whiten.T) ** 2, axis=-1)


def _through_origin(data: CorrelatedMeans, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The GLS slope of y = a x through the origin, for each row of ``x``."""
    wx, wy = x @ data.whiten.T, y @ data.whiten.T
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.sum(wx * wy, axis=-1) / np.sum(wx * wx, axis=-1)


def candidates(data: CorrelatedMeans, K: float, e: float | None = None) -> np.ndarray:
    """(mu, beta0) rows among which Walton's least GLS cost lies (as
    ``fits.walton_candidates``: every split, every angle on the kink, the
    flat directions at their defined edges, clipped to the bounds)."""
    slope = _slopes(data, K, e)
    order = np.argsort(slope, kind="stable")
    rows = []
    for k in range(len(slope) + 1):  # the k smallest slopes slide
        sliding = np.zeros(len(slope), bool)
        sliding[order[:k]] = True
        if k == 0:  # all on the plateau: beta0 their GLS mean, mu the least that keeps it
            beta0 = _through_origin(data, np.ones((1, len(slope))), data.beta[None])[0]
            rows.append(((1.0 + beta0) / slope[order[0]], beta0))
        elif k == len(slope):  # all slide: beta0 the least above every one
            mu = _through_origin(data, slope[None], data.beta[None] + 1.0)[0]
            rows.append((mu, mu * slope[order[-1]] - 1.0))
        else:
            design = np.column_stack([np.where(sliding, slope, 0.0), (~sliding).astype(float)])
            target = data.beta + sliding
            solution, *_ = np.linalg.lstsq(data.whiten @ design, data.whiten @ target, rcond=None)
            rows.append(tuple(solution))
    # angle j exactly on the kink: every angle's model mu min(slope_i, slope_j) - 1
    capped = np.minimum(slope[None, :], slope[:, None])
    on_kink = np.nan_to_num(_through_origin(data, capped, data.beta[None] + 1.0), nan=0.0)
    on_kink = np.clip(on_kink, 0.0, np.minimum(MU_HIGH, (1.0 + BETA0_BOUNDS[1]) / slope))
    points = np.array(rows + list(zip(on_kink, on_kink * slope - 1.0, strict=True)))
    mu = np.clip(np.nan_to_num(points[:, 0], nan=0.0), 0.0, MU_HIGH)
    return np.column_stack([mu, np.clip(np.nan_to_num(points[:, 1], nan=-1.0), *BETA0_BOUNDS)])


def fit(data: CorrelatedMeans, K: float, e: float | None = None) -> dict:
    """Walton's (mu, beta0) of least GLS cost, exact, with ``chi2`` and
    ``dof`` (angles - 2)."""
    points = candidates(data, K, e)
    e_values = data.e if e is None else e
    models = walton_beta(data.psi, e_values, points[:, :1], points[:, 1:], K)
    costs = _chi2(data, models)
    scale = float(_chi2(data, np.full_like(data.beta, -1.0))) or 1.0
    mu, beta0 = _least_point(points, costs, scale)
    best = float(_chi2(data, walton_beta(data.psi, e_values, mu, beta0, K)))
    return {"mu": float(mu), "beta0": float(beta0), "chi2": best, "dof": len(data.psi) - 2}


def profile(data: CorrelatedMeans, K: float, mu: float, e: float | None = None) -> float:
    """The least GLS cost at a fixed ``mu`` over beta0, exact: the cost is
    quadratic in beta0 between the kinks mu slope_i - 1, so its least is at
    a kink, a bound, or a piece's own least (the angles of the j highest
    kinks on the plateau, the others on their sliding line)."""
    kinks = mu * _slopes(data, K, e) - 1.0
    order = np.argsort(kinks, kind="stable")[::-1]
    plateau = np.zeros((len(kinks), len(kinks)))
    for j in range(len(kinks)):
        plateau[j, order[: j + 1]] = 1.0
    sliding_part = np.where(plateau > 0, 0.0, kinks)
    piece = _through_origin(data, plateau, data.beta[None] - sliding_part)
    beta0 = np.clip(np.concatenate([kinks, np.nan_to_num(piece), BETA0_BOUNDS]), *BETA0_BOUNDS)
    return float(_chi2(data, np.minimum(beta0[:, None], kinks[None, :])).min())


def mu_bounds(
    data: CorrelatedMeans, K: float, e: float | None = None, rise: float = 4.0
) -> tuple[float, float]:
    """The mu whose profile is within ``rise`` of the least (4: two errors,
    the correlations counted), as (lowest, highest); highest infinite where
    mu at the fit's bound fits as well (``fits.profile_bounds``)."""
    return profile_bounds(lambda m: profile(data, K, m, e), fit(data, K, e)["mu"], rise)


def estimates(table: SeedTable, K: float, resamples: int = 200) -> dict | None:
    """The fit (``fit``, e measured per angle), its two-error range of mu
    (``mu_bounds``), and the errors of mu and beta0 over whole seeds
    (``seeds.seed_errors``: the bootstrap from 16 seeds, the jackknife
    below), the covariance estimated anew on every resample; None below
    FIT_FROM_SEEDS complete seeds."""
    data = correlated_means(table)
    if data is None or data.seeds < FIT_FROM_SEEDS:
        return None
    found = fit(data, K)

    def statistic(tables: dict[str, SeedTable]) -> dict:
        resampled = correlated_means(tables["t"])
        if resampled is None:
            return {"mu": np.nan, "beta0": np.nan}
        again = fit(resampled, K)
        return {"mu": again["mu"], "beta0": again["beta0"]}

    sd, errors = seed_errors({"t": table}, statistic, resamples)
    return {
        **found,
        "mu_sd": float(sd["mu"]),
        "beta0_sd": float(sd["beta0"]),
        "mu_bounds": mu_bounds(data, K),
        "shrinkage": data.shrinkage,
        "seeds": data.seeds,
        "errors": errors["method"],
    }
