"""Model-free measures of a lattice's rebound (docs/model.md section 6).

They describe the data where the theories do not, each from the per-angle
means (every angle counts alike), and get their errors from the seed
bootstrap like every other number:

- ``e_normal``: e near normal incidence, the mean over the angles with
  cot gamma >= 1;
- ``e_grazing``: the mean e over the three smallest cot gamma;
- ``beta_normal``: beta near normal incidence, the mean over cot gamma >= 4;
- ``mu_eff``: the implied Coulomb friction (1 + beta) / ((1 + e) K psi) at
  every angle, which Walton's sliding branch holds constant at mu;
- ``mu_branch``: mu on the sliding branch found in the rows, the mean
  mu_eff of its angles (``sliding.sliding_branch``; NaN without a branch);
- ``share_beta_positive``: the share of the angles whose mean beta is above 0;
- ``share_near_side``: the share of all the lattice's contacts whose disk
  centre came within ``table.NEAR_SIDE`` of a fixed side of the wall.
"""

from __future__ import annotations

import numpy as np

from ground.digits import rounded

from ..table import NEAR_SIDE
from .seeds import SeedTable

E_NORMAL_PSI = 1.0  # e near normal incidence: cot gamma >= 1
BETA_NORMAL_PSI = 4.0  # beta near normal incidence: cot gamma >= 4
GRAZING_ANGLES = 3  # e at grazing incidence: the three smallest cot gamma


def mu_eff(psi, e, beta, K: float) -> np.ndarray:
    """The Coulomb friction that Walton's sliding branch would need for this beta.

    Parameters
    ----------
    psi, e, beta : array_like
        cot gamma and the means of e and beta at each angle.
    K : float
        1 + M R^2 / I of the disk.

    Returns
    -------
    numpy.ndarray
        (1 + beta) / ((1 + e) K psi).
    """
    return (1.0 + np.asarray(beta)) / ((1.0 + np.asarray(e)) * K * np.asarray(psi))


def as_written(values) -> np.ndarray:
    """``values`` as the tables write them (ground.digits), for comparisons
    with a threshold: an angle at cot gamma 1 measured as 1 - 1e-15 is at 1."""
    return np.array([rounded(float(v)) for v in np.ravel(values)]).reshape(np.shape(values))


def measures(table: SeedTable, K: float, branch: np.ndarray) -> dict[str, np.ndarray]:
    """The model-free measures of one lattice (module docstring).

    Parameters
    ----------
    table : SeedTable
        The lattice's impacts by seed and angle.
    K : float
        1 + M R^2 / I of the disk.
    branch : numpy.ndarray
        The sliding branch's angles (``sliding.sliding_branch``), one bool per
        angle of ``table``.

    Returns
    -------
    dict
        ``e_normal``, ``e_grazing``, ``beta_normal``, ``mu_branch``,
        ``share_beta_positive``, ``share_near_side`` (floats, NaN where no
        angle qualifies) and ``mu_eff`` (one per angle of ``table``).
    """
    psi, e, beta = table.mean("cot_gamma"), table.mean("e"), table.mean("beta")
    band = as_written(psi)  # which angles a band holds, decided as written
    with np.errstate(invalid="ignore"):
        order = np.argsort(band, kind="stable")
        grazing = order[:GRAZING_ANGLES]
        mu = mu_eff(psi, e, beta, K)
        clearance = table.values["side_clearance"]
        reached = np.isfinite(clearance)
        return {
            "e_normal": _mean(e[band >= E_NORMAL_PSI]),
            "e_grazing": _mean(e[grazing]),
            "beta_normal": _mean(beta[band >= BETA_NORMAL_PSI]),
            "mu_eff": mu,
            "mu_branch": _mean(mu[branch]) if branch.sum() >= 2 else np.nan,
            "share_beta_positive": _mean((beta > 0)[np.isfinite(beta)]),
            "share_near_side": float(np.sum(clearance[reached] < NEAR_SIDE) / reached.sum())
            if reached.any()
            else np.nan,
        }


def _mean(values: np.ndarray) -> float:
    values = np.asarray(values, float)
    values = values[np.isfinite(values)]
    return float(values.mean()) if values.size else np.nan
