"""e at grazing incidence: its peak against tan gamma, and whether e > 1.

The seed paper's authors, in a companion letter (Phys. Rev. Lett. 93,
154301, 2004; cond-mat/0310058), reported e above 1 in oblique impacts, peaking against the
angle of incidence. A study whose angles go past the paper's last, 80.5
degrees, gets this section: per lattice, the peak of the mean e against
tan gamma (a parabola through the largest mean and its two neighbours), its
position and height with seed-bootstrap errors (whole seeds resampled, as
everywhere), and whether the largest mean e is above 1 by more than two of
its errors once the look-elsewhere effect is counted: the largest of A means
was chosen after the fact, so its (e - 1) / error is compared with the
largest of the A angles' standardised deviations over resamples of whole
seeds (a max-statistic test, which keeps the angles' correlation), not with
one normal variate.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import norm

from .impact.failures import genuine
from .statistics.seeds import SeedTable, seed_bootstrap, seed_draws, seed_tables

PAPER_LAST_ANGLE = 80.5  # degrees: the paper's last angle
SIGNIFICANT = 2.0  # e > 1 counts when it is above 1 by this many errors (look-elsewhere counted)
# Resamples of the look-elsewhere test: its p is a tail share, which 200 would
# resolve only to 0.005
LOOK_ELSEWHERE_RESAMPLES = 4000


def look_elsewhere(table: SeedTable, z: float, resamples: int = LOOK_ELSEWHERE_RESAMPLES) -> dict:
    """How often the largest of the angles' standardised deviations reaches ``z``.

    Each resample of whole seeds gives every angle's mean e; its deviation
    from the study's mean over that angle's bootstrap error, maximised over
    the angles, is what the largest of A means would show by chance if no
    angle's e were above the level tested. The share of resamples whose
    maximum reaches ``z`` is the global p (with the usual +1 in numerator and
    denominator), and its normal quantile the global z.

    Parameters
    ----------
    table : SeedTable
        One lattice's impacts.
    z : float
        The largest mean's (e - 1) / error.
    resamples : int
        Resamples of whole seeds (generator ``seeds.RNG_SEED``).

    Returns
    -------
    dict
        ``angles``, ``resamples``, ``p`` and ``z`` (global), NaN if z is.
    """
    draws = seed_draws({"t": table}, lambda ts: {"e": ts["t"].mean("e")}, resamples)["e"]
    centre, spread = table.mean("e"), np.nanstd(draws, axis=0, ddof=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        largest = np.nanmax((draws - centre) / spread, axis=1)
    if not np.isfinite(z):
        return {"angles": int(len(centre)), "resamples": resamples, "p": np.nan, "z": np.nan}
    reached = int(np.sum(largest >= z))
    p = (reached + 1) / (resamples + 1)
    return {
        "angles": int(np.sum(np.isfinite(centre))),
        "resamples": resamples,
        "p": float(p),
        "z": float(norm.isf(p)),
        # no resample reached z: p is a bound, and z at least this
        "bound": reached == 0,
    }


def peak(x, y) -> tuple[float, float] | None:
    """The top of y(x): the vertex of the parabola through the largest y and
    its two neighbours; None where the largest y is at either end (no peak
    inside the range) or is not finite.

    Parameters
    ----------
    x, y : array_like
        Increasing x, and the values there.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if not np.all(np.isfinite(y)) or len(y) < 3:
        return None
    i = int(np.argmax(y))
    if i in (0, len(y) - 1):
        return None
    a, b, c = np.polyfit(x[i - 1 : i + 2], y[i - 1 : i + 2], 2)
    if a >= 0:
        return None
    top = -b / (2 * a)
    return float(top), float(c - b * b / (4 * a))


def grazing_numbers(rows: list[dict], resamples: int = 200, check: dict | None = None) -> dict:
    """Per lattice: tan gamma, mean e with errors, the peak, the largest mean
    and, with the normals' check (``analysis.normal_check.robustness``), each
    angle's verdict and the largest mean that the normals agree on.

    Parameters
    ----------
    rows : list of dict
        impacts.csv rows.
    resamples : int
        Seed-bootstrap resamples.
    check : dict, optional
        The normals' check of the same rows.

    Returns
    -------
    dict
        Per lattice; ``largest`` and ``largest_robust`` each with its e,
        error, local z and global (look-elsewhere) p and z.
    """
    tables = seed_tables(rows, ("e", "beta"))

    def tan(table: SeedTable) -> np.ndarray:
        return np.tan(np.radians(table.gamma_deg))

    def statistic(ts: dict[str, SeedTable]) -> dict:
        out = {}
        for name, t in ts.items():
            top = peak(tan(t), t.mean("e"))
            out[name + "/peak_x"], out[name + "/peak_e"] = top if top else (np.nan, np.nan)
            out[name + "/e"] = t.mean("e")
        return out

    central = statistic(tables)
    error = seed_bootstrap(tables, statistic, resamples)
    out = {}
    for name, t in tables.items():
        e, e_err = central[name + "/e"], error[name + "/e"]
        above = np.nan_to_num(t.values["e"]) > 1.0
        entry = (check or {}).get("lattices", {}).get(name)
        robust = spread = contact = None
        if entry is not None:
            index = {round(g, 9): j for j, g in enumerate(entry["gamma_deg"])}
            at = [index[round(float(g), 9)] for g in t.gamma_deg]
            robust = np.array([bool(entry["e_robust"][j]) for j in at])
            spread = np.array([float(entry["e_spread"][j]) for j in at])
            if "e_contact_robust" in entry:  # the headline and the impulse's normal alone
                contact = np.array([bool(entry["e_contact_robust"][j]) for j in at])

        def largest(among: np.ndarray) -> dict | None:
            if not among.any():
                return None
            top = int(np.nanargmax(np.where(among, e, -np.inf)))
            z = float((e[top] - 1.0) / e_err[top]) if e_err[top] > 0 else float("nan")
            return {
                "gamma_deg": float(t.gamma_deg[top]),
                "e": float(e[top]),
                "error": float(e_err[top]),
                "z": z,
                # the null of the largest of all the angles: conservative for a subset
                "global": look_elsewhere(t, z),
                "robust": True if robust is None else bool(robust[top]),
                "spread": None if spread is None else float(spread[top]),
            }

        everywhere = np.isfinite(e)
        out[name] = {
            "tan_gamma": tan(t).tolist(),
            "gamma_deg": t.gamma_deg.tolist(),
            "e": e.tolist(),
            "e_error": e_err.tolist(),
            "impacts": t.counts().tolist(),
            "share_above_1": (above.sum(axis=0) / np.maximum(t.counts(), 1)).tolist(),
            "peak_tan_gamma": central[name + "/peak_x"],
            "peak_tan_gamma_error": float(error[name + "/peak_x"]),
            "peak_e": central[name + "/peak_e"],
            "peak_e_error": float(error[name + "/peak_e"]),
            "largest": largest(everywhere),
            "largest_robust": largest(everywhere if robust is None else everywhere & robust),
            # where the headline and the impulse's normal agree, the first touch set aside
            "largest_contact": None if contact is None else largest(everywhere & contact),
        }
        if robust is not None:
            out[name].update(
                robust=robust.tolist(), spread=spread.tolist(), normals=check["normals"]
            )
    return out


def has_grazing_angles(rows: list[dict]) -> bool:
    return any(float(r["gamma_deg"]) > PAPER_LAST_ANGLE + 1e-6 for r in rows)


def significant(numbers: dict) -> bool:
    """e > 1 counts: the largest mean that the normals agree on is above 1
    beyond SIGNIFICANT errors once the look-elsewhere is counted."""
    largest = numbers.get("largest_robust")
    if not largest:
        return False
    z = largest["global"]["z"]
    return z is not None and np.isfinite(z) and z > SIGNIFICANT


def readings_numbers(
    readings: dict[str, tuple[dict, list[dict], list[dict]]], resamples: int = 200
) -> list[dict]:
    """The same grazing study under other readings (their tables: study.json,
    impacts.csv's and failed.csv's rows, by name): per reading and lattice,
    its grazing numbers (``grazing_numbers`` with the normals' check), its
    impacts, failed and stuck ones, and the share of contacts whose disk
    centre came within 1 R of a held side (None for two disks: no wall)."""
    from .normal_check import robustness

    out = []
    for name, (info, rows, failed) in readings.items():
        numbers = grazing_numbers(rows, resamples, robustness(rows, resamples))
        for lattice, n in numbers.items():
            mine = [r for r in rows if r["study_lattice"] == lattice]
            sides = [float(r["side_clearance"]) for r in mine if r.get("side_clearance") != ""]
            lost = len(genuine(failed))
            out.append(
                {
                    "reading": name,
                    "lattice": lattice,
                    "info": info,
                    "numbers": n,
                    "impacts": len(mine),
                    "failed": lost,
                    "stuck": len(failed) - lost,
                    "near_side": float(np.mean([c < 1.0 for c in sides])) if sides else None,
                }
            )
    return out
