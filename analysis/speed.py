"""e and beta against the impact speed: the speed study's numbers (its page: pages.speed).

A speed study (``runner study speed``) runs every lattice at a few angles and
several normal approach speeds v_n, with the same seeds at every speed and
angle; so, as everywhere in this project, errors come from resampling whole
seeds (analysis.statistics.seeds): a seed's impacts at every speed, angle and lattice go
into a resample together.

From the means per lattice, speed and angle:

- ``1 - e`` against v_n, and a power law 1 - e = A v_n^p fitted over the
  widest run of consecutive speeds where it holds (reduced chi^2 at most
  ``POWER_LAW_CHI2``), p with its seed-bootstrap error;
- beta at the sticking angle (the largest cot gamma below the near-normal
  one) and the Coulomb friction the sliding angle (the smallest cot gamma)
  implies, mu_eff = (1 + beta) / ((1 + e) K psi) (analysis.statistics.measures), as
  beta0 and mu against v_n;
- the lattices' order by e beside their order by shear over bulk modulus
  (calibration/materials.json), which Gerl and Zippelius (Phys. Rev. E 59,
  2361, 1999) found to set how inelastic a lattice disk is.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from builder.materials import calibrated
from ground.digits import rounded
from ground.gate import write_text

from .impact.failures import genuine
from .statistics.measures import mu_eff
from .statistics.seeds import RNG_SEED, SeedTable, seed_bootstrap, seed_tables
from .table import NEAR_SIDE

# A power law "holds" over a run of speeds whose fit has a reduced chi^2 at
# most this; the run must hold at least POWER_LAW_POINTS speeds.
POWER_LAW_CHI2 = 2.0
POWER_LAW_POINTS = 3
SPEED_QUANTITIES = ("e", "beta", "side_clearance")


def power_law(v, y, sigma) -> dict:
    """Fit y = A v^p by weighted least squares in log-log.

    Parameters
    ----------
    v, y, sigma : array_like
        Speeds, values (> 0) and their standard errors.

    Returns
    -------
    dict
        ``p``, ``A``, ``p_fit_error`` (from the fit's covariance, the points
        taken as independent) and ``chi2`` (reduced; NaN with no degrees of
        freedom).
    """
    v, y, sigma = (np.asarray(a, float) for a in (v, y, sigma))
    log_sigma = sigma / y
    # a straight line in log-log: numpy's weighted least squares in closed
    # form, its covariance from the errors as given (absolute)
    (p, log_a), cov = np.polyfit(np.log(v), np.log(y), 1, w=1.0 / log_sigma, cov="unscaled")
    residual = (np.log(y) - log_a - p * np.log(v)) / log_sigma
    dof = len(v) - 2
    return {
        "p": float(p),
        "A": float(math.exp(log_a)),
        "p_fit_error": float(math.sqrt(cov[0, 0])),
        "chi2": float(np.sum(residual**2) / dof) if dof > 0 else float("nan"),
    }


def power_law_range(
    v, y, sigma, max_chi2: float = POWER_LAW_CHI2, min_points: int = POWER_LAW_POINTS
) -> tuple[int, int] | None:
    """The widest run of consecutive points [i, j) that a power law fits.

    Among runs of at least ``min_points`` points with every y > 0 and a
    reduced chi^2 at most ``max_chi2``, the longest; between runs as long,
    the one of least chi^2. None if there is none.
    """
    v, y, sigma = (np.asarray(a, float) for a in (v, y, sigma))
    best, best_key = None, None
    for i in range(len(v)):
        for j in range(i + min_points, len(v) + 1):
            ok = np.all(y[i:j] > 0) and np.all(np.isfinite(sigma[i:j])) and np.all(sigma[i:j] > 0)
            if not ok:
                continue
            fit = power_law(v[i:j], y[i:j], sigma[i:j])
            if not fit["chi2"] <= max_chi2:
                continue
            key = (j - i, -fit["chi2"])
            if best_key is None or key > best_key:
                best, best_key = (i, j), key
    return best


def speed_rows(rows: list[dict]) -> list[dict]:
    """The rows with a table key per lattice and speed, for seed_tables."""
    return [{**r, "study_lattice": f"{r['study_lattice']}|{float(r['vn']):g}"} for r in rows]


def split_key(key: str) -> tuple[str, float]:
    lattice, vn = key.split("|")
    return lattice, float(vn)


def shear_over_bulk(lattice: str, k2_over_k1: float | None = None) -> float:
    """Shear over 2-D bulk modulus in the axes' frame, the wall's normal and
    tangent (calibration/materials.json): the strip pulled at 45 degrees gives
    the axes' G (docs/calibration/materials.md); the random lattice has one G."""
    angle = 0.0 if lattice == "random" else 45.0
    return float(calibrated(lattice, k2_over_k1, angle)["G_over_B"])


def estimates(rows: list[dict], resamples: int = 200) -> dict:
    """Means, power laws, beta0 and mu per lattice and speed, with seed-bootstrap errors."""
    tables = seed_tables(speed_rows(rows), SPEED_QUANTITIES)
    lattices = sorted({split_key(k)[0] for k in tables})
    speeds = sorted({split_key(k)[1] for k in tables})
    gammas = next(iter(tables.values())).gamma_deg
    psi = 1.0 / np.tan(np.radians(gammas))
    K = {r["study_lattice"]: 1.0 + 1.0 / float(r["disk_inertia_ratio"]) for r in rows}
    # angles increase: the first is near-normal, the next the sticking one, the
    # last the sliding one
    sticking = 1 if len(gammas) > 2 else 0
    sliding = len(gammas) - 1

    def key(lattice: str, vn: float) -> str:
        return f"{lattice}|{vn:g}"

    def means(ts: dict[str, SeedTable]) -> dict:
        """e and beta per angle, beta0 and mu_eff, per lattice and speed."""
        out = {}
        for lattice in lattices:
            for vn in speeds:
                k = key(lattice, vn)
                e, beta = ts[k].mean("e"), ts[k].mean("beta")
                out[k + "/e"], out[k + "/beta"] = e, beta
                out[k + "/beta0"] = beta[sticking]
                out[k + "/mu"] = mu_eff(psi[sliding], e[sliding], beta[sliding], K[lattice])
        return out

    central = means(tables)
    error = seed_bootstrap(tables, means, resamples, RNG_SEED)

    # each power law's run of speeds is fixed from the central means and their
    # errors before its exponent is resampled
    spans = {}
    for lattice in lattices:
        for j in range(len(gammas)):
            y = [1.0 - central[key(lattice, vn) + "/e"][j] for vn in speeds]
            sigma = [error[key(lattice, vn) + "/e"][j] for vn in speeds]
            span = power_law_range(speeds, y, sigma)
            if span is not None:
                spans[(lattice, j)] = (span, np.array(sigma[span[0] : span[1]]))

    def exponents(ts: dict[str, SeedTable]) -> dict:
        out = {}
        for (lattice, j), ((i0, i1), sigma) in spans.items():
            y = np.array([1.0 - ts[key(lattice, vn)].mean("e")[j] for vn in speeds[i0:i1]])
            ok = np.all(y > 0)
            out[f"{lattice}/{j}"] = power_law(speeds[i0:i1], y, sigma)["p"] if ok else np.nan
        return out

    p_error = seed_bootstrap(tables, exponents, resamples, RNG_SEED)

    out: dict = {
        "speeds": speeds,
        "gamma_deg": [float(g) for g in gammas],
        "cot_gamma": [float(p) for p in psi],
        "sticking_gamma": float(gammas[sticking]),
        "sliding_gamma": float(gammas[sliding]),
        "resamples": resamples,
        "lattices": {},
    }
    for lattice in lattices:
        laws = []
        for j in range(len(gammas)):
            if (lattice, j) not in spans:
                laws.append(None)
                continue
            (i0, i1), sigma = spans[(lattice, j)]
            y = [1.0 - central[key(lattice, vn) + "/e"][j] for vn in speeds[i0:i1]]
            law = power_law(speeds[i0:i1], y, sigma)
            law.update(
                v_low=speeds[i0],
                v_high=speeds[i1 - 1],
                points=i1 - i0,
                p_error=float(p_error[f"{lattice}/{j}"]),
            )
            laws.append(law)

        def column(name: str, source: dict, lattice: str = lattice) -> list:
            return [np.asarray(source[key(lattice, vn) + name]).tolist() for vn in speeds]

        out["lattices"][lattice] = {
            "K": K[lattice],
            "impacts": [tables[key(lattice, vn)].counts().tolist() for vn in speeds],
            "e": column("/e", central),
            "e_error": column("/e", error),
            "beta": column("/beta", central),
            "beta_error": column("/beta", error),
            "beta0": column("/beta0", central),
            "beta0_error": column("/beta0", error),
            "mu": column("/mu", central),
            "mu_error": column("/mu", error),
            "power_law": laws,
        }
    return out


def write_json(numbers: dict, path: Path) -> None:
    """speed.json, with null where a number is undefined (JSON has no NaN)."""
    write_text(path, json.dumps(rounded(numbers), indent=1).replace("NaN", "null") + "\n")


# Gerl and Zippelius's trend and order count where e differs by more than
# this many combined errors.
BEYOND = 2.0


def by_shear_over_bulk(numbers: dict, lattice_specs: dict) -> list[dict]:
    """The lattices of ``numbers`` that ``lattice_specs`` (builder.materials)
    has, in increasing shear over bulk modulus G / B, each with its G / B."""
    ratio = {
        k: shear_over_bulk(s["lattice"], s.get("k2_over_k1")) for k, s in lattice_specs.items()
    }
    present = [k for k in numbers["lattices"] if k in ratio]
    return [{"lattice": k, "ratio": ratio[k]} for k in sorted(present, key=lambda k: ratio[k])]


def trend(numbers: dict, lattices: list[str]) -> dict:
    """e at near-normal incidence from the slowest to the fastest impact, per
    lattice (``e0``, ``e1``, and the change ``drop`` in combined errors), and
    on how many lattices it falls by more than BEYOND errors."""
    out, falls = [], 0
    for k in lattices:
        data = numbers["lattices"][k]
        e0, e1 = data["e"][0][0], data["e"][-1][0]
        s0, s1 = data["e_error"][0][0], data["e_error"][-1][0]
        drop = float((e0 - e1) / np.hypot(s0, s1))
        falls += drop > BEYOND
        out.append({"lattice": k, "e0": e0, "e1": e1, "drop": drop})
    return {"lattices": out, "falls": int(falls)}


def order_counts(numbers: dict, by_ratio: list[str]) -> list[dict]:
    """Per speed, the pairs of lattices whose e differs by more than BEYOND
    combined errors: how many are in the order of G / B (the lower G / B,
    the lower e) and how many against it."""
    out = []
    for i, v in enumerate(numbers["speeds"]):
        e = [numbers["lattices"][k]["e"][i][0] for k in by_ratio]
        s = [numbers["lattices"][k]["e_error"][i][0] for k in by_ratio]
        agree = against = 0
        for a in range(len(e)):
            for b in range(a + 1, len(e)):
                if abs(e[b] - e[a]) > BEYOND * np.hypot(s[a], s[b]):
                    agree += e[b] > e[a]
                    against += e[b] < e[a]
        out.append({"vn": v, "agree": int(agree), "against": int(against)})
    return out


def outcomes(rows: list[dict], failed: list[dict], speeds: list[float]) -> list[dict]:
    """Per speed: the impacts, those that failed, those whose energy drift
    exceeds the guard, and the largest |drift|."""
    out = []
    for v in speeds:
        mine = [r for r in rows if math.isclose(float(r["vn"]), v)]
        lost = [f for f in genuine(failed) if math.isclose(float(f.get("vn") or "nan"), v)]
        drift = [abs(float(r["energy_drift"])) for r in mine] or [float("nan")]
        above = sum(str(r["drift_exceeded"]) == "True" for r in mine)
        counts = {"impacts": len(mine), "failed": len(lost), "above": above}
        out.append({"vn": v, **counts, "drift": max(drift)})
    return out


def near_side_counts(rows: list[dict]) -> list[dict]:
    """Per lattice, speed and angle: the impacts, and those whose disk centre
    came within 1 R of a held side (analysis.table.NEAR_SIDE)."""
    out: dict = {}
    for r in rows:
        key = (f"{r['study_lattice']}, v_n {float(r['vn']):g}", float(r["gamma_deg"]))
        entry = out.setdefault(
            key, {"study_lattice": key[0], "gamma_deg": key[1], "near_side": 0, "samples": 0}
        )
        entry["samples"] += 1
        entry["near_side"] += float(r["side_clearance"]) < NEAR_SIDE
    return [m for m in out.values() if m["near_side"]]
