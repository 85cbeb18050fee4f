"""Fits of the theories to the measured beta(psi), with bootstrap uncertainties.

The data are per-sample results: for each angle, the e, beta and psi of every
sample. A fit uses the means per angle, weighted by their standard errors;
the uncertainty of its parameters is the spread of the fits to bootstrap
resamples of the samples (drawn with replacement within each angle).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from .theory import Compliant, compliant_beta, walton_beta


@dataclass
class Means:
    """Per-angle means of psi, e and beta, with the standard errors of beta."""

    psi: np.ndarray
    e: np.ndarray
    beta: np.ndarray
    beta_se: np.ndarray


def means(groups: list[np.ndarray]) -> Means:
    """Means per angle of an array (samples, 3) of (psi, e, beta) per group.

    Parameters
    ----------
    groups : list of numpy.ndarray
        One (samples, 3) array of (psi, e, beta) per angle
        (``analysis.table.groups``).

    Returns
    -------
    Means
        psi, e and beta averaged per angle, and the standard error of beta; an
        angle whose samples agree exactly gets the median standard error, not
        infinite weight.
    """
    psi = np.array([g[:, 0].mean() for g in groups])
    e = np.array([g[:, 1].mean() for g in groups])
    beta = np.array([g[:, 2].mean() for g in groups])
    se = np.array([g[:, 2].std(ddof=1) / np.sqrt(len(g)) if len(g) > 1 else np.nan for g in groups])
    finite = se[np.isfinite(se) & (se > 0)]
    floor = np.median(finite) if finite.size else 1.0
    # an angle whose samples agree exactly would get infinite weight
    se = np.where(np.isfinite(se) & (se > 0.1 * floor), se, floor)
    return Means(psi, e, beta, se)


# Both models are piecewise in psi (a kink where sliding gives way to
# sticking), so the cost has local minima in mu: the local fit starts from the
# best of a coarse grid of mu.
MU_GRID = np.geomspace(1e-3, 3.0, 25)


def fit_walton(data: Means, K: float) -> np.ndarray:
    """(mu, beta0) of Walton's model, e measured at each angle.

    Parameters
    ----------
    data : Means
        Per-angle means (``means``).
    K : float
        1 + M R^2 / I of the disk.

    Returns
    -------
    numpy.ndarray
        The weighted least-squares (mu, beta0).
    """

    def residuals(p):
        return (walton_beta(data.psi, data.e, p[0], p[1], K) - data.beta) / data.beta_se

    # beta of single impacts can pass 1 (near-normal, tiny tangential velocity)
    beta0 = float(np.clip(np.max(data.beta), -1.4, 1.4))
    mu = min(MU_GRID, key=lambda m: np.sum(residuals([m, beta0]) ** 2))
    return least_squares(residuals, [mu, beta0], bounds=([0.0, -1.5], [5.0, 1.5])).x


def fit_compliant(data: Means, nu: float, alpha: float) -> np.ndarray:
    """mu of the compliant model, with nu and alpha = K measured, e at each angle.

    Parameters
    ----------
    data : Means
        Per-angle means (``means``).
    nu : float
        The lattice's Poisson ratio.
    alpha : float
        K = 1 + M R^2 / I of the disk.

    Returns
    -------
    numpy.ndarray
        The weighted least-squares (mu,), one element.
    """

    def residuals(p):
        model = [
            compliant_beta(psi, Compliant(e=e, mu=p[0], nu=nu, alpha=alpha))
            for psi, e in zip(data.psi, data.e)
        ]
        return (np.array(model) - data.beta) / data.beta_se

    mu = min(MU_GRID, key=lambda m: np.sum(residuals([m]) ** 2))
    return least_squares(residuals, [mu], bounds=([1e-4], [5.0])).x


def bootstrap(
    groups: list[np.ndarray], fit, resamples: int = 200, rng: np.random.Generator | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The fit to the data and the standard deviation of fits to resamples.

    Parameters
    ----------
    groups : list of numpy.ndarray
        One (samples, 3) array of (psi, e, beta) per angle.
    fit : callable
        Maps ``Means`` to an array of parameters, e.g.
        ``lambda d: fit_walton(d, K)``.
    resamples : int
        Number of resamples, each drawing every angle's samples with replacement.
    rng : numpy.random.Generator, optional
        Random draws; default a generator with seed 0 (reproducible).

    Returns
    -------
    best : numpy.ndarray
        The parameters fitted to ``groups``.
    sd : numpy.ndarray
        Their standard deviations over the resamples.
    """
    rng = rng or np.random.default_rng(0)
    best = fit(means(groups))
    draws = []
    for _ in range(resamples):
        resampled = [g[rng.integers(0, len(g), len(g))] for g in groups]
        draws.append(fit(means(resampled)))
    return best, np.std(draws, axis=0, ddof=1)


def reduced_chi2(data: Means, model_beta: np.ndarray, parameters: int) -> float:
    """Weighted squared residuals per degree of freedom: about 1 if the model
    describes the means within their standard errors.

    Parameters
    ----------
    data : Means
        Per-angle means with the standard errors of beta.
    model_beta : numpy.ndarray
        The model's beta at each angle.
    parameters : int
        Number of fitted parameters.

    Returns
    -------
    float
        chi2 / (angles - parameters), the divisor at least 1.
    """
    residuals = (np.asarray(model_beta) - data.beta) / data.beta_se
    return float(np.sum(residuals**2) / max(len(residuals) - parameters, 1))
