"""Two disks against the symmetric references (studies/binary_references.toml,
docs/studies/binary_references/): does two-body physics change e, beta and
mu, and does the way the wall is built?

Five readings (analysis.kinds.readings.REFERENCES) of what the disk hits, every
seed's disk the same in all five:

- ``pair``: a second, independent disk, the binary studies' pair, at v_n;
- ``image``: the disk's own image (``partner image``: the disk turned by 180
  degrees), a symmetric collision, at v_n;
- ``image-held``: that image held, rigid and immovable, at v_n / 2;
- ``surface``: a wall built like a disk's surface (``partner surface``: a held
  ring of radius 20 R at the disk's spacing and roughness, the contact acting
  both ways), at v_n / 2;
- ``wall``: the default wall (the clamped beam, one-sided contact), at v_n / 2.

The one-body references run at half the pair's relative speed (``plan``): in
the centre of mass each disk of a pair brings the contact v_n / 2. The
two-body compliant model maps the pair onto one disk against a rigid flat
at v_n / 2 (docs/model.md, "Two disks"); ``image`` against ``surface`` tests
it, ``surface`` against ``wall`` measures the wall's construction.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.stats import norm

from ..binary_comparison import first_touch_incidence, verdict
from ..impact.failures import impact_state
from ..normal_check import robustness
from ..statistics.estimates import fit, lattice_constants, study_estimates, way
from ..statistics.fits import means
from ..statistics.seeds import seed_bootstrap, seed_tables
from .readings import ONE_BODY, REFERENCES, Setup

COLUMNS = (
    "reading",
    "reference",
    "study_lattice",
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "vn",
    "vn_in_c",
    "target",
    "target_held",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "side_clearance",
    "energy_drift",
    "drift_exceeded",
    "disk_inertia_ratio",
    "target_inertia_ratio",
    "n_disk_points",
    "n_target_points",
    "nu",
    "e_first_touch",
    "beta_first_touch",
    "cot_gamma_first_touch",
    "e_impulse",
    "beta_impulse",
    "cot_gamma_impulse",
    "impulse_tilt_deg",
    "aim_incidence_deg",
    "aim_turn_deg",
    "steps",
    "dt",
    "error",
)
ORDER = tuple(REFERENCES)  # pair, image, image-held, surface, wall


def label(choice: dict) -> str:
    """A combination's reading: its reference's name."""
    return str(choice["reference"])


def row_fields(choice: dict, setup: Setup) -> dict:
    """Each row's reference (``pair_speed`` derives the pair's speed from it)."""
    return {"reference": choice["reference"]}


def plan(choice: dict, study):
    """The one-body references at half the pair's speed (each speed of the
    study's axis, or its v_n)."""
    if choice["reference"] not in ONE_BODY:
        return study
    return replace(study, vn=study.vn / 2.0, speeds=tuple(speed / 2.0 for speed in study.speeds))


RESAMPLES = 200
CHI2_LIMIT = 2.0  # a fit with chi2/dof above this fails: its systematic error counts
QUANTITIES = ("e_first", "contact_time", "mu")
# The comparisons: (question, reference, reference)
QUESTIONS = (
    ("the two-body mapping", "image", "surface"),
    ("the wall's construction", "surface", "wall"),
    ("the partner's own disk", "pair", "image"),
    ("the partner's compliance, its shape kept", "image", "image-held"),
)
VERDICTS = ("same", "undecided", "differs", "withheld")


def finished(rows: list[dict]) -> list[dict]:
    return [r for r in rows if not r.get("error") and r.get("e") not in (None, "")]


def pair_speed(row: dict) -> float:
    """The pair's relative speed a row stands beside (twice a one-body run's)."""
    factor = 2.0 if row["reference"] in ONE_BODY else 1.0
    return round(factor * float(row["vn"]), 9)


def group_key(reference: str, speed: float) -> str:
    return f"{reference}@{speed:g}"


def grouped(rows: list[dict]) -> dict[str, list[dict]]:
    """Rows by reference and pair speed, each marked as its own study lattice."""
    out: dict[str, list[dict]] = {}
    for row in rows:
        key = group_key(row["reference"], pair_speed(row))
        out.setdefault(key, []).append({**row, "study_lattice": key})
    return out


def joint_numbers(groups: dict[str, list[dict]], resamples: int) -> dict:
    """e and the contact time at the first angle (the nearest normal
    incidence) and Walton's mu (the measured-way fit, as ``walton``'s), per
    group, and the differences QUESTIONS asks, with joint seed errors: a
    difference's error keeps the correlation of the two groups' seeds."""
    rows = [row for group in groups.values() for row in group]
    tables = seed_tables(rows, ("cot_gamma", "e", "beta", "contact_time"))
    speeds = sorted({float(k.split("@")[1]) for k in groups})
    fitted = {}
    for key in tables:
        nu, _, K = lattice_constants(rows, key)
        fitted[key] = way("walton", "measured", K, nu)

    def statistic(ts) -> dict:
        out = {}
        for key, table in ts.items():
            out[("e_first", key)] = float(table.mean("e")[0])
            out[("contact_time", key)] = float(table.mean("contact_time")[0])
            out[("mu", key)] = float(fit("walton", means(table), fitted[key])[0])
        for speed in speeds:
            for _, a, b in QUESTIONS:
                ka, kb = group_key(a, speed), group_key(b, speed)
                if ka in ts and kb in ts:
                    for q in QUANTITIES:
                        out[(f"d_{q}", ka, kb)] = out[(q, ka)] - out[(q, kb)]
        return out

    return {"value": statistic(tables), "error": seed_bootstrap(tables, statistic, resamples)}


def walton(group: list[dict], resamples: int) -> dict:
    """Walton's measured-way fit of one group: mu, its seed error, chi2/dof,
    and the systematic error of the fitting choices."""
    fits, _ = study_estimates(group, resamples=resamples, compliant=False)
    entry = next(iter(fits["lattices"].values()))
    fit = entry["walton"]["measured"]
    systematic = entry["walton"]["systematic"]["mu"]
    failing = fit["chi2"] > CHI2_LIMIT
    error = float(np.hypot(fit["mu_sd"], systematic)) if failing else float(fit["mu_sd"])
    return {
        "mu": fit["mu"],
        "sd": fit["mu_sd"],
        "chi2": fit["chi2"],
        "systematic": systematic,
        "error": error,
        "failing": failing,
        "mu_branch": entry["measures"]["mu_branch"],
    }


def first_robust(checks: dict[str, dict | None], key: str) -> tuple[bool, float]:
    """Whether the first angle's e of a group is robust to the normal, and
    by how much its normals differ."""
    check = checks.get(key)
    if not check:
        return False, float("nan")
    entry = next(iter(check["lattices"].values()))
    return bool(entry["e_robust"][0]), float(entry["e_spread"][0])


def numbers(rows: list[dict], resamples: int = RESAMPLES) -> dict:
    """Every number of the references' page.

    Returns
    -------
    dict
        ``speeds`` (the pair's), ``present`` (references with rows, in
        ORDER), ``angles``, ``impacts``/``failed``/``stuck``; ``value`` and
        ``error`` (``joint_numbers``), ``fits`` (``walton``) and ``checks``
        (the normals' check) per group; ``comparisons``: per speed and
        question, each quantity's difference, error, verdict and whether
        both e are robust to the normal; ``counts``: the verdicts per
        question and quantity over the speeds; ``largest``: per quantity,
        its largest difference with the look-elsewhere effect
        (``largest_difference``); ``aim``: how the aim hit (``aim_numbers``).
    """
    done = finished(rows)
    groups = grouped(done)
    speeds = sorted({float(k.split("@")[1]) for k in groups})
    joint = joint_numbers(groups, resamples)
    value, error = joint["value"], joint["error"]
    fits = {key: walton(group, resamples) for key, group in groups.items()}
    checks = {key: robustness(group, resamples) for key, group in groups.items()}
    comparisons = []
    for s in speeds:
        for question, a, b in QUESTIONS:
            ka, kb = group_key(a, s), group_key(b, s)
            if ka not in groups or kb not in groups:
                continue
            robust = first_robust(checks, ka)[0] and first_robust(checks, kb)[0]
            for q in QUANTITIES:
                d, err = value[(f"d_{q}", ka, kb)], error[(f"d_{q}", ka, kb)]
                if q == "mu":  # the joint seed error, and a failing fit's systematic one
                    failing = [fits[k]["systematic"] for k in (ka, kb) if fits[k]["failing"]]
                    err = float(np.sqrt(err**2 + sum(x**2 for x in failing)))
                word = verdict(d, err)
                if q == "e_first" and not robust:
                    word = "withheld"
                comparisons.append(
                    {"speed": s, "question": question, "a": a, "b": b, "quantity": q,
                     "difference": d, "error": err, "verdict": word}
                )  # fmt: skip
    counts = {
        question: {
            q: {
                word: sum(
                    c["verdict"] == word
                    for c in comparisons
                    if c["question"] == question and c["quantity"] == q
                )
                for word in VERDICTS
            }
            for q in QUANTITIES
        }
        for question, _, _ in QUESTIONS
    }
    states = [impact_state(r["error"]) for r in rows if r.get("error")]
    return {
        "aim": aim_numbers(groups),
        "largest": {q: largest_difference(comparisons, q) for q in QUANTITIES},
        "speeds": speeds,
        "present": [r for r in ORDER if any(group_key(r, s) in groups for s in speeds)],
        "angles": sorted({float(r["gamma_deg"]) for r in done}),
        "impacts": len(rows),
        "failed": states.count("failed"),
        "stuck": states.count("stuck"),
        "value": value,
        "error": error,
        "fits": fits,
        "checks": checks,
        "comparisons": comparisons,
        "counts": counts,
    }


def aim_numbers(groups: dict[str, list[dict]]) -> dict | None:
    """How the aim by the contact hit, over the groups of two disks (the wall
    is placed, not aimed): the largest relative departure of a group's mean
    incidence at the first contact from the nominal angle, over how many
    means, and the impacts turned or past a jump (``first_touch_incidence``);
    None for rows made before the aim recorded its turn."""
    aimed = [r for key, group in groups.items() if not key.startswith("wall@") for r in group]
    if not aimed or any(r.get("aim_turn_deg") in (None, "") for r in aimed):
        return None
    touch = first_touch_incidence(aimed) or {}
    return {
        "worst": max(abs(x) for t in touch.values() for x in t["relative"]),
        "means": sum(len(t["relative"]) for t in touch.values()),
        "impacts": sum(sum(t["impacts"]) for t in touch.values()),
        "turned": sum(sum(t["turned"]) for t in touch.values()),
        "no_line": sum(sum(t["no_line"]) for t in touch.values()),
    }


def largest_difference(comparisons: list[dict], quantity: str) -> dict | None:
    """The largest of one quantity's differences in errors, judged as the
    largest of all its comparisons (the look-elsewhere effect): its two-sided
    normal p, and the chance that the largest of n reaches it with no
    difference anywhere, 1 - (1 - p)^n (Sidak's; for comparisons that
    correlate, as these share seeds and references, it overstates that
    chance, so it errs towards 'by chance'). None without a comparison."""
    judged = [
        c
        for c in comparisons
        if c["quantity"] == quantity and c["verdict"] != "withheld" and c["error"] > 0
    ]
    if not judged:
        return None
    top = max(judged, key=lambda c: abs(c["difference"]) / c["error"])
    z = abs(top["difference"]) / top["error"]
    p_global = float(-np.expm1(len(judged) * np.log1p(-2.0 * norm.sf(z))))
    return {
        "z": float(z),
        "count": len(judged),
        "p_global": p_global,
        "z_global": float(norm.isf(p_global / 2.0)),
        "speed": top["speed"],
        "question": top["question"],
        "a": top["a"],
        "b": top["b"],
    }
