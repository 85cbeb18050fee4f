"""The paper's claims against a study's numbers (docs/model.md section 8).

Each fact the paper reports is set beside the project's number measured the
paper's way (its fitting procedure) and model-free, each with its error, and
gets a verdict computed by a stated rule:

- a fact "x is near v" (what counts as near: docs/model.md section 8's unit of
  that fact) **meets** if the interval x +- 2 errors lies inside v +- near,
  **misses** if it lies wholly outside, and is **undecided** otherwise;
- a fact "a equals b" (no unit: the paper says "the same") **meets** if
  |a - b| <= 2 errors, **misses** if it is above 3 errors, and is
  **undecided** between;
- a lower bound of x (mu_eff at the most grazing angle, where the rows hold
  no sliding branch) **misses** "x is near v" if it lies above v + near by
  more than 2 errors, and is **undecided** otherwise.

The error is the seed-bootstrap standard deviation; for a fitted parameter
whose fit has a reduced chi^2 above the limit (the model does not describe
the data), it is that combined in quadrature with the systematic error (half
the parameter's range over the fitting choices, ``analysis.statistics.estimates``).
"""

from __future__ import annotations

import math

# What counts as near (docs/model.md section 8). The triangular disk's share of
# angles with beta > 0 has no unit there: a tenth of the angles is this page's.
NEAR = {"e": 0.1, "mu": 0.05, "beta0": 0.2, "share_beta_positive": 0.1, "near_side": 0.1}
# The rules' numbers of errors (module docstring): within SAME errors a
# number meets, beyond DIFFERS it misses (pages/templates/results/claims.md.j2
# states them).
SAME, DIFFERS = 2.0, 3.0


def verdict(value, error, paper: float, near: float | None) -> str:
    """The verdict of one number on one fact (module docstring); '-' without a number."""
    if value is None or not math.isfinite(value):
        return "-"
    error = error if error is not None and math.isfinite(error) else 0.0
    if near is None:
        gap = abs(value - paper)
        if gap <= SAME * error:
            return "meets"
        return "misses" if gap > DIFFERS * error else "undecided"
    low, high = value - SAME * error, value + SAME * error
    if paper - near <= low and high <= paper + near:
        return "meets"
    if high < paper - near or low > paper + near:
        return "misses"
    return "undecided"


def lower_bound_verdict(value, error, paper: float, near: float) -> str:
    """The verdict of a lower bound of x on "x near v": it **misses** if the
    bound lies above v + near by more than SAME errors, and is
    **undecided** otherwise (x may lie anywhere above it)."""
    if value is None or not math.isfinite(value):
        return "-"
    return "misses" if value - SAME * (error or 0.0) > paper + near else "undecided"


def _number(value, sd, systematic=None) -> dict | None:
    if value is None:
        return None
    error = math.hypot(sd or 0.0, systematic or 0.0)
    return {"value": value, "sd": sd, "systematic": systematic, "error": error}


def _fitted(fits: dict, lattice: str, theory: str, parameter: str) -> dict | None:
    """A paper's-way parameter with its seed error, and the systematic error
    where the fit does not describe the data."""
    fit = fits["lattices"].get(lattice, {}).get(theory)
    if not fit:
        return None
    paper = fit["paper"]
    failed = paper["chi2"] > fits["chi2_limit"]
    return _number(
        paper[parameter], paper[f"{parameter}_sd"], fit["systematic"][parameter] if failed else None
    )


def _measure(fits: dict, lattice: str, name: str) -> dict | None:
    entry = fits["lattices"].get(lattice, {}).get("measures", {}).get(name)
    return _number(entry["value"], entry["sd"]) if entry else None


def _friction(fits: dict, lattice: str) -> tuple[dict | None, str]:
    """mu read without a model: on the sliding branch the rows hold
    (``analysis.statistics.sliding``), or, where they hold none, mu_eff at
    the most grazing angle, a lower bound of mu (``lower_bound``)."""
    measures = fits["lattices"].get(lattice, {}).get("measures")
    if not measures:
        return None, "mu on the sliding branch"
    on_branch = measures["mu_branch"]
    if on_branch["value"] is not None and math.isfinite(on_branch["value"]):
        return _number(on_branch["value"], on_branch["sd"]), "mu on the sliding branch"
    mu = measures["mu_eff"]
    j = min(range(len(mu["cot_gamma"])), key=lambda i: mu["cot_gamma"][i])
    bound = {**_number(mu["value"][j], mu["sd"][j]), "lower_bound": True}
    return bound, (
        f"mu_eff at {mu['gamma_deg'][j]:g} degrees, a lower bound: no sliding branch in the rows"
    )


def _pair(fits: dict) -> tuple[dict | None, dict | None]:
    pair = fits.get("pair")
    if not pair:
        return None, None
    failed = any(
        fits["lattices"][pair[k]]["walton"]["paper"]["chi2"] > fits["chi2_limit"]
        for k in ("lower_nu", "higher_nu")
    )
    fitted = pair["beta0_difference_paper"]
    return (
        _number(fitted["value"], fitted["sd"], fitted["systematic"] if failed else None),
        _number(pair["beta_normal_difference"]["value"], pair["beta_normal_difference"]["sd"]),
    )


def claims(fits: dict) -> list[dict]:
    """The paper's facts with the study's numbers and verdicts.

    Parameters
    ----------
    fits : dict
        ``analysis.statistics.estimates.study_estimates``'s fits (fits.json).

    Returns
    -------
    list of dict
        One per fact: ``fact``, ``paper`` (its value), ``near`` (None for
        "the same"), ``procedure`` and ``model_free`` (each None or value, sd,
        systematic, error, and what it is: ``procedure_is``,
        ``model_free_is``) and their verdicts.
    """
    beta0_same, beta_normal_same = _pair(fits)
    friction, friction_is = _friction(fits, "random")
    pair = fits.get("pair") or {}
    rows = [
        (
            "random lattice: e near 0.8 (the paper's fit fixed e at 0.8)",
            0.8,
            NEAR["e"],
            None,
            "fixed at 0.8",
            _measure(fits, "random", "e_normal"),
            "mean e at cot gamma >= 1",
        ),
        (
            "random lattice: Walton's mu near 0.18",
            0.18,
            NEAR["mu"],
            _fitted(fits, "random", "walton", "mu"),
            "Walton, e 0.8, K 3, unweighted",
            friction,
            friction_is,
        ),
        (
            "random lattice: Walton's beta0 near 0.56",
            0.56,
            NEAR["beta0"],
            _fitted(fits, "random", "walton", "beta0"),
            "Walton, e 0.8, K 3, unweighted",
            _measure(fits, "random", "beta_normal"),
            "mean beta at cot gamma >= 4",
        ),
        (
            "triangular disk: beta negative at every angle (share of angles with beta > 0: 0)",
            0.0,
            NEAR["share_beta_positive"],
            None,
            "-",
            _measure(fits, "triangular", "share_beta_positive"),
            "share of angles whose mean beta > 0",
        ),
        (
            "random lattice: no contact runs off the wall (share within 1 R of a side: 0)",
            0.0,
            NEAR["near_side"],
            None,
            "-",
            _measure(fits, "random", "share_near_side"),
            "share of contacts within 1 R of a fixed side",
        ),
        (
            "random lattice: the compliant model's mu near 0.3 with eta 1.015",
            0.3,
            NEAR["mu"],
            _fitted(fits, "random", "compliant", "mu"),
            "compliant, eta 1.015, alpha 3.02, e 0.8, unweighted",
            None,
            "-",
        ),
        (
            "beta0 the same for nu 0.1 and 0.3 (difference 0)",
            0.0,
            None,
            beta0_same,
            f"Walton beta0, {pair.get('higher_nu', '?')} - {pair.get('lower_nu', '?')}",
            beta_normal_same,
            "mean beta at cot gamma >= 4, the same difference",
        ),
    ]
    out = []
    for fact, paper, near, procedure, procedure_is, model_free, model_free_is in rows:
        bound = bool(model_free and model_free.get("lower_bound"))
        out.append(
            {
                "fact": fact,
                "paper": paper,
                "near": near,
                "procedure": procedure,
                "procedure_is": procedure_is,
                "procedure_verdict": verdict(
                    procedure and procedure["value"], procedure and procedure["error"], paper, near
                ),
                "model_free": model_free,
                "model_free_is": model_free_is,
                "model_free_verdict": (lower_bound_verdict if bound else verdict)(
                    model_free and model_free["value"],
                    model_free and model_free["error"],
                    paper,
                    near,
                ),
            }
        )
    return out
