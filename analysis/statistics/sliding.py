"""Walton's sliding branch, read from the rows (docs/model.md section 6).

On the sliding branch beta = -1 + mu (1 + e) K psi, so mu_eff = (1 + beta) /
((1 + e) K psi) is mu at each of its angles; past its kink, toward normal
incidence, beta keeps to its plateau and mu_eff falls. So the branch is
found without a model: the longest run of the most grazing angles whose
mu_eff one constant describes, at p at or above BRANCH_P.

A seed's surface serves every angle, so a seed's mu_eff moves at all of
them together: the test is on each seed's own differences between the
run's angles (Hotelling's T^2 on the successive differences, exact for
normal errors: F with k - 1 and n - k + 1 degrees of freedom for k angles
and n seeds with every angle), which a shift common to a seed's angles
leaves out, as the per-angle errors cannot. A run needs more seeds than
angles.

mu on the branch (``measures``) is the mean of its angles' mu_eff. Where
no run of two angles or more passes, the rows hold no sliding branch, and
mu_eff at the most grazing angle bounds mu from below only. The run is
chosen once, from all the data; the seed errors keep it fixed and do not
count the choice.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from ground.digits import rounded

from .measures import as_written, mu_eff
from .seeds import SeedTable

BRANCH_P = 0.05  # a constant describes a run's mu_eff at p at or above this


def per_seed_mu_eff(table: SeedTable, K: float) -> np.ndarray:
    """(1 + beta) / ((1 + e) K cot gamma) of every impact, seeds x angles."""
    v = table.values
    with np.errstate(invalid="ignore", divide="ignore"):
        return mu_eff(v["cot_gamma"], v["e"], v["beta"], K)


def constant_p(per_seed: np.ndarray) -> float | None:
    """p of one constant for the column means of ``per_seed`` (seeds x k
    angles): Hotelling's T^2 on the seeds' successive differences (module
    docstring), from the seeds with every angle; None where they are not
    more than k or their differences do not vary."""
    values = per_seed[np.all(np.isfinite(per_seed), axis=1)]
    n, k = values.shape
    if n <= k:
        return None
    steps = np.diff(values, axis=1)
    mean, covariance = steps.mean(axis=0), np.atleast_2d(np.cov(steps, rowvar=False))
    try:
        t2 = n * float(mean @ np.linalg.solve(covariance, mean))
    except np.linalg.LinAlgError:
        return None
    return float(stats.f.sf(t2 * (n - k + 1) / ((n - 1) * (k - 1)), k - 1, n - k + 1))


def sliding_branch(table: SeedTable, K: float) -> tuple[np.ndarray, float | None]:
    """The sliding branch of one lattice (module docstring).

    Parameters
    ----------
    table : SeedTable
        The lattice's impacts by seed and angle.
    K : float
        1 + M R^2 / I of the disk.

    Returns
    -------
    (numpy.ndarray, float or None)
        True at the branch's angles (none, or at least two), and the p of
        one constant over them (None without a branch).
    """
    # the most grazing first, ordered as written (an angle's cot gamma
    # measured a few ulps apart on another CPU keeps its place)
    psi = as_written(table.mean("cot_gamma"))
    order = [i for i in np.argsort(psi, kind="stable") if np.isfinite(psi[i])]
    values = per_seed_mu_eff(table, K)
    branch, p_branch = np.zeros(len(psi), bool), None
    for k in range(2, len(order) + 1):
        p = constant_p(values[:, order[:k]])
        if p is not None and rounded(p) >= BRANCH_P:  # the longest that passes
            branch[:], p_branch = False, p
            branch[order[:k]] = True
    return branch, p_branch
