"""A quantity's limit as the resolution grows, with its form as a systematic
(docs/studies/resolution/resolution.md; its numbers for any reading and any set of levels).

The levels are disk resolutions N with a value and its statistical error;
the spacing is h = sqrt(REFERENCE_N / N) (1 at the paper's 800 points). From
FIT_FROM points up, three forms are fitted by weighted least squares
(``fit_form``, the errors absolute):

- ``h``: Q0 + c h;
- ``h2``: Q0 + c h^2;
- ``power``: Q0 + c h^p, p free in POWER_BOUNDS (only with four levels or
  more, so that it has a degree of freedom; an exponent that ends on a bound
  is not determined, and that fit describes nothing).

A form describes the levels unless its chi^2 has a p-value below P_VALUE
(with one degree of freedom chi2/dof 2.2 is p 0.14: it describes). The limit
is the middle of the describing forms' intercepts; its statistical error the
larger of the fixed-exponent forms' intercept errors (the power law's
exponent is the form's uncertainty, in the band); its systematic error half
the band between the intercepts, stated separately.

Before any limit, the last two halvings of h: with d_last = Q(N) - Q(N/2)
and d_before = Q(N/2) - Q(N/4) at the finest N, a quantity whose last step is
real (|d_last| above AGREE errors; where the two levels share fewer than 16
seeds, above the t quantile of a 95 % interval with the fewer seeds' n - 1
degrees of freedom) and no smaller than the step before is
"not converged at N", with both steps and their errors, never a limit. The
levels' errors combine as independent draws (rows whose seeds are coupled
across N pass the paired steps' own errors, ``steps``).

Levels whose errors are correlated (multilevel estimates, which share the
coarsest level's: analysis.statistics.levels.multilevel_levels) pass their
covariance; the forms are then fitted by generalized least squares and
chi^2 is r^T C^-1 r.

How far the 800-point level lies from the limit is the fits' c (the curve's
rise from h = 0 to h = 1) with its error: the 800-point value is itself in
the fits, so its distance from their intercept in combined errors would
count it twice.
"""

from __future__ import annotations

import numpy as np
from scipy import linalg, stats

from ground.digits import half_range

from .fits import least_of_smooth
from .seeds import BOOTSTRAP_FROM, interval_factor

REFERENCE_N = 800
FIT_FROM = 800
P_VALUE = 0.05
AGREE = 2.0
FORMS = ("h", "h2", "power")
FIXED_FORMS = ("h", "h2")
# The power law's exponent is sought in these bounds; one that ends on a
# bound is not determined by the levels, and its intercept enters no band.
POWER_BOUNDS = (0.25, 4.0)


def spacing(n) -> np.ndarray:
    """h = sqrt(REFERENCE_N / N)."""
    return np.sqrt(REFERENCE_N / np.asarray(n, float))


# The power law's exponent: scanned on this grid, then the least of the
# profiled chi^2 between the scan's neighbours (the root of its slope).
POWER_GRID = np.geomspace(*POWER_BOUNDS, 49)
EXPONENTS = {"h": 1.0, "h2": 2.0}


def _whitener(sigma: np.ndarray):
    """A function that whitens vectors and matrices by the levels' errors:
    divides by their sd, or solves with the covariance's Cholesky factor
    (generalized least squares becomes ordinary least squares)."""
    if sigma.ndim == 1:
        return lambda a: (np.asarray(a, float).T / sigma).T
    factor = linalg.cholesky(sigma, lower=True)
    return lambda a: linalg.solve_triangular(factor, a, lower=True)


def _line(h: np.ndarray, q: np.ndarray, p: float, whiten) -> tuple[np.ndarray, float]:
    """(Q0, c) of Q0 + c h^p by (generalized) least squares, and its chi^2:
    closed form, the same to the last bits wherever it runs."""
    design = whiten(np.column_stack([np.ones_like(h), h**p]))
    target = whiten(q)
    coef = np.linalg.lstsq(design, target, rcond=None)[0]
    residual = target - design @ coef
    return coef, float(residual @ residual)


def fit_form(n, q, sd, form: str, covariance=None, sandwich: bool = False) -> dict | None:
    """One form fitted to levels (N, Q, sd), or to levels whose errors are
    correlated (``covariance``, whose diagonal is sd squared); None with too
    few levels (the power law needs four) or if the fit fails.

    With ``sandwich`` and a covariance estimated from few seeds, the form is
    fitted with each level weighted by its own sd and its errors are
    A C A^T (A the weighted fit's linear map, C the covariance), while
    chi^2 is the GLS fit's least r^T C^-1 r: the inverse of an estimated covariance is
    biased high (about (n - 1) / (n - p - 2) for p levels from n seeds, the
    inverse Wishart's mean), which would shrink a GLS fit's errors by as
    much; its chi^2 is the stricter for it.

    The fixed exponents are linear least squares, in closed form; the power
    law's exponent minimises the chi^2 profiled over (Q0, c), which is
    smooth in p (``fits.least_of_smooth``), so that no search's stopping
    point sets the last digits. The errors are those of the linearised
    model at the least, the errors absolute.

    Returns
    -------
    dict
        ``limit``, ``limit_sd``, ``c``, ``c_sd``, ``p`` (1, 2 or fitted),
        ``p_sd`` (0 if fixed), ``chi2`` (per degree of freedom), ``dof``,
        ``p_value``, ``pinned`` (the exponent on a bound), ``describes`` and
        ``levels``.
    """
    n, q, sd = (np.asarray(v, float) for v in (n, q, sd))
    h = spacing(n)
    parameters = 3 if form == "power" else 2
    if len(q) < parameters + 1:
        return None
    sigma = sd if covariance is None else np.asarray(covariance, float)
    try:
        whiten = _whitener(sd if sandwich else sigma)
        pinned = False
        if form == "power":
            profile = [_line(h, q, p, whiten)[1] for p in POWER_GRID]
            k = int(np.argmin(profile))
            low, high = POWER_GRID[max(k - 1, 0)], POWER_GRID[min(k + 1, len(POWER_GRID) - 1)]
            found = least_of_smooth(lambda p: _line(h, q, p, whiten)[1], low, high)
            exponent = POWER_GRID[k] if found is None else found
            pinned = found is None and k in (0, len(POWER_GRID) - 1)
        else:
            exponent = EXPONENTS[form]
        (q0, c), chi2 = _line(h, q, exponent, whiten)
        columns = [np.ones_like(h), h**exponent]
        if form == "power":  # the exponent's column of the linearised model
            columns.append(c * h**exponent * np.log(h))
        jacobian = whiten(np.column_stack(columns))
        with np.errstate(all="ignore"):
            inverse = np.linalg.inv(jacobian.T @ jacobian)
            if sandwich and covariance is not None:
                linear_map = inverse @ jacobian.T @ whiten(np.eye(len(q)))
                errors = np.sqrt(np.abs(np.diag(linear_map @ sigma @ linear_map.T)))
                # the goodness of fit is the form's at its GLS least: the
                # weighted fit's own residuals carry the levels' shared
                # shift, which the covariance says is no misfit
                chi2 = _line(h, q, exponent, _whitener(sigma))[1]
            else:
                errors = np.sqrt(np.abs(np.diag(inverse)))
    except (ValueError, np.linalg.LinAlgError):
        return None
    dof = len(q) - parameters
    p_value = float(stats.chi2.sf(chi2, dof))
    return {
        "form": form,
        "limit": float(q0),
        "limit_sd": float(errors[0]),
        "c": float(c),
        "c_sd": float(errors[1]),
        "p": float(exponent),
        "p_sd": float(errors[2]) if form == "power" else 0.0,
        "chi2": chi2 / dof,
        "dof": dof,
        "p_value": p_value,
        "pinned": bool(pinned),
        "describes": bool(p_value >= P_VALUE and not pinned and np.all(np.isfinite(errors))),
        "levels": len(q),
    }


def halvings(
    levels: list[tuple[int, float, float]],
    steps: dict | None = None,
    seeds: dict | None = None,
) -> dict | None:
    """The last two halvings of h at the finest level (module docstring), or
    None without levels N, N/2 and N/4.

    Parameters
    ----------
    levels : list of (N, value, sd)
    steps : dict, optional
        N -> (Q(N) - Q(N/2), its error) from coupled seeds; default the
        levels' values and errors combined as independent.
    seeds : dict, optional
        N -> the level's seeds: below BOOTSTRAP_FROM the last step is real
        beyond the t quantile (``analysis.statistics.seeds.interval_factor``), not AGREE.
    """
    by_n = {int(n): (v, s) for n, v, s in levels}
    finest = max(by_n, default=0)
    if finest // 2 not in by_n or finest // 4 not in by_n or finest % 4:
        return None

    def step(n: int) -> tuple[float, float]:
        if steps and n in steps:
            return steps[n]
        (a, sa), (b, sb) = by_n[n], by_n[n // 2]
        return a - b, float(np.hypot(sa, sb))

    last, before = step(finest), step(finest // 2)
    few = min(seeds.get(finest, 0), seeds.get(finest // 2, 0)) if seeds else BOOTSTRAP_FROM
    threshold = AGREE if few >= BOOTSTRAP_FROM or few < 2 else interval_factor(few)
    real = abs(last[0]) > threshold * last[1]
    converged = not (real and abs(last[0]) >= abs(before[0]))
    return {
        "finest": finest,
        "last": last,
        "before": before,
        "threshold": float(threshold),
        "last_is_real": bool(real),
        "converged": bool(converged),
    }


def limit(
    levels: list[tuple[int, float, float]],
    steps: dict | None = None,
    seeds: dict | None = None,
    covariance: dict | None = None,
    sandwich: bool = False,
) -> dict:
    """A quantity's limit N -> infinity from its levels (N, value, sd);
    ``steps`` and ``seeds`` as for ``halvings``; ``covariance`` (N, N') ->
    the covariance of two levels' errors where they are correlated (its
    diagonal the sd squared), for the fits (``sandwich`` as for ``fit_form``).

    Returns
    -------
    dict
        ``status``: "limit", "not converged", "no form" (no form describes
        the levels) or "too few" (fewer than three levels from FIT_FROM up);
        ``levels`` used; ``forms`` (form -> ``fit_form``'s dict or None);
        ``halvings``; and with a limit ``value``, ``stat``, ``systematic``,
        ``band`` (lowest and highest describing intercepts), ``described_by``,
        ``shift_800`` and ``shift_800_sd`` (the 800-point level's height
        above the limit by the fits' c).
    """
    finest = sorted((int(n), float(v), float(s)) for n, v, s in levels if n >= FIT_FROM)
    if len(finest) >= 3 and all(v == finest[0][1] and s == 0 for _, v, s in finest):
        # the same at every level, without scatter (a share of 0, say): that value
        return {
            "levels": [n for n, _, _ in finest],
            "forms": {},
            "halvings": None,
            "status": "limit",
            "value": finest[0][1],
            "stat": 0.0,
            "systematic": 0.0,
            "band": (finest[0][1], finest[0][1]),
            "described_by": ["constant"],
            "shift_800": 0.0,
            "shift_800_sd": 0.0,
        }
    use = [(n, v, s) for n, v, s in finest if np.isfinite(v) and np.isfinite(s) and s > 0]
    out: dict = {
        "levels": [n for n, _, _ in use],
        "forms": {},
        "halvings": halvings(use, steps, seeds),
    }
    if len(use) < 3:
        out["status"] = "too few"
        return out
    n, q, sd = zip(*use, strict=True)
    matrix = None if covariance is None else [[covariance[a, b] for b in n] for a in n]
    out["forms"] = {form: fit_form(n, q, sd, form, matrix, sandwich) for form in FORMS}
    if out["halvings"] and not out["halvings"]["converged"]:
        out["status"] = "not converged"
        return out
    good = [f for f in out["forms"].values() if f and f["describes"]]
    if not good:
        out["status"] = "no form"
        return out
    intercepts = [f["limit"] for f in good]
    fixed = [f for f in good if f["form"] in FIXED_FORMS] or good
    shifts = [f["c"] for f in good]
    out.update(
        status="limit",
        value=0.5 * (min(intercepts) + max(intercepts)),
        stat=max(f["limit_sd"] for f in fixed),
        systematic=half_range(intercepts),
        band=(min(intercepts), max(intercepts)),
        described_by=[f["form"] for f in good],
        shift_800=0.5 * (min(shifts) + max(shifts)),
        shift_800_sd=max(f["c_sd"] for f in fixed),
    )
    return out
