"""e, beta and the fits against the disk's resolution (studies/resolution.toml,
docs/studies/resolution/resolution.md), for any reading (the rows' ``limit``) and any levels.

The study runs the random and triangular disks from 200 to 12,800 points on
walls of twice their points, under readings of how the model is carried to
finer disks (analysis.kinds.readings.LIMITS). Fewer seeds where an impact costs
more (``plan``). Per reading and resolution (``summaries``): the model-free
measures and Walton's fits both ways (analysis.statistics.estimates.study_estimates on
that resolution's impacts alone; errors by the seed count,
analysis.statistics.seeds.seed_errors), the fitting choice's systematic error, and
whether the level is left out of the fits (too many impacts over the drift
limit or failed). Per quantity, its limit with the form's band or "not
converged" (``limits``, analysis.statistics.extrapolation), and per reading the
per-seed differences between resolutions and Giles's allocation of seeds
(``multilevel``, analysis.statistics.levels). Its page: pages.resolution.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from builder.study_names import LIMITS

from ..statistics import extrapolation, levels, walton_gls
from ..statistics.claims import SAME
from ..statistics.estimates import PAPER, lattice_constants, study_estimates
from ..statistics.fits import means, walton_mu_bounds
from ..statistics.measures import GRAZING_ANGLES
from ..statistics.plateau import beta_rise, mu_eff_grazing
from ..statistics.seeds import seed_tables
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
COUPLED = (
    "profile",
    "smooth",
    "paper-slope",
    "profile-floor",
    "slope0.3-floor",
    "paper-slope-floor",
)
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


def plan(choice: dict, study, thin: bool = True):
    """The combination's study as run, or None to skip it: seeds by cost
    (unless ``thin`` is False: the study file gave each level's seeds, which
    every reading then runs as given, the smooth one too); the
    per-point readings on the random disk up to PER_POINT_UP_TO; the
    triangular disk up to TRIANGULAR_UP_TO."""
    n_disk = choice["n_disk"]
    lattices = tuple(study.lattices)
    samples = study.samples
    if choice["limit"] == "smooth":
        if n_disk > SMOOTH_UP_TO:
            return None
        return replace(study, samples=min(samples, SMOOTH_SAMPLES) if thin else samples)
    if choice["limit"] in COUPLED:
        return replace(study, samples=coupled_samples_at(n_disk, samples) if thin else samples)
    if choice["limit"] != "continuum":
        if n_disk > PER_POINT_UP_TO:
            return None
        lattices = tuple(x for x in lattices if x == "random")
    elif n_disk > TRIANGULAR_UP_TO:
        lattices = tuple(x for x in lattices if x != "triangular")
    if not lattices:
        return None
    return replace(
        study, lattices=lattices, samples=samples_at(n_disk, samples) if thin else samples
    )


RESAMPLES = 200
# The quantities followed against N: (key, label); ``extract`` reads them.
QUANTITIES = (
    ("e_normal", "e near normal incidence (cot gamma >= 1)"),
    ("e_grazing", "e at grazing incidence (3 smallest cot gamma)"),
    ("mu", "Walton's mu (measured way)"),
    ("beta0", "Walton's beta0 (measured way)"),
    ("mu_branch", "mu on the sliding branch found in the rows (its angles' mean mu_eff)"),
    ("mu_eff_grazing", "mu_eff at the most grazing angle (mu, or a lower bound of it)"),
    ("mu_gls", "Walton's mu, fitted with the seeds' covariance"),
    ("beta0_gls", "Walton's beta0, fitted with the seeds' covariance"),
)
# The quantities whose steps between resolutions are paired by seed (``limits``).
PAIRED = ("e_normal", "e_grazing")
# Walton's fitted parameters, which carry the fitting choice's systematic error.
FITTED = ("mu", "beta0", "mu_paper", "beta0_paper")
# A level with more than this share of its impacts over the drift limit, or
# failed, is left out of the fits (its numbers are shown, marked).
DRIFT_SHARE = 0.1
FAILED_SHARE = 0.1


def finished(rows: list[dict]) -> list[dict]:
    return [r for r in rows if not r.get("error") and r.get("e") not in (None, "")]


def extract(fits: dict, lattice: str) -> dict[str, tuple[float, float]]:
    """(value, statistical error) of each quantity from one level's
    ``study_estimates``: QUANTITIES, the paper's-way fit (``mu_paper``,
    ``beta0_paper``), ``beta_normal``, ``share_beta_positive`` and
    ``share_near_side``."""
    entry = fits["lattices"][lattice]
    out = {
        key: (value["value"], value["sd"])
        for key, value in entry["measures"].items()
        if key != "mu_eff" and value["value"] is not None
    }
    # a level whose rows hold no sliding branch keeps it, as NaN: its claim
    # is undecided there, and the limit withheld (``unidentified``)
    if entry["measures"]["mu_branch"]["value"] is None:
        out["mu_branch"] = (float("nan"), float("nan"))
    for way, suffix in (("measured", ""), ("paper", "_paper")):
        walton = entry["walton"][way]
        out[f"mu{suffix}"] = (walton["mu"], walton["mu_sd"])
        out[f"beta0{suffix}"] = (walton["beta0"], walton["beta0_sd"])
    return {k: (float(v), float(s) if s is not None else float("nan")) for k, (v, s) in out.items()}


def grazing_peak(done: list[dict], mean_sd: dict, lattice: str) -> tuple[float, float]:
    """The largest mean e of the GRAZING_ANGLES most grazing angles, with its
    error (the letter's e > 1 grazing peak)."""
    best = None
    for gamma in sorted({float(r["gamma_deg"]) for r in done}, reverse=True)[:GRAZING_ANGLES]:
        e = np.mean([float(r["e"]) for r in done if float(r["gamma_deg"]) == gamma])
        if best is None or e > best[0]:
            best = (float(e), float(mean_sd[(lattice, gamma)]["e_seed_sd"]))
    return best


def short_angles(done: list[dict], seeds: int) -> list[tuple[float, int]]:
    """(gamma_deg, seeds) of the angles that rest on fewer than all the level's seeds."""
    count: dict[float, set] = {}
    for r in done:
        count.setdefault(float(r["gamma_deg"]), set()).add(r["seed"])
    return [(g, len(s)) for g, s in sorted(count.items()) if len(s) < seeds]


def excluded(entry: dict) -> str | None:
    """Why a level is left out of the fits (DRIFT_SHARE, FAILED_SHARE), or None."""
    if entry["impacts"] and entry["drifted"] > DRIFT_SHARE * entry["impacts"]:
        return f"{entry['drifted']} of {entry['impacts']} impacts over the drift limit"
    if entry["impacts"] and entry["failed"] > FAILED_SHARE * entry["impacts"]:
        return f"{entry['failed']} of {entry['impacts']} impacts failed"
    return None


def summaries(rows: list[dict]) -> dict[tuple[str, str, int], dict]:
    """(limit, lattice, n_disk) -> its quantities (value, statistical error),
    Walton's fitting-choice systematic and chi2/dof, impacts, seeds, the
    errors' method, failures, drift, the angles short of seeds and whether
    the level is left out of the fits."""
    out = {}
    keys = sorted({(r["limit"], r["study_lattice"], int(r["n_disk"])) for r in rows})
    for limit, lattice, n_disk in keys:
        group = [
            r
            for r in rows
            if r["limit"] == limit and r["study_lattice"] == lattice and int(r["n_disk"]) == n_disk
        ]
        done = finished(group)
        seeds = len({r["seed"] for r in group})
        entry = {
            "impacts": len(group),
            "failed": len(group) - len(done),
            "seeds": seeds,
            "dt": float(done[0]["dt"]) if done else float("nan"),
            "drift": max((abs(float(r["energy_drift"])) for r in done), default=float("nan")),
            "drifted": sum(r["drift_exceeded"] in ("True", "true", "1") for r in done),
            "short_angles": short_angles(done, seeds),
            "values": {},
        }
        entry["excluded"] = excluded(entry)
        if done:
            fits, mean_sd = study_estimates(
                done, resamples=RESAMPLES, compliant=False, by_seed_count=True
            )
            entry["values"] = extract(fits, lattice)
            entry["values"]["e_peak_grazing"] = grazing_peak(done, mean_sd, lattice)
            walton = fits["lattices"][lattice]["walton"]
            entry["systematic"] = walton["systematic"]
            entry["chi2"] = {way: walton[way]["chi2"] for way in ("measured", "paper")}
            entry["errors"] = fits["errors"]
            entry["mu_bounds"] = mu_bounds(done, lattice)
            # what the rows say with no model, seed by seed (analysis.statistics.plateau)
            table = seed_tables(done)[lattice]
            entry["plateau"] = beta_rise(table)
            grazing = mu_eff_grazing(table, lattice_constants(done, lattice)[2])
            entry["values"]["mu_eff_grazing"] = (grazing["value"], grazing["sd"])
            entry["grazing_deg"] = grazing["gamma_deg"]
            # the same bound as the paper's way writes mu (e 0.8, K 3)
            paper = mu_eff_grazing(table, PAPER["K"], PAPER["e"])
            entry["mu_eff_grazing_paper"] = (paper["value"], paper["sd"])
            # Walton with the means' correlations counted (analysis.statistics.walton_gls)
            gls = walton_gls.estimates(table, lattice_constants(done, lattice)[2], RESAMPLES)
            if gls is not None:
                entry["gls"] = gls
                entry["mu_bounds"]["gls"] = gls["mu_bounds"]
                entry["chi2"]["gls"] = gls["chi2"] / gls["dof"]
                entry["values"]["mu_gls"] = (gls["mu"], gls["mu_sd"])
                entry["values"]["beta0_gls"] = (gls["beta0"], gls["beta0_sd"])
        out[(limit, lattice, n_disk)] = entry
    return out


# The rise of chi^2 that bounds mu: two errors, as every claim is judged
# (analysis.statistics.claims.SAME).
MU_RISE = SAME**2


def mu_bounds(done: list[dict], lattice: str) -> dict[str, tuple[float, float]]:
    """Walton's mu that a level's per-angle means allow, both ways
    (``analysis.statistics.fits.walton_mu_bounds``: within MU_RISE of the
    least chi^2, the means weighted by their errors, which say what the data
    can tell apart, also for the paper's unweighted way); infinite above
    where the weighted fit puts no angle on its sliding branch."""
    data = means(seed_tables(done)[lattice])
    K = lattice_constants(done, lattice)[2]
    return {
        "measured": walton_mu_bounds(data, K, rise=MU_RISE),
        "paper": walton_mu_bounds(data, PAPER["K"], PAPER["e"], rise=MU_RISE),
    }


# Walton's mu, each way: where a level's data bound it from below only (no
# angle on the sliding branch), no limit is sought; nor for mu on the
# branch where a level's rows hold no branch (analysis.statistics.sliding).
# The paper's way is the paper's own procedure: its number and seed error
# stand as the paper gave them, judged against the rows' own lower bound
# (analysis.statistics.resolution_claims.contradicted), not withheld.
MU_WAYS = {"mu": "measured", "mu_gls": "gls"}


def unidentified(summary: dict, limit: str, lattice: str, quantity: str) -> list[tuple]:
    """[(N, lowest mu)] of the fitted levels whose data leave ``quantity``
    (MU_WAYS) without an upper bound, or hold no sliding branch for
    mu_branch (its lowest: mu_eff at the most grazing angle). One such level
    withholds the limit, however few the levels ("not identified" before
    "too few")."""
    mine = [
        (n, entry)
        for (li, la, n), entry in sorted(summary.items())
        if (li, la) == (limit, lattice) and n >= extrapolation.FIT_FROM and not entry["excluded"]
    ]
    if quantity == "mu_branch":
        return [
            (n, entry["values"]["mu_eff_grazing"][0])
            for n, entry in mine
            if "mu_branch" in entry["values"] and not np.isfinite(entry["values"]["mu_branch"][0])
        ]
    if quantity not in MU_WAYS:
        return []
    return [
        (n, entry["mu_bounds"][MU_WAYS[quantity]][0])
        for n, entry in mine
        if MU_WAYS[quantity] in entry.get("mu_bounds", {})
        and np.isinf(entry["mu_bounds"][MU_WAYS[quantity]][1])
    ]


def rising(summary: dict, limit: str, lattice: str) -> list[int]:
    """The levels N (from extrapolation.FIT_FROM) whose beta rises, seed by
    seed, from grazing to normal incidence (``plateau.beta_rise``): not
    Walton's one plateau, whatever its fit's profile says of mu."""
    return [
        n
        for (li, la, n), entry in sorted(summary.items())
        if (li, la) == (limit, lattice)
        and n >= extrapolation.FIT_FROM
        and entry.get("plateau", {}).get("on_plateau") is False
    ]


def levels_of(summary: dict, limit: str, lattice: str, quantity: str, fitted_only: bool = True):
    """[(N, value, error)] of one quantity, the excluded levels left out if ``fitted_only``."""
    return [
        (n, *entry["values"][quantity])
        for (li, la, n), entry in sorted(summary.items())
        if (li, la) == (limit, lattice)
        and quantity in entry["values"]
        and not (fitted_only and entry["excluded"])
    ]


def limits(
    summary: dict, quantities=tuple(q for q, _ in QUANTITIES), rows: list[dict] | None = None
) -> dict:
    """(limit, lattice, quantity) -> ``analysis.statistics.extrapolation.limit`` of its
    levels that are not excluded, each level's seeds setting the test of its
    steps; with ``rows``, the steps of the quantities that have a value per
    seed (PAIRED) are the per-seed differences paired by seed and angle
    (``analysis.statistics.levels.coupled_differences``: right whether or not the seeds
    are coupled across N, and tighter where they are). For a reading whose
    seeds draw one surface at every N (COUPLED), and whose every step varies
    less than its level, those quantities' levels from
    extrapolation.FIT_FROM up enter as their multilevel estimates
    (``coupled_levels``), with their covariance."""
    pairs = sorted({(k[0], k[1]) for k in summary}, key=order)
    out = {}
    for limit, lattice in pairs:
        seeds = {
            n: s["seeds"] for (li, la, n), s in summary.items() if (li, la) == (limit, lattice)
        }
        mine = [r for r in rows or () if r["limit"] == limit and r["study_lattice"] == lattice]
        for q in quantities:
            steps, pays = None, False
            if mine and q in PAIRED:
                differences = levels.coupled_differences(mine, q)
                steps = {d["n"]: (d["mean"], d["se"]) for d in differences}
                # the multilevel estimate pays where every step varies less
                # than its level (the smooth disk's interiors, drawn anew at
                # each N, couple nothing)
                pays = limit in COUPLED and all(
                    d["variance_ratio"] < 1 for d in differences if d["n"] > extrapolation.FIT_FROM
                )
            found, covariance = levels_of(summary, limit, lattice, q), None
            if open_above := unidentified(summary, limit, lattice, q):
                # the fit's value is wherever its search stopped in a flat valley
                out[(limit, lattice, q)] = {
                    "status": "not identified",
                    "levels": [n for n, _, _ in found if n >= extrapolation.FIT_FROM],
                    "forms": {},
                    "halvings": None,
                    "open_above": open_above,
                    "rising": rising(summary, limit, lattice),
                    "of": q,
                }
                continue
            if pays:
                found, covariance = coupled_levels(found, steps)
            out[(limit, lattice, q)] = extrapolation.limit(found, steps, seeds, covariance)
    return out


def coupled_levels(found: list[tuple], steps: dict) -> tuple[list[tuple], dict | None]:
    """The levels (N, value, error) from extrapolation.FIT_FROM up as their
    multilevel estimates (analysis.statistics.levels.multilevel_levels): the
    FIT_FROM level over all its seeds plus the paired steps up to each, which
    vary far less than the levels where one surface serves every N. Unbiased
    as the levels are, and on more seeds; their errors are then correlated
    (the covariance, for the fits). The levels as they are (and no
    covariance) unless the steps join every one of them."""
    by_n = {n: (v, s) for n, v, s in found}
    fitted = sorted(n for n in by_n if n >= extrapolation.FIT_FROM)
    if not fitted or fitted[0] != extrapolation.FIT_FROM:
        return found, None
    base = (fitted[0], *by_n[fitted[0]])
    chain, covariance = levels.multilevel_levels(
        base, {n: steps[n] for n in fitted[1:] if n in steps}
    )
    if [n for n, _, _ in chain] != fitted:
        return found, None
    below = [x for x in found if x[0] < extrapolation.FIT_FROM]
    return below + chain, covariance


def order(key: tuple[str, str]) -> tuple[int, str, str]:
    """(reading, lattice) in the order the readings are declared
    (builder.study_names.LIMITS), then by name: never a set's order, which
    changes with the interpreter's string hashing."""
    limits = tuple(LIMITS)
    return (limits.index(key[0]) if key[0] in limits else len(limits), key[0], key[1])


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


# The multilevel estimate's targets (issue 46): standard errors wanted.
TARGETS = {"e_normal": 0.005, "mu": 0.01}


def halving_chain(ns: list[int]) -> list[int]:
    """The levels from extrapolation.FIT_FROM up that follow each other by halvings."""
    chain = [n for n in ns if n == extrapolation.FIT_FROM]
    while chain and 2 * chain[-1] in ns:
        chain.append(2 * chain[-1])
    return chain


def multilevel(rows: list[dict], summary: dict, limit: str, lattice: str) -> dict:
    """One reading and lattice's per-seed differences between resolutions
    (``analysis.statistics.levels.coupled_differences`` of every group) and, per
    quantity of TARGETS, Giles's seeds per level over the halvings from 800
    points that are not left out: the level variances per seed (the
    coarsest's from its error times its seeds; the differences' measured per
    seed for e, and for Walton's mu, which has no per-seed value, the two
    levels' per-seed variances summed, as for independent draws), the cost of
    a seed in 800-point seeds, the allocation, and the finest level alone at
    the same error."""
    mine = [r for r in finished(rows) if r["limit"] == limit and r["study_lattice"] == lattice]
    differences = {group: levels.coupled_differences(mine, group) for group in levels.GROUPS}
    chain = halving_chain([n for n, *_ in levels_of(summary, limit, lattice, "e_normal")])
    out = {"differences": differences, "plans": {}}
    if len(chain) < 2:
        return out
    angles = len({r["gamma_deg"] for r in mine})
    cost = {n: c * angles for n, c in levels.cost_per_impact(mine).items()}
    unit = cost[chain[0]]

    def per_seed(q: str, n: int) -> float:
        entry = summary[(limit, lattice, n)]
        return levels.variance_per_seed(entry["values"][q][1], entry["seeds"])

    for q, target in TARGETS.items():
        if unidentified(summary, limit, lattice, q):  # no error to allocate for
            continue
        variances, costs = [per_seed(q, chain[0])], [cost[chain[0]] / unit]
        measured = {d["n"]: d["sd_difference"] ** 2 for d in differences["e_normal"]}
        for n in chain[1:]:
            if q == "e_normal" and n in measured:
                variances.append(measured[n])
            else:
                variances.append(per_seed(q, n) + per_seed(q, n // 2))
            costs.append((cost[n] + cost[n // 2]) / unit)
        plan = levels.allocation(variances, costs, target)
        alone = max(np.ceil(per_seed(q, chain[-1]) / target**2), levels.MIN_SEEDS)
        out["plans"][q] = {
            "target": target,
            "levels": chain,
            "variances": variances,
            "costs": costs,
            **plan,
            "finest_alone_seeds": int(alone),
            "finest_alone_cost": float(alone * cost[chain[-1]] / unit),
        }
    return out
