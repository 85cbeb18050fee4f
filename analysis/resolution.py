"""e, beta and the fits against the disk's resolution (studies/resolution.toml,
docs/resolution.md).

The study runs the random and triangular disks from 200 to 12,800 points on
walls of twice their points, under three readings of how the model is carried
to finer disks (analysis.readings.LIMITS): "continuum" (a roughness profile of
fixed correlation length, the contact scaled with the spacing), and each of the
paper's per-point readings in turn. Fewer seeds where an impact costs more
(``plan``). Per reading and resolution: the model-free measures and Walton's
measured-way fit of every study (analysis.estimates.study_estimates on that
resolution's impacts alone, with its seed-bootstrap errors), then, per
quantity, a weighted straight line in the spacing h = sqrt(800 / N) through
the resolutions from 800 points up, whose intercept is the estimate of the
limit N -> infinity (its page: pages.resolution).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .estimates import study_estimates
from .readings import Setup

COLUMNS = (
    "reading",
    "limit",
    "n_disk",
    "study_lattice",
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "vn",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "side_clearance",
    "energy_drift",
    "drift_exceeded",
    "n_wall_points",
    "disk_inertia_ratio",
    "nu",
    "steps",
    "dt",
    "error",
)
# Seeds are full up to this many disk points; beyond, they fall as the
# points grow (an impact's cost grows about as N^1.5), to at least MIN_SAMPLES.
FULL_SAMPLES_UP_TO = 1600
MIN_SAMPLES = 4
# The per-point readings are followed as far as this (the paper's fixed
# contact is refused beyond: its exponential is not resolved at the cutoff).
PER_POINT_UP_TO = 3200
# The triangular disk as far as this, the random one as far as the study goes.
TRIANGULAR_UP_TO = 6400
# Readings whose seeds are coupled across the resolutions (one surface per
# seed: builder/profile.py): their seeds fall as N^-0.75 beyond
# FULL_SAMPLES_UP_TO, the multilevel allocation sqrt(V / C) for a cost per
# impact growing as N^1.5 and a variance of the differences that does not
# grow; the smooth baseline at SMOOTH_SAMPLES seeds up to SMOOTH_UP_TO.
COUPLED = ("profile", "smooth", "paper-slope")
SMOOTH_SAMPLES = 4
SMOOTH_UP_TO = 6400


def label(choice: dict) -> str:
    """A combination's reading: ``continuum_n800``."""
    return f"{choice['limit']}_n{choice['n_disk']}"


def row_fields(choice: dict, setup: Setup) -> dict:
    return {"limit": choice["limit"], "n_disk": choice["n_disk"]}


def samples_at(n_disk: int, samples: int) -> int:
    """Seeds at ``n_disk`` points: ``samples`` up to FULL_SAMPLES_UP_TO, then
    falling as 1 / N, never below MIN_SAMPLES."""
    if n_disk <= FULL_SAMPLES_UP_TO:
        return samples
    return max(MIN_SAMPLES, round(samples * FULL_SAMPLES_UP_TO / n_disk))


def coupled_samples_at(n_disk: int, samples: int) -> int:
    """Seeds at ``n_disk`` points for a coupled reading (COUPLED)."""
    if n_disk <= FULL_SAMPLES_UP_TO:
        return samples
    return max(MIN_SAMPLES, round(samples * (FULL_SAMPLES_UP_TO / n_disk) ** 0.75))


def plan(choice: dict, study):
    """The combination's study as run, or None to skip it: seeds by cost; the
    per-point readings on the random disk up to PER_POINT_UP_TO; the
    triangular disk up to TRIANGULAR_UP_TO."""
    n_disk = choice["n_disk"]
    lattices = tuple(study.lattices)
    if choice["limit"] == "smooth":
        if n_disk > SMOOTH_UP_TO:
            return None
        return replace(study, samples=min(study.samples, SMOOTH_SAMPLES))
    if choice["limit"] in COUPLED:
        return replace(study, samples=coupled_samples_at(n_disk, study.samples))
    if choice["limit"] != "continuum":
        if n_disk > PER_POINT_UP_TO:
            return None
        lattices = tuple(x for x in lattices if x == "random")
    elif n_disk > TRIANGULAR_UP_TO:
        lattices = tuple(x for x in lattices if x != "triangular")
    if not lattices:
        return None
    return replace(study, lattices=lattices, samples=samples_at(n_disk, study.samples))


RESAMPLES = 200
# The quantities followed against N: (key, label); ``extract`` reads them.
QUANTITIES = (
    ("e_normal", "e near normal incidence (cot gamma >= 1)"),
    ("mu", "Walton's mu (measured way)"),
    ("beta0", "Walton's beta0 (measured way)"),
    ("mu_eff_top", "mu_eff at the sliding branch's top"),
    ("e_grazing", "e at grazing incidence (3 smallest cot gamma)"),
)
# The extrapolation uses the resolutions from this many points up.
EXTRAPOLATE_FROM = 800
# Two numbers agree when they differ by less than this many combined errors.
AGREE = 2.0
CHI2_LIMIT = 2.0


def finished(rows: list[dict]) -> list[dict]:
    return [r for r in rows if not r.get("error") and r.get("e") not in (None, "")]


def extract(entry: dict) -> dict[str, tuple[float, float]]:
    """(value, seed-bootstrap sd) of each of QUANTITIES from a fits.json lattice entry."""
    walton = entry["walton"]["measured"]
    measures = entry["measures"]
    out = {
        key: (measures[key]["value"], measures[key]["sd"])
        for key in measures
        if key in dict(QUANTITIES)
    }
    out["mu"] = (walton["mu"], walton["mu_sd"])
    out["beta0"] = (walton["beta0"], walton["beta0_sd"])
    out["mu_chi2"] = (walton["chi2"], float("nan"))
    return out


def summaries(rows: list[dict]) -> dict[tuple[str, str, int], dict]:
    """(limit, lattice, n_disk) -> its quantities, impacts, seeds, failures and drift."""
    out = {}
    keys = sorted({(r["limit"], r["study_lattice"], int(r["n_disk"])) for r in rows})
    for limit, lattice, n_disk in keys:
        group = [
            r
            for r in rows
            if r["limit"] == limit and r["study_lattice"] == lattice and int(r["n_disk"]) == n_disk
        ]
        done = finished(group)
        entry = {
            "impacts": len(group),
            "failed": len(group) - len(done),
            "seeds": len({r["seed"] for r in group}),
            "dt": float(done[0]["dt"]) if done else float("nan"),
            "drift": max((abs(float(r["energy_drift"])) for r in done), default=float("nan")),
            "drifted": sum(r["drift_exceeded"] in ("True", "true", "1") for r in done),
        }
        if done:
            fits, _ = study_estimates(done, resamples=RESAMPLES, compliant=False)
            entry.update(extract(fits["lattices"][lattice]))
        out[(limit, lattice, n_disk)] = entry
    return out


def extrapolate(points: list[tuple[int, float, float]]) -> dict | None:
    """Weighted line q = q_inf + A h, h = sqrt(800 / N), through (N, q, sd)
    with N >= EXTRAPOLATE_FROM; None with fewer than three such points."""
    use = [(n, q, s) for n, q, s in points if n >= EXTRAPOLATE_FROM and s > 0 and np.isfinite(q)]
    if len(use) < 3:
        return None
    n, q, s = (np.array(v, float) for v in zip(*use, strict=True))
    h = np.sqrt(800.0 / n)
    design = np.stack([np.ones_like(h), h], axis=1) / s[:, None]
    coef, *_ = np.linalg.lstsq(design, q / s, rcond=None)
    covariance = np.linalg.inv(design.T @ design)
    chi2 = float(np.sum(((q - design @ coef * s) / s) ** 2) / (len(q) - 2))
    return {
        "limit": float(coef[0]),
        "limit_sd": float(np.sqrt(covariance[0, 0])),
        "slope": float(coef[1]),
        "slope_sd": float(np.sqrt(covariance[1, 1])),
        "chi2": chi2,
        "points": len(q),
        "from": int(n.min()),
        "to": int(n.max()),
    }


def limit_lines(summary: dict) -> dict:
    """Per (limit, lattice, quantity): its points (N, value, sd), the line
    ``extrapolate`` gives, the 800-point value and the finest (N, value)."""
    out = {}
    for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=order):
        ns = sorted(n for (li, la, n) in summary if (li, la) == (limit, lattice))
        for q, _ in QUANTITIES:
            points = [
                (n, *summary[(limit, lattice, n)][q])
                for n in ns
                if q in summary[(limit, lattice, n)]
            ]
            out[(limit, lattice, q)] = {
                "line": extrapolate(points),
                "at_800": next(((v, s) for n, v, s in points if n == 800), None),
                "finest": (points[-1][0], points[-1][1]) if points else None,
            }
    return out


def order(key: tuple[str, str]) -> tuple[int, str]:
    limits = ("continuum", "point-roughness", "fixed-contact")
    return (limits.index(key[0]) if key[0] in limits else len(limits), key[1])


def means_by_angle(rows: list[dict], limit: str, lattice: str) -> dict[int, list[tuple]]:
    """N -> [(cot gamma, e mean, e se, beta mean, beta se)] over the seeds."""
    out: dict[int, list[tuple]] = {}
    mine = [r for r in finished(rows) if r["limit"] == limit and r["study_lattice"] == lattice]
    for n in sorted({int(r["n_disk"]) for r in mine}):
        at_n = [r for r in mine if int(r["n_disk"]) == n]
        points = []
        for gamma in sorted({float(r["gamma_deg"]) for r in at_n}):
            here = [r for r in at_n if float(r["gamma_deg"]) == gamma]
            e = np.array([float(r["e"]) for r in here])
            beta = np.array([float(r["beta"]) for r in here])
            cot = float(np.mean([float(r["cot_gamma"]) for r in here]))
            se = lambda a: a.std(ddof=1) / np.sqrt(len(a)) if len(a) > 1 else np.nan  # noqa: E731
            points.append((cot, e.mean(), se(e), beta.mean(), se(beta)))
        out[n] = points
    return out
