"""Fits of the theories to the per-angle means of beta(psi) (docs/model.md section 6).

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
from scipy.optimize import brentq, minimize_scalar

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


# Walton's model is piecewise linear in (mu, beta0): an angle slides or
# sits on the plateau, and the cost is a quadratic on each side of every
# kink. Its least is therefore found exactly (``walton_candidates``), not
# by a search whose stopping point moves with the data's last bits: every
# split of the angles into sliding and plateau solved in closed form, and
# every angle put exactly on the kink. The fit's bounds: mu up to MU_HIGH
# (where a plateau at every angle leaves mu free), beta0 in BETA0_BOUNDS.
MU_HIGH = 5.0
BETA0_BOUNDS = (-1.5, 1.5)
# The profile's grid of mu, refined at its edges by root finding.
MU_GRID = np.concatenate([[0.0], np.geomspace(1e-3, MU_HIGH, 60)])
# Two costs this close (relative) are the same least: the point with the
# smaller mu (then the smaller beta0) is reported, so that a flat valley
# gives its defined edge rather than whichever point the rounding favours.
SAME_COST = 1e-10
# The compliant model's scan of mu (each point a sum over the angles of its
# closed-form curve: the cost of its fit), then the root of the cost's slope.
COMPLIANT_MU_GRID = np.geomspace(1e-3, 3.0, 25)
# The relative step of a central difference of a smooth cost, and how far
# (relative) on either side of a search's stop its slope's root is sought.
SLOPE_STEP = 1e-4
POLISH = 1e-4


def walton_costs(
    data: Means, K: float, mu, beta0, e: float | None = None, weighted: bool = True
) -> np.ndarray:
    """The cost (sum of squared residuals, weighted as ``fit_walton``
    weighs them) of Walton's model at every (mu, beta0) of two arrays, as a
    (len(mu), len(beta0)) array."""
    mu, beta0 = np.asarray(mu, float), np.asarray(beta0, float)
    model = walton_beta(data.psi, _e(data, e), mu[:, None, None], beta0[None, :, None], K)
    return np.sum(((model - data.beta) / _scale(data, weighted)) ** 2, axis=-1)


def _least_point(points: np.ndarray, costs: np.ndarray, scale: float) -> np.ndarray:
    """The point of least cost; among costs within SAME_COST of it (relative
    to ``scale``, a cost of the data's own size), the least mu, then the
    least beta0."""
    tied = costs <= costs.min() + SAME_COST * scale
    rows = np.flatnonzero(tied)
    return points[rows[np.lexsort((points[rows, 1], points[rows, 0]))[0]]]


def walton_candidates(
    data: Means, K: float, e: float | None = None, weighted: bool = True
) -> np.ndarray:
    """(mu, beta0), one row per place where Walton's least cost may lie,
    within the fit's bounds: for every split of the angles into a sliding
    set (the smallest (1 + e) K psi) and a plateau, the two closed-form
    least-squares solutions (beta + 1 = mu (1 + e) K psi through the
    origin; beta0 the plateau's weighted mean); and for every angle put
    exactly on the kink (beta0 = mu (1 + e) K psi_j - 1, one parameter left,
    again in closed form). A split with no sliding angle or no plateau puts
    its free parameter at the edge of its flat direction: the least mu that
    keeps every angle on the plateau, the least beta0 above every sliding
    angle. The cost is continuous and quadratic between kinks, so its least
    is at one of these rows (or on a bound, where a row is clipped to)."""
    slope = (1.0 + _e(data, e)) * K * data.psi
    order = np.argsort(slope, kind="stable")
    slope, beta = slope[order], data.beta[order]
    weight = 1.0 / _scale(data, weighted)[order] ** 2
    # splits: sums over the k smallest slopes (sliding) and over the rest (plateau)
    sliding_xy = np.concatenate([[0.0], np.cumsum(weight * slope * (beta + 1.0))])
    sliding_xx = np.concatenate([[0.0], np.cumsum(weight * slope**2)])
    plateau_y = np.concatenate([np.cumsum((weight * beta)[::-1])[::-1], [0.0]])
    plateau_w = np.concatenate([np.cumsum(weight[::-1])[::-1], [0.0]])
    with np.errstate(divide="ignore", invalid="ignore"):
        mu = sliding_xy / sliding_xx
        beta0 = plateau_y / plateau_w
    mu[0] = (1.0 + beta0[0]) / slope[0]
    beta0[-1] = mu[-1] * slope[-1] - 1.0
    # kinks: angle j on it, every angle's model mu min(slope_i, slope_j) - 1;
    # mu clipped to the bounds along the kink line before beta0 follows it,
    # so that a least beyond a bound becomes the corner on that line
    capped = np.minimum(slope[None, :], slope[:, None])
    with np.errstate(divide="ignore", invalid="ignore"):
        on_kink = (capped * weight * (beta + 1.0)).sum(axis=1) / (capped**2 * weight).sum(axis=1)
        highest = np.minimum(MU_HIGH, (1.0 + BETA0_BOUNDS[1]) / slope)
    on_kink = np.clip(np.nan_to_num(on_kink, nan=0.0), 0.0, highest)
    mu = np.concatenate([mu, on_kink])
    beta0 = np.concatenate([beta0, on_kink * slope - 1.0])
    mu = np.clip(np.nan_to_num(mu, nan=0.0), 0.0, MU_HIGH)
    return np.column_stack([mu, np.clip(np.nan_to_num(beta0, nan=-1.0), *BETA0_BOUNDS)])


def fit_walton(data: Means, K: float, e: float | None = None, weighted: bool = True) -> np.ndarray:
    """(mu, beta0) of Walton's model by least squares on the per-angle means:
    the least of ``walton_candidates`` (exact, no search); where a valley
    of equal cost is flat, its least mu.

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
    points = walton_candidates(data, K, e, weighted)
    model = walton_beta(data.psi, _e(data, e), points[:, :1], points[:, 1:], K)
    costs = np.sum(((model - data.beta) / _scale(data, weighted)) ** 2, axis=1)
    return _least_point(points, costs, _cost_scale(data, weighted))


def _cost_scale(data: Means, weighted: bool) -> float:
    """A cost of the data's own size: the squared distance of every mean
    from beta = -1, weighted as the fit weighs it."""
    return float(np.sum(((data.beta + 1.0) / _scale(data, weighted)) ** 2)) or 1.0


def walton_profile(
    data: Means, K: float, mu: float, e: float | None = None, weighted: bool = True
) -> float:
    """The least cost of Walton's model at a fixed ``mu`` over beta0, exact:
    at fixed mu the cost is quadratic in beta0 between the angles' kinks
    (beta0 = mu (1 + e) K psi - 1), an angle on the plateau where beta0 is
    below its kink, so the least is at a kink, at a bound, or at the weighted
    mean of the angles of the j highest kinks (those on the plateau)."""
    slope = (1.0 + _e(data, e)) * K * data.psi
    order = np.argsort(slope, kind="stable")[::-1]
    weight = 1.0 / _scale(data, weighted)[order] ** 2
    plateau_means = np.cumsum(weight * data.beta[order]) / np.cumsum(weight)
    beta0 = np.concatenate([mu * slope - 1.0, plateau_means, BETA0_BOUNDS])
    beta0 = np.clip(beta0, *BETA0_BOUNDS)
    return float(walton_costs(data, K, [mu], beta0, e, weighted).min())


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
    return profile_bounds(
        lambda m: walton_profile(data, K, m, e, weighted), fit_walton(data, K, e, weighted)[0], rise
    )


def profile_bounds(profile, fitted_mu: float, rise: float) -> tuple[float, float]:
    """(lowest, highest) mu whose ``profile`` (the least cost at that mu) is
    within ``rise`` of its least: on MU_GRID and the fit's own mu (its
    minimum may be narrower than the grid's steps), refined at the edges by
    root finding; highest infinite where the profile stays within ``rise``
    up to MU_HIGH."""
    grid = np.union1d(MU_GRID, [fitted_mu])
    costs = np.array([profile(m) for m in grid])
    level = costs.min() + rise
    inside = np.flatnonzero(costs <= level)

    def edge(outside: int, within: int) -> float:
        """Where the profile crosses ``level`` between two grid points."""
        low, high = sorted((grid[outside], grid[within]))
        return float(brentq(lambda m: profile(m) - level, low, high, xtol=1e-13))

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
        found = least_of_smooth(cost, start / 1.25, start * 1.25)
        if found is not None:
            return np.array([found])
    grid = COMPLIANT_MU_GRID
    k = int(np.argmin([cost(m) for m in grid]))
    low, high = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    found = least_of_smooth(cost, low, high)
    return np.array([found if found is not None else grid[k]])


def least_of_smooth(cost, low: float, high: float) -> float | None:
    """Where a smooth cost of one positive parameter is least inside (low,
    high); None if it is least at an end.

    A search on the cost's values (Brent's, ``minimize_scalar``) stops
    within about sqrt(machine epsilon) of the least, where the cost no
    longer tells points apart, and where it stops moves with the data's
    last bits. So the search only comes near, and the least is then the
    root of the cost's slope (a central difference of relative step
    SLOPE_STEP), from a secant through two points POLISH on either side,
    or by Brent's root finding if the search stopped farther off: a point
    that moves by about 1e-10 of itself, far below the written six digits,
    wherever it is computed. Where neither brackets a root (a flat or
    kinked cost), the search's own stop (to 1e-6)."""

    def slope(x: float) -> float:
        step = SLOPE_STEP * x
        return cost(x + step) - cost(x - step)

    near = minimize_scalar(cost, bounds=(low, high), method="bounded", options={"xatol": 1e-6})
    x = float(near.x)
    if not low * 1.001 < x < high / 1.001:
        return None
    a, b = x * (1.0 - POLISH), x * (1.0 + POLISH)
    slope_a, slope_b = slope(a), slope(b)
    if slope_a < 0.0 < slope_b:
        return a - slope_a * (b - a) / (slope_b - slope_a)
    if slope(low) < 0.0 < slope(high):
        return float(brentq(slope, low, high, xtol=1e-15, rtol=1e-14))
    return x


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
