"""Fits of the theories to the per-angle means of beta(psi) (MODEL.md section 6).

A fit takes the means per angle (``Means``) and either weights each angle by
the standard error of its mean of beta (``weighted=True``) or weights every
angle alike (least squares on the means, the paper's way). e is either the
measured mean at each angle or a fixed number (the paper's 0.8). The errors
of the fitted parameters come from the seed bootstrap (``analysis.statistics.seeds``),
not from here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, least_squares, minimize_scalar

from ..theory.tangential import Compliant, compliant_beta, walton_beta
from .seeds import SeedTable


@dataclass
class Means:
    """Per-angle means of psi, e and beta, with the standard errors of beta."""

    psi: np.ndarray
    e: np.ndarray
    beta: np.ndarray
    beta_se: np.ndarray

    def select(self, keep: np.ndarray) -> Means:
        """The angles where ``keep`` is True."""
        return Means(self.psi[keep], self.e[keep], self.beta[keep], self.beta_se[keep])


def means(table: SeedTable) -> Means:
    """The per-angle means of a lattice's impacts, at the angles with at least
    two impacts.

    Parameters
    ----------
    table : SeedTable
        One lattice's impacts by seed and angle.

    Returns
    -------
    Means
        psi, e and beta averaged per angle and the standard error of the mean
        of beta (sd / sqrt(n)); only an angle whose samples agree exactly (a
        standard error of exactly 0) gets the median standard error instead,
        not infinite weight.
    """
    keep = table.counts() > 1
    se = table.standard_error("beta")[keep]
    return Means(
        table.mean("cot_gamma")[keep],
        table.mean("e")[keep],
        table.mean("beta")[keep],
        weights_floor(se),
    )


def weights_floor(se: np.ndarray) -> np.ndarray:
    """Standard errors with only the exactly zero (or undefined) ones replaced
    by the median of the others (1 if there are none): an angle whose samples
    agree exactly would get infinite weight. Every other standard error, however
    small, is kept, so the fit weights each angle as documented.

    Parameters
    ----------
    se : numpy.ndarray
        Standard errors of the per-angle means.

    Returns
    -------
    numpy.ndarray
        The same, with the zeros replaced.
    """
    se = np.asarray(se, float)
    usable = np.isfinite(se) & (se > 0)
    floor = np.median(se[usable]) if usable.any() else 1.0
    return np.where(usable, se, floor)


def _scale(data: Means, weighted: bool) -> np.ndarray:
    return data.beta_se if weighted else np.ones_like(data.beta)


def _e(data: Means, e: float | None) -> np.ndarray:
    return data.e if e is None else np.full_like(data.psi, e)


# Both models are piecewise in psi (a kink where sliding gives way to
# sticking), so the cost has local minima. Walton's fit starts from every
# split of the angles into a sliding set (the smallest psi) and a plateau,
# each solved in closed form, and polishes the cheapest (on seven committed
# tables, both ways, within 4e-4 of the least cost from 16 grid starts).
# The profile's grids: mu up to the fit's bound MU_HIGH, where a plateau at
# every angle leaves mu free, and beta0.
MU_HIGH = 5.0
MU_GRID = np.concatenate([[0.0], np.geomspace(1e-3, MU_HIGH, 60)])
BETA0_GRID = np.linspace(-1.5, 1.5, 121)
# The compliant model's scan of mu (each point a sum over the angles of its
# closed-form curve: the cost of its fit).
COMPLIANT_MU_GRID = np.geomspace(1e-3, 3.0, 25)


def walton_costs(
    data: Means, K: float, mu, beta0, e: float | None = None, weighted: bool = True
) -> np.ndarray:
    """The cost (sum of squared residuals, weighted as ``fit_walton``
    weighs them) of Walton's model at every (mu, beta0) of two arrays, as a
    (len(mu), len(beta0)) array."""
    mu, beta0 = np.asarray(mu, float), np.asarray(beta0, float)
    model = walton_beta(data.psi, _e(data, e), mu[:, None, None], beta0[None, :, None], K)
    return np.sum(((model - data.beta) / _scale(data, weighted)) ** 2, axis=-1)


def fit_walton(data: Means, K: float, e: float | None = None, weighted: bool = True) -> np.ndarray:
    """(mu, beta0) of Walton's model by least squares on the per-angle means,
    polished from the cheapest of ``walton_splits``' starts.

    Parameters
    ----------
    data : Means
        Per-angle means (``means``).
    K : float
        1 + M R^2 / I of the disk (the paper's way: 3).
    e : float, optional
        A fixed e (the paper's way: 0.8); default the measured mean e at each angle.
    weighted : bool
        Residuals over the standard errors of the means (True), or all alike.

    Returns
    -------
    numpy.ndarray
        (mu, beta0).
    """
    e_values, scale = _e(data, e), _scale(data, weighted)

    def residuals(p):
        return (walton_beta(data.psi, e_values, p[0], p[1], K) - data.beta) / scale

    starts = walton_splits(data, K, e, weighted)
    cheapest = starts[np.argmin([np.sum(residuals(p) ** 2) for p in starts])]
    return least_squares(residuals, cheapest, bounds=([0.0, -1.5], [MU_HIGH, 1.5])).x


def walton_splits(
    data: Means, K: float, e: float | None = None, weighted: bool = True
) -> np.ndarray:
    """(mu, beta0), one row per split of the angles into a sliding set, the
    s smallest psi (beta + 1 = mu (1 + e) K psi, least squares through the
    origin), and a plateau, the others (beta0 their weighted mean), for s =
    0 to the number of angles, clipped to the fit's bounds."""
    order = np.argsort(data.psi)
    slope = ((1.0 + _e(data, e)) * K * data.psi)[order]
    beta = data.beta[order]
    weight = 1.0 / _scale(data, weighted)[order] ** 2
    # sums over the s smallest psi (sliding) and over the rest (plateau)
    sliding_xy = np.concatenate([[0.0], np.cumsum(weight * slope * (beta + 1.0))])
    sliding_xx = np.concatenate([[0.0], np.cumsum(weight * slope**2)])
    plateau_y = np.concatenate([np.cumsum((weight * beta)[::-1])[::-1], [0.0]])
    plateau_w = np.concatenate([np.cumsum(weight[::-1])[::-1], [0.0]])
    with np.errstate(divide="ignore", invalid="ignore"):
        mu = sliding_xy / sliding_xx
        beta0 = plateau_y / plateau_w
    # no sliding angle (s = 0) or no plateau (s = all): the free parameter at
    # the edge of its flat direction, the least mu that keeps every angle on
    # the plateau, the least beta0 above every angle's sliding branch
    mu[0] = np.max((1.0 + beta0[0]) / slope)
    beta0[-1] = np.max(mu[-1] * slope - 1.0)
    return np.column_stack([np.clip(mu, 0.0, MU_HIGH), np.clip(beta0, -1.5, 1.5)])


def walton_profile(
    data: Means, K: float, mu: float, e: float | None = None, weighted: bool = True
) -> float:
    """The least cost of Walton's model at a fixed ``mu`` over beta0: the
    best of BETA0_GRID, refined by a bounded search around it (the cost is
    piecewise quadratic in beta0, not convex)."""
    e_values, scale = _e(data, e), _scale(data, weighted)

    def cost(beta0: float) -> float:
        model = walton_beta(data.psi, e_values, mu, beta0, K)
        return float(np.sum(((model - data.beta) / scale) ** 2))

    costs = walton_costs(data, K, [mu], BETA0_GRID, e, weighted)[0]
    best, step = BETA0_GRID[np.argmin(costs)], BETA0_GRID[1] - BETA0_GRID[0]
    bounds = (max(best - step, BETA0_GRID[0]), min(best + step, BETA0_GRID[-1]))
    return min(float(costs.min()), minimize_scalar(cost, bounds=bounds, method="bounded").fun)


def walton_mu_bounds(
    data: Means, K: float, e: float | None = None, weighted: bool = True, rise: float = 1.0
) -> tuple[float, float]:
    """The mu that Walton's fit allows: those whose profile cost
    (``walton_profile``) is within ``rise`` of the least, as (lowest,
    highest), on MU_GRID and the fit's own mu, refined at the edges. The
    highest is infinite where mu at the fit's bound (MU_HIGH) fits as well:
    no angle is then on the sliding branch, beta is on its plateau
    throughout, and the data bound mu from below only (it is not
    identified). With weights by the standard errors (the measured way),
    ``rise`` 1 gives the profile's one-sigma interval and 4 its two-sigma
    one, the angles taken as independent (a gauge of the width). Where beta
    is on its plateau at every angle the profile is flat above the lower
    bound, whatever the rise; where the data show a faint sliding branch, a
    larger rise may leave mu unbounded."""
    # the fit's own mu besides the grid: its minimum may be narrower than the grid's steps
    grid = np.union1d(MU_GRID, [fit_walton(data, K, e, weighted)[0]])
    costs = np.array([walton_profile(data, K, m, e, weighted) for m in grid])
    level = costs.min() + rise
    inside = np.flatnonzero(costs <= level)

    def edge(outside: int, within: int) -> float:
        """Where the profile crosses ``level`` between two grid points."""
        low, high = sorted((grid[outside], grid[within]))
        return float(
            brentq(lambda m: walton_profile(data, K, m, e, weighted) - level, low, high, xtol=1e-5)
        )

    first, last = inside[0], inside[-1]
    low = 0.0 if first == 0 else edge(first - 1, first)
    high = np.inf if last == len(grid) - 1 else edge(last + 1, last)
    return low, high


def compliant_curve(data: Means, mu: float, nu: float, alpha: float, e=None) -> np.ndarray:
    """The compliant model's beta at the angles of ``data``."""
    return np.array(
        [
            compliant_beta(p, Compliant(e=ei, mu=mu, nu=nu, alpha=alpha))
            for p, ei in zip(data.psi, _e(data, e))
        ]
    )


def fit_compliant(
    data: Means,
    nu: float,
    alpha: float,
    e: float | None = None,
    weighted: bool = True,
    start: float | None = None,
) -> np.ndarray:
    """mu of the compliant model by least squares on the per-angle means.

    Parameters
    ----------
    data : Means
        Per-angle means (``means``).
    nu : float
        Poisson ratio (the paper's eta = 1.015 is ``theory.nu_for_eta(1.015)``).
    alpha : float
        K = 1 + M R^2 / I (the paper's: 3.02).
    e : float, optional
        A fixed e (the paper's way: 0.8); default the measured mean e at each angle.
    weighted : bool
        Residuals over the standard errors of the means (True), or all alike.
    start : float, optional
        A mu near the answer (a bootstrap resample's fit starts from the
        fit to all the data): the search then brackets it instead of
        scanning ``COMPLIANT_MU_GRID``, and falls back to the scan if the answer is at
        the bracket's edge.

    Returns
    -------
    numpy.ndarray
        (mu,), one element.
    """
    scale = _scale(data, weighted)

    def cost(mu):
        return float(np.sum(((compliant_curve(data, mu, nu, alpha, e) - data.beta) / scale) ** 2))

    if start is not None:
        low, high = start / 1.25, start * 1.25
        found = minimize_scalar(cost, bounds=(low, high), method="bounded", options={"xatol": 1e-6})
        if low * 1.001 < found.x < high / 1.001:
            return np.array([found.x])
    grid = COMPLIANT_MU_GRID
    costs = [cost(m) for m in grid]
    k = int(np.argmin(costs))
    low, high = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    found = minimize_scalar(cost, bounds=(low, high), method="bounded", options={"xatol": 1e-6})
    return np.array([found.x])


def reduced_chi2(
    data: Means, model_beta: np.ndarray, parameters: int, sd: np.ndarray | None = None
) -> float:
    """Squared residuals over the errors of the means, per degree of freedom:
    about 1 if the model describes the means within their errors.

    Parameters
    ----------
    data : Means
        Per-angle means.
    model_beta : numpy.ndarray
        The model's beta at each angle.
    parameters : int
        Number of fitted parameters.
    sd : numpy.ndarray, optional
        The errors of the means of beta (the seed bootstrap's); default
        ``data.beta_se``. The angles are treated as independent, which they
        are not quite (one seed serves all): a gauge, not a test.

    Returns
    -------
    float
        chi2 / (angles - parameters), the divisor at least 1.
    """
    sd = data.beta_se if sd is None else np.asarray(sd)
    residuals = (np.asarray(model_beta) - data.beta) / sd
    return float(np.sum(residuals**2) / max(len(residuals) - parameters, 1))
