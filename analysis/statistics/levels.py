"""Differences between resolutions per seed, and the multilevel Monte Carlo
allocation of seeds per resolution (docs/studies/resolution/resolution.md).

A multilevel estimate of Q at the finest resolution N_L writes it as
Q(N_0) + sum_l [Q(N_l) - Q(N_l-1)] and estimates each term from its own
seeds. Where a seed draws the same surface at every resolution, the per-seed
differences vary far less than Q itself, and few seeds suffice at the costly
levels. ``coupled_differences`` measures that: per pair of neighbouring
resolutions, the per-seed differences paired by seed and angle, their
seed-to-seed sd, and the sd of Q(N) over the same seeds. On rows whose
surfaces are redrawn per resolution the differences are what they are.

``allocation`` is Giles's (Acta Numerica 2015, section 1.3): for level
variances V_l (per seed) and costs C_l (per seed), the seeds that reach a
standard error ``target`` at the least cost are
n_l = target^-2 sqrt(V_l / C_l) sum_k sqrt(V_k C_k).
"""

from __future__ import annotations

import math

import numpy as np

from .measures import BETA_NORMAL_PSI, E_NORMAL_PSI, GRAZING_ANGLES

# The per-seed quantities: (impact column, the angles it averages).
GROUPS = {
    "e_normal": ("e", "normal", E_NORMAL_PSI),
    "e_grazing": ("e", "grazing", None),
    "beta_normal": ("beta", "normal", BETA_NORMAL_PSI),
    "beta_grazing": ("beta", "grazing", None),
}
MIN_SEEDS = 2


def _finished(rows: list[dict]) -> list[dict]:
    return [r for r in rows if not r.get("error") and r.get("e") not in (None, "")]


def angles_of(rows: list[dict], group: str) -> set[float]:
    """The angles (gamma_deg) a group averages: cot gamma at least its bound,
    or the GRAZING_ANGLES smallest cot gamma."""
    _, where, bound = GROUPS[group]
    cot = {float(r["gamma_deg"]): float(r["cot_gamma"]) for r in rows}
    if where == "grazing":
        return set(sorted(cot, key=cot.get)[:GRAZING_ANGLES])
    return {g for g, c in cot.items() if c >= bound}


def by_seed(rows: list[dict], column: str, angles: set[float]) -> dict[int, dict[float, float]]:
    """seed -> gamma_deg -> the impact's value, at ``angles``."""
    out: dict[int, dict[float, float]] = {}
    for r in _finished(rows):
        gamma = float(r["gamma_deg"])
        if gamma in angles:
            out.setdefault(int(float(r["seed"])), {})[gamma] = float(r[column])
    return out


def coupled_differences(rows: list[dict], group: str) -> list[dict]:
    """Per neighbouring pair of resolutions (N/2, N) of one reading and
    lattice's rows: the per-seed differences of ``group`` (GROUPS) paired by
    seed and angle.

    Returns
    -------
    list of dict
        One per N whose N/2 is in the rows: ``n``, ``seeds`` (paired),
        ``mean`` and ``se`` of the differences, ``sd_difference`` and
        ``sd_level`` (seed-to-seed sd, ddof 1, of Q(N) - Q(N/2) and of Q(N)
        on the same seeds and angles) and ``variance_ratio``.
    """
    column = GROUPS[group][0]
    done = _finished(rows)
    levels = sorted({int(r["n_disk"]) for r in done})
    out = []
    for n in levels:
        if n // 2 not in levels or n % 2:
            continue
        fine_rows = [r for r in done if int(r["n_disk"]) == n]
        coarse_rows = [r for r in done if int(r["n_disk"]) == n // 2]
        angles = angles_of(fine_rows, group) & angles_of(coarse_rows, group)
        fine, coarse = by_seed(fine_rows, column, angles), by_seed(coarse_rows, column, angles)
        differences, values = [], []
        for seed in sorted(set(fine) & set(coarse)):
            both = sorted(set(fine[seed]) & set(coarse[seed]))
            if not both:
                continue
            f = np.array([fine[seed][g] for g in both])
            c = np.array([coarse[seed][g] for g in both])
            differences.append(float(np.mean(f - c)))
            values.append(float(np.mean(f)))
        if len(differences) < MIN_SEEDS:
            continue
        sd_d, sd_q = np.std(differences, ddof=1), np.std(values, ddof=1)
        out.append(
            {
                "n": n,
                "seeds": len(differences),
                "mean": float(np.mean(differences)),
                "se": float(sd_d / math.sqrt(len(differences))),
                "sd_difference": float(sd_d),
                "sd_level": float(sd_q),
                "variance_ratio": float(sd_d**2 / sd_q**2) if sd_q > 0 else float("nan"),
            }
        )
    return out


def cost_per_impact(rows: list[dict]) -> dict[int, float]:
    """N -> the mean cost of one finished impact: its LAMMPS seconds where
    every row has them (timings.csv), else its atom-steps (steps times the
    disk's and the wall's points), a proxy that grows as the work does."""
    done = _finished(rows)
    timed = all(r.get("wall_seconds") not in (None, "") for r in done)
    out: dict[int, list[float]] = {}
    for r in done:
        if timed:
            cost = float(r["wall_seconds"])
        else:
            cost = float(r["steps"]) * (float(r["n_disk"]) + float(r["n_wall_points"]))
        out.setdefault(int(r["n_disk"]), []).append(cost)
    return {n: float(np.mean(v)) for n, v in sorted(out.items())}


def allocation(variances, costs, target: float, min_seeds: int = MIN_SEEDS) -> dict:
    """Giles's multilevel allocation of seeds (module docstring).

    Parameters
    ----------
    variances : sequence of float
        Per level, the per-seed variance of its term: of Q at the coarsest
        level, of Q(N_l) - Q(N_l-1) at the others.
    costs : sequence of float
        Per level, the cost of one seed of its term (a difference costs both
        resolutions' impacts).
    target : float
        The standard error wanted for the estimate of Q at the finest level.
    min_seeds : int
        At least this many seeds per level (an error needs two).

    Returns
    -------
    dict
        ``seeds`` (per level, whole), ``error`` (the standard error they
        give, sqrt(sum V_l / n_l)) and ``cost`` (sum n_l C_l).
    """
    v, c = np.asarray(variances, float), np.asarray(costs, float)
    if target <= 0 or np.any(v < 0) or np.any(c <= 0):
        raise ValueError("allocation needs target > 0, variances >= 0 and costs > 0")
    total = float(np.sum(np.sqrt(v * c)))
    seeds = np.maximum(np.ceil(np.sqrt(v / c) * total / target**2), min_seeds).astype(int)
    return {
        "seeds": seeds.tolist(),
        "error": float(np.sqrt(np.sum(v / seeds))),
        "cost": float(np.sum(seeds * c)),
    }


def variance_per_seed(sd: float, seeds: int) -> float:
    """A level's per-seed variance from the error of its estimate over
    ``seeds`` seeds (se^2 n): for quantities with no per-seed value (a fit)."""
    return float(sd**2 * seeds)


def multilevel_levels(
    base: tuple[int, float, float], steps: dict[int, tuple[float, float]]
) -> tuple[list[tuple[int, float, float]], dict[tuple[int, int], float]]:
    """Each level's multilevel estimate: the coarsest level ``base`` (N_0,
    value, error over all its seeds) plus the paired steps up to it
    (``steps``: N -> mean of Q(N) - Q(N/2) and its error, from
    ``coupled_differences``), following the halvings from N_0 while a step
    is there.

    Returns
    -------
    levels : list of (N, value, sd)
    covariance : dict
        (N, N') -> the covariance of the two estimates' errors: they share
        the coarsest level's and the steps below the coarser of the two,
        each term from its own seeds' draw and so independent of the others.
    """
    n0, value, sd = base
    chain, variances = [(n0, value)], [sd**2]
    while 2 * chain[-1][0] in steps:
        n = 2 * chain[-1][0]
        mean, se = steps[n]
        chain.append((n, chain[-1][1] + mean))
        variances.append(variances[-1] + se**2)
    out = [(n, v, math.sqrt(var)) for (n, v), var in zip(chain, variances, strict=True)]
    covariance = {
        (a, b): variances[min(i, j)]
        for i, (a, _) in enumerate(chain)
        for j, (b, _) in enumerate(chain)
    }
    return out, covariance
