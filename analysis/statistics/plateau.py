"""Is beta on a plateau, and how much friction does the most grazing angle
show? Both read seed by seed from the rows, with no model.

Walton's model puts beta on one flat plateau beta0 at every angle past its
kink. Before a page says "on its plateau at every angle", the rows are asked
directly: per seed, the mean beta near normal incidence (cot gamma >=
NORMAL_FROM) minus the mean beta at the GRAZING most grazing angles. A
plateau at every angle gives 0; beta rising toward normal incidence (as a
tangentially compliant contact makes it, Maw, Barber and Fawcett) gives more.

At the most grazing angle, mu_eff = (1 + beta) / ((1 + e) K cot gamma) is
mu itself where the disk slides throughout the contact (Walton's sliding
branch) and less than mu where it does not: a model-free lower bound of mu.

Each number is a mean over seeds of per-seed values, and its error the
standard error over the seeds, sd / sqrt(n), which is the seed jackknife's
for a mean: whole seeds, as every error here. Below ``FEW_SEEDS`` seeds a
verdict uses the t quantile of a 95 % interval instead of two errors.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from ground.digits import rounded

from .measures import as_written
from .seeds import SeedTable

NORMAL_FROM = 1.0  # cot gamma: near normal incidence
GRAZING = 4  # the most grazing angles beta is compared with
SAME = 2.0  # errors within which a difference is "consistent with 0"
FEW_SEEDS = 8


def over_seeds(values) -> dict:
    """Mean over the seeds of per-seed values (NaN ones left out): ``value``,
    ``sd`` (standard error over seeds), ``seeds`` and ``threshold`` (how many
    errors a difference from 0 must exceed to be real: SAME, or the t
    quantile of a 95 % interval below FEW_SEEDS seeds)."""
    a = np.asarray(values, float)
    a = a[np.isfinite(a)]
    n = len(a)
    if n < 2:
        return {"value": float(a.mean()) if n else np.nan, "sd": np.nan, "seeds": n}
    threshold = SAME if n >= FEW_SEEDS else float(stats.t.ppf(0.975, n - 1))
    return {
        "value": float(a.mean()),
        "sd": float(a.std(ddof=1) / np.sqrt(n)),
        "seeds": n,
        "threshold": threshold,
    }


def beta_rise(table: SeedTable) -> dict:
    """Per seed, mean beta at cot gamma >= NORMAL_FROM minus mean beta at
    the GRAZING most grazing angles, over the seeds (``over_seeds``), with
    ``on_plateau``: whether that difference is consistent with 0."""
    cot = as_written(table.mean("cot_gamma"))
    beta = table.values["beta"]
    normal = cot >= NORMAL_FROM
    grazing = np.argsort(cot)[:GRAZING]
    if not normal.any() or normal[grazing].any():
        return {"value": np.nan, "sd": np.nan, "seeds": 0, "on_plateau": None}
    with np.errstate(invalid="ignore"):
        per_seed = np.nanmean(beta[:, normal], axis=1) - np.nanmean(beta[:, grazing], axis=1)
    out = over_seeds(per_seed)
    # decided on the numbers as written (ground.digits), as every verdict
    value, sd = rounded(out["value"]), rounded(out["sd"])
    real = out["seeds"] > 1 and abs(value) > out["threshold"] * sd
    out["on_plateau"] = None if out["seeds"] < 2 else not real
    return out


def mu_eff_grazing(table: SeedTable, K: float, e: float | None = None) -> dict:
    """mu_eff = (1 + beta) / ((1 + e) K cot gamma) at the most grazing angle,
    over the seeds (``over_seeds``), with that angle's ``gamma_deg``; e the
    measured one, or a fixed ``e`` (the paper's way of fitting: 0.8 with K
    3), so that it bounds the mu of a fit made that way."""
    cot = table.values["cot_gamma"]
    j = int(np.argmin(table.mean("cot_gamma")))
    beta = table.values["beta"][:, j]
    e_values = table.values["e"][:, j] if e is None else e
    out = over_seeds((1.0 + beta) / ((1.0 + e_values) * K * cot[:, j]))
    out["gamma_deg"] = float(table.gamma_deg[j])
    return out
