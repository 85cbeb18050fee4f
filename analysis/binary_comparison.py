"""Two disks colliding beside the same disks on the wall: a binary study's
comparison, in numbers (its page section and figures: pages.binary).

The binary study's seeds and angles are those of a wall study (the paper's,
docs/studies/results/): a seed's disk is the same in both (builder/binary.py), so
each seed gives a pair of impacts, and every error resamples whole seeds of
both studies together (analysis.statistics.seeds).
"""

from __future__ import annotations

import numpy as np

from builder.aim import AIM_TOLERANCE_DEG

from .normal_check import robustness
from .statistics.estimates import CHI2_LIMIT, lattice_constants, study_estimates
from .statistics.fits import fit_walton, means
from .statistics.seeds import SeedTable, seed_bootstrap, seed_tables

TARGETS = ("disk", "wall")
QUANTITIES = ("e", "beta", "cot_gamma", "vibration_disk", "vibration_wall")
# The claims' rule for "the same" (analysis.statistics.claims): within 2 errors the two
# agree, beyond 3 they differ, in between undecided.
SAME, DIFFERENT = 2.0, 3.0


def verdict(difference: float, error: float) -> str:
    if not (np.isfinite(difference) and np.isfinite(error)):
        return "-"
    if abs(difference) <= SAME * error:
        return "same"
    return "differs" if abs(difference) > DIFFERENT * error else "undecided"


def paired_rows(rows: list[dict], wall_rows: list[dict]) -> tuple[list[dict], list[dict]]:
    """The wall study's impacts of the binary study's lattices, seeds and
    angles, and the binary study's of the wall's: the pairs both have."""
    keys = lambda r: (r["study_lattice"], int(float(r["seed"])), float(r["gamma_deg"]))  # noqa: E731
    both = {keys(r) for r in rows} & {keys(r) for r in wall_rows}
    return [r for r in rows if keys(r) in both], [r for r in wall_rows if keys(r) in both]


def columns(table: SeedTable, keep: np.ndarray) -> SeedTable:
    """The table at the angles where ``keep`` is True."""
    return SeedTable(
        table.seeds, table.gamma_deg[keep], {k: v[:, keep] for k, v in table.values.items()}
    )


def common_range(disk: SeedTable, wall: SeedTable) -> tuple[np.ndarray, np.ndarray, list]:
    """The angles of each target whose mean measured cot gamma lies in the
    range both targets cover, and that range: two fits compared over unlike
    incidences would compare the incidences, not the targets."""
    cot_disk, cot_wall = disk.mean("cot_gamma"), wall.mean("cot_gamma")
    low = max(np.nanmin(cot_disk), np.nanmin(cot_wall))
    high = min(np.nanmax(cot_disk), np.nanmax(cot_wall))
    inside = lambda cot: (cot >= low) & (cot <= high)  # noqa: E731
    return inside(cot_disk), inside(cot_wall), [float(low), float(high)]


def in_angles(rows: list[dict], lattice: str, gammas) -> list[dict]:
    """A lattice's rows at these angles (and every other lattice's rows)."""
    chosen = {float(g) for g in gammas}
    return [r for r in rows if r["study_lattice"] != lattice or float(r["gamma_deg"]) in chosen]


def difference_systematic(disk_fit: dict, wall_fit: dict) -> float:
    """Half the range of mu (disks) - mu (wall) over the fitting choices that
    both targets were fitted with (the same choice on both)."""
    shifts = [
        a["mu"] - b["mu"]
        for a in disk_fit["variants"]
        for b in wall_fit["variants"]
        if (a["e"], a["weights"], a["angles"]) == (b["e"], b["weights"], b["angles"])
    ]
    return 0.5 * (max(shifts) - min(shifts)) if shifts else float("nan")


THIS_STUDY = "two disks (this study)"


def normal_checks(
    rows: list[dict], walls: dict[str, list[dict]], pairs: dict[str, list[dict]], resamples: int
) -> dict:
    """The normals' check (analysis.normal_check) of this study's pairs, of the
    other pair studies (smooth baselines, ...), and of each wall study's
    impacts of this study's seeds and angles."""
    checks = {THIS_STUDY: robustness(rows, resamples)}
    for name, pair in pairs.items():
        checks[f"two disks, docs/studies/{name}"] = robustness(pair, resamples)
    for name, wall in walls.items():
        checks[f"the wall, docs/studies/{name}"] = robustness(paired_rows(rows, wall)[1], resamples)
    return checks


def comparison(rows: list[dict], wall_rows: list[dict], resamples: int = 200) -> dict:
    """Per lattice and angle: e, beta, cot gamma and the vibrations of the
    binary impacts and of the wall's, their differences, each with its seed-
    bootstrap error, and the verdicts; both studies' fits over the cot gamma
    range both cover, and the difference of their measured-way Walton mu with
    its seed error (both studies resampled together) and its systematic error;
    the momenta.

    Parameters
    ----------
    rows : list of dict
        The binary study's impacts.csv rows.
    wall_rows : list of dict
        A wall study's rows of the same seeds and angles.
    resamples : int
        Seed-bootstrap resamples.

    Returns
    -------
    dict
        What fits.json keeps under ``wall_comparison`` for this wall study.
    """
    disk_rows, wall_rows = paired_rows(rows, wall_rows)
    labelled = [{**r, "study_lattice": f"{r['study_lattice']}|disk"} for r in disk_rows] + [
        {**r, "study_lattice": f"{r['study_lattice']}|wall"} for r in wall_rows
    ]
    tables = seed_tables(labelled, QUANTITIES)
    lattices = sorted({r["study_lattice"] for r in disk_rows})
    ranges = {
        lattice: common_range(tables[f"{lattice}|disk"], tables[f"{lattice}|wall"])
        for lattice in lattices
    }
    K = {
        (lattice, target): lattice_constants(chosen, lattice)[2]
        for lattice in lattices
        for target, chosen in (("disk", disk_rows), ("wall", wall_rows))
    }

    def walton_mu(table: SeedTable, keep: np.ndarray, k: float) -> float:
        return float(fit_walton(means(columns(table, keep)), k)[0])

    def statistic(ts: dict[str, SeedTable]) -> dict:
        out = {}
        for lattice in lattices:
            disk, wall = ts[f"{lattice}|disk"], ts[f"{lattice}|wall"]
            for q in QUANTITIES:
                out[f"{lattice}/{q}/disk"] = disk.mean(q)
                out[f"{lattice}/{q}/wall"] = wall.mean(q)
            for q in ("e", "beta"):
                out[f"{lattice}/{q}/difference"] = disk.mean(q) - wall.mean(q)
            keep_disk, keep_wall, _ = ranges[lattice]
            out[f"{lattice}/mu/difference"] = walton_mu(
                disk, keep_disk, K[(lattice, "disk")]
            ) - walton_mu(wall, keep_wall, K[(lattice, "wall")])
        return out

    central = statistic(tables)
    error = seed_bootstrap(tables, statistic, resamples)
    out: dict = {
        "wall_vn": sorted({float(r["vn"]) for r in wall_rows}),
        "disk_vn": sorted({float(r["vn"]) for r in disk_rows}),
        "pairs": len(disk_rows),
        "lattices": {},
    }
    for lattice in lattices:
        gammas = tables[f"{lattice}|disk"].gamma_deg
        entry = {
            "gamma_deg": gammas.tolist(),
            "cot_gamma_nominal": (1.0 / np.tan(np.radians(gammas))).tolist(),
            "impacts": tables[f"{lattice}|disk"].counts().tolist(),
        }
        for key in central:
            if key.startswith(f"{lattice}/") and key != f"{lattice}/mu/difference":
                short = key[len(lattice) + 1 :].replace("/", "_")
                entry[short] = np.asarray(central[key]).tolist()
                entry[short + "_error"] = np.asarray(error[key]).tolist()
        for q in ("e", "beta"):
            entry[f"{q}_verdict"] = [
                verdict(d, s)
                for d, s in zip(entry[f"{q}_difference"], entry[f"{q}_difference_error"])
            ]
        out["lattices"][lattice] = entry
    disk_fit_rows, wall_fit_rows = disk_rows, wall_rows
    for lattice in lattices:
        keep_disk, keep_wall, _ = ranges[lattice]
        disk_fit_rows = in_angles(
            disk_fit_rows, lattice, tables[f"{lattice}|disk"].gamma_deg[keep_disk]
        )
        wall_fit_rows = in_angles(
            wall_fit_rows, lattice, tables[f"{lattice}|wall"].gamma_deg[keep_wall]
        )
    out["fits"] = {
        "disk": study_estimates(disk_fit_rows, resamples)[0]["lattices"],
        "wall": study_estimates(wall_fit_rows, resamples)[0]["lattices"],
    }
    out["mu_difference"] = {}
    for lattice in lattices:
        keep_disk, keep_wall, cot_range = ranges[lattice]
        disk_fit, wall_fit = out["fits"]["disk"][lattice], out["fits"]["wall"][lattice]
        # a chi2 that is not finite (a mean without spread) fails as well
        chi2 = [f["walton"]["measured"]["chi2"] for f in (disk_fit, wall_fit)]
        fails = any(c is None or not c <= CHI2_LIMIT for c in chi2)
        systematic = difference_systematic(disk_fit["walton"], wall_fit["walton"])
        sd = float(error[f"{lattice}/mu/difference"])
        total = float(np.hypot(sd, systematic if fails else 0.0))
        value = float(central[f"{lattice}/mu/difference"])
        out["mu_difference"][lattice] = {
            "cot_gamma_range": cot_range,
            "gamma_deg_disk": tables[f"{lattice}|disk"].gamma_deg[keep_disk].tolist(),
            "gamma_deg_wall": tables[f"{lattice}|wall"].gamma_deg[keep_wall].tolist(),
            "value": value,
            "sd": sd,
            "systematic": systematic,
            "fits_fail": fails,
            "error": total,
            "z": abs(value) / total if total > 0 else float("nan"),
            "verdict": verdict(value, total),
        }
    for column, key in (("momentum_change", "momentum"), ("angular_momentum_change", "angular")):
        out[f"largest_{key}_change"] = max(float(r[column]) for r in disk_rows)
    out["first_touch"] = first_touch_incidence(disk_rows)
    return out


def first_touch_incidence(rows: list[dict]) -> dict | None:
    """Per lattice and nominal angle, the mean incidence at the first touch
    (degrees, from each impact's cot gamma there, which the analysis reads
    from the rows), its relative departure from the nominal angle and the
    largest departure of one impact: how well the aim by the contact hit."""
    if not all(r.get("cot_gamma_first_touch") not in (None, "") for r in rows):
        return None  # tables from before the normals
    out = {}
    for lattice in sorted({r["study_lattice"] for r in rows}):
        by_angle: dict[float, list[float]] = {}
        missed: dict[float, int] = {}
        turns: dict[float, int] = {}
        for r in rows:
            if r["study_lattice"] == lattice:
                gamma = float(r["gamma_deg"])
                angle = np.degrees(np.arctan2(1.0, float(r["cot_gamma_first_touch"])))
                by_angle.setdefault(gamma, []).append(float(angle))
                # no line of these rough rings, turned or not, first touches
                # at gamma: the incidence jumps past it onto another asperity,
                # and the aim (builder.aim.aim_turned) took the nearest line
                aimed = r.get("aim_incidence_deg")
                jumped = aimed not in (None, "") and abs(float(aimed) - gamma) > AIM_TOLERANCE_DEG
                missed[gamma] = missed.get(gamma, 0) + int(jumped)
                # where none did unturned, the pair was turned until one did
                turn = r.get("aim_turn_deg")
                turned = turn not in (None, "") and float(turn) != 0.0
                turns[gamma] = turns.get(gamma, 0) + int(turned)
        gammas = sorted(by_angle)
        mean = [float(np.mean(by_angle[g])) for g in gammas]
        out[lattice] = {
            "gamma_deg": gammas,
            "incidence_deg": mean,
            "relative": [m / g - 1.0 for m, g in zip(mean, gammas)],
            "no_line": [missed[g] for g in gammas],
            "turned": [turns[g] for g in gammas],
            "impacts": [len(by_angle[g]) for g in gammas],
            # an impact's own departure (degrees) at worst: the rows' reading
            "largest_deg": [float(np.max(np.abs(np.subtract(by_angle[g], g)))) for g in gammas],
        }
    return out


def robust_at(check: dict | None, lattice: str, gamma: float, quantity: str) -> bool:
    """Whether the normals' check finds this angle's mean robust (True where
    there is no check: tables from before it)."""
    if not check or lattice not in check["lattices"]:
        return True
    entry = check["lattices"][lattice]
    for j, g in enumerate(entry["gamma_deg"]):
        if abs(g - gamma) < 1e-9:
            return bool(entry[f"{quantity}_robust"][j])
    return True


VERDICTS = ("same", "undecided", "differs", "withheld")


def shown(entry: dict, lattice: str, robust: dict) -> dict:
    """Which of a lattice's comparisons the page shows: per angle, e and beta
    of each target where the normals' check (``robust``: by target) finds
    them robust, a difference where both are, and its verdict ("withheld"
    where it is not shown); and how many angles have each verdict."""
    angles = []
    for j, gamma in enumerate(entry["gamma_deg"]):
        kept = {
            f"{q}_{t}": robust_at(robust.get(t), lattice, gamma, q)
            for q in ("e", "beta")
            for t in TARGETS
        }
        for q in ("e", "beta"):
            kept[f"{q}_difference"] = kept[f"{q}_disk"] and kept[f"{q}_wall"]
        verdicts = {
            q: entry[f"{q}_verdict"][j] if kept[f"{q}_difference"] else "withheld"
            for q in ("e", "beta")
        }
        angles.append({"kept": kept, "verdict": verdicts})
    counts = {
        q: {v: sum(a["verdict"][q] == v for a in angles) for v in VERDICTS} for q in ("e", "beta")
    }
    return {"angles": angles, "counts": counts}


def aim(numbers: dict) -> dict | None:
    """How far the mean incidence at the first touch is from the nominal
    angle at worst (relative), over how many angles; None for tables made
    before the aim by the contact."""
    touch = numbers.get("first_touch")
    if not touch:
        return None
    return {
        "worst": max(abs(x) for entry in touch.values() for x in entry["relative"]),
        "count": sum(len(entry["relative"]) for entry in touch.values()),
    }
