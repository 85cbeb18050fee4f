"""Two disks colliding beside the same disks on the wall: a binary study's
comparison, its figures and its page section (analysis.report's
``wall_comparison``).

The binary study's seeds and angles are those of a wall study (the paper's,
docs/results/): a seed's disk is the same in both (builder/binary.py), so
each seed gives a pair of impacts, and every error resamples whole seeds of
both studies together (analysis.seeds).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .estimates import CHI2_LIMIT, lattice_constants, study_estimates
from .fits import fit_walton, means
from .normal_check import robustness
from .page import pm
from .seeds import SeedTable, seed_bootstrap, seed_tables

TARGETS = ("disk", "wall")
QUANTITIES = ("e", "beta", "cot_gamma", "vibration_disk", "vibration_wall")
# The claims' rule for "the same" (analysis.claims): within 2 errors the two
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
        checks[f"two disks, docs/{name}"] = robustness(pair, resamples)
    for name, wall in walls.items():
        checks[f"the wall, docs/{name}"] = robustness(paired_rows(rows, wall)[1], resamples)
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


# The aim's own tolerance is 5e-11 rad and placing the disk on the binary
# grid moves the incidence by at most 1e-5 degrees; an aimed incidence
# further from the nominal one than this is the nearest line past a jump.
AIM_TOLERANCE_DEG = 1e-3


def first_touch_incidence(rows: list[dict]) -> dict | None:
    """Per lattice and nominal angle, the mean incidence at the first touch
    (degrees, from each impact's cot gamma there) and its relative
    departure from the nominal angle: how well the aim by the contact hit."""
    if not all(r.get("cot_gamma_first_touch") not in (None, "") for r in rows):
        return None  # tables from before the normals
    out = {}
    for lattice in sorted({r["study_lattice"] for r in rows}):
        by_angle: dict[float, list[float]] = {}
        missed: dict[float, int] = {}
        for r in rows:
            if r["study_lattice"] == lattice:
                gamma = float(r["gamma_deg"])
                angle = np.degrees(np.arctan2(1.0, float(r["cot_gamma_first_touch"])))
                by_angle.setdefault(gamma, []).append(float(angle))
                # no line of these rough rings first touches at gamma: the
                # incidence jumps past it onto another asperity, and the aim
                # (builder.binary.aim) took the nearest line
                aimed = r.get("aim_incidence_deg")
                jumped = aimed not in (None, "") and abs(float(aimed) - gamma) > AIM_TOLERANCE_DEG
                missed[gamma] = missed.get(gamma, 0) + int(jumped)
        gammas = sorted(by_angle)
        mean = [float(np.mean(by_angle[g])) for g in gammas]
        out[lattice] = {
            "gamma_deg": gammas,
            "incidence_deg": mean,
            "relative": [m / g - 1.0 for m, g in zip(mean, gammas)],
            "no_line": [missed[g] for g in gammas],
            "impacts": [len(by_angle[g]) for g in gammas],
        }
    return out


def draw(numbers: dict, folder: Path | str, name: str) -> None:
    """e and beta against cot gamma, two disks (filled) beside the wall study
    ``name`` (open): binary_e_<name>.png, binary_beta_<name>.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for q, label in (("e", "e"), ("beta", "beta")):
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        ax.set_xscale("log")
        ax.set_xlabel("cot gamma (mean of the measured)")
        ax.set_ylabel(label)
        for colour, (lattice, entry) in zip(("C0", "C1", "C2", "C3"), numbers["lattices"].items()):
            for target, face in (("disk", colour), ("wall", "none")):
                x = np.asarray(entry[f"cot_gamma_{target}"])
                keep = x > 0
                ax.errorbar(
                    x[keep],
                    np.asarray(entry[f"{q}_{target}"])[keep],
                    yerr=np.asarray(entry[f"{q}_{target}_error"])[keep],
                    fmt="o" if target == "disk" else "s",
                    color=colour,
                    mfc=face,
                    capsize=2,
                    label=f"{lattice}, on {'a disk' if target == 'disk' else 'the wall'}",
                )
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(folder / f"binary_{q}_{name}.png", dpi=110)
        plt.close(fig)


def with_systematic(fit: dict, theory: str, parameter: str) -> str:
    """A measured-way parameter +- its seed error, then +- its systematic
    error where the fit's chi2/dof is above the limit."""
    way = fit[theory]["measured"]
    cell = pm(way.get(parameter), way.get(f"{parameter}_sd"))
    systematic = fit[theory].get("systematic", {}).get(parameter)
    # a chi2 that is not finite (None in fits.json: a mean without spread) fails too
    fails = way["chi2"] is None or way["chi2"] > CHI2_LIMIT
    if cell != "-" and fails and systematic is not None:
        cell += f" +- {systematic:.3f}"
    return cell


def fit_rows(fits: dict) -> list[str]:
    """Walton's and the compliant fits and the model-free measures, both targets."""
    lines = [
        "| lattice | hits | angles | Walton mu | Walton beta0 | chi2/dof | compliant mu | "
        "chi2/dof | e near normal | beta at cot gamma >= 4 | mu_eff on the sliding branch |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for lattice in fits["disk"]:
        for target in TARGETS:
            f = fits[target][lattice]
            walton, compliant = f["walton"]["measured"], f.get("compliant", {}).get("measured", {})
            m = f["measures"]
            compliant_cells = (
                f"{with_systematic(f, 'compliant', 'mu')} | {pm(compliant['chi2'], digits=1)}"
                if compliant
                else "- | -"
            )
            lines.append(
                f"| {lattice} | {'a disk' if target == 'disk' else 'the wall'} | {f['angles']} | "
                f"{with_systematic(f, 'walton', 'mu')} | "
                f"{with_systematic(f, 'walton', 'beta0')} | {pm(walton['chi2'], digits=1)} | "
                f"{compliant_cells} | "
                f"{pm(m['e_normal']['value'], m['e_normal']['sd'])} | "
                f"{pm(m['beta_normal']['value'], m['beta_normal']['sd'])} | "
                f"{pm(m['mu_eff_top']['value'], m['mu_eff_top']['sd'])} |"
            )
    return lines


def aim_sentence(numbers: dict) -> str:
    """How far the mean incidence at first touch is from the nominal angle."""
    touch = numbers.get("first_touch")
    if not touch:
        return (
            "the nominal angle set the first touch of rigid circles of radius R (tables made "
            "before the aim by the contact)"
        )
    worst = max(abs(x) for entry in touch.values() for x in entry["relative"])
    count = sum(len(entry["relative"]) for entry in touch.values())
    return (
        "the disk is aimed by the contact (builder/binary.py): the mean incidence at the "
        f"first touch is within {100 * worst:.2f} % of the nominal angle at all {count} "
        "angles"
    )


def section(by_wall: dict[str, dict], figure_dir: str, checks: dict | None = None) -> list[str]:
    """The page's section: for each wall study, the comparison's tables and
    figures; e and beta withheld where the normals' check (``checks``,
    ``normal_checks``) finds them not robust."""
    by_wall = {name: numbers for name, numbers in by_wall.items() if numbers}
    if not by_wall:
        return []
    first = next(iter(by_wall.values()))
    lines = [
        "## Two disks beside the same disks on the wall",
        "",
        "Each seed's disk hits a second disk here and the wall in the wall studies below "
        "(pairs of impacts of the same seed, lattice and nominal angle). e and beta of "
        "two disks are those of the contact points' relative velocity at the line of centres "
        "where the centres come closest (docs/model.md, 'Two disks'), and cot gamma is "
        f"measured there too; {aim_sentence(first)}. The line of centres turns during the "
        "contact, so the cot gamma at the apse is not the nominal one (the figures plot the "
        "measured one; pairs are compared by nominal angle). An e or beta that the normals' "
        "check (below, 'The normal') finds not robust is withheld, with its difference. Every "
        "+- is the seed bootstrap's error (whole seeds of both studies resampled together); "
        "a difference is 'same' within 2 errors, 'differs' beyond 3.",
        "",
        "The relative normal speed of two disks is v_n; in the centre of mass each disk "
        "meets the contact at about v_n / 2, with a quarter of the kinetic energy per mass "
        "that a disk brings to the wall at v_n: on the wall at v_n / 2 it brings the wall "
        "what it brings its partner. The disks here are compared with the wall at v_n = "
        + " and at ".join(
            ", ".join(f"{v:g}" for v in numbers["wall_vn"]) + " c" for numbers in by_wall.values()
        )
        + ".",
        "",
        f"Total momentum and angular momentum: the largest change over a run, relative to the "
        f"disks' own, is {first['largest_momentum_change']:.1e} and "
        f"{first['largest_angular_change']:.1e}.",
        "",
    ]
    checks = checks or {}
    for name, numbers in by_wall.items():
        robust = {
            "disk": checks.get(THIS_STUDY),
            "wall": checks.get(f"the wall, docs/{name}"),
        }
        lines += wall_section(name, numbers, figure_dir, robust)
    return lines


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


def wall_section(
    name: str, numbers: dict, figure_dir: str, robust: dict | None = None
) -> list[str]:
    """One wall study's comparison: per lattice and angle, then the fits."""
    robust = robust or {}
    speeds = ", ".join(f"{v:g}" for v in numbers["wall_vn"])
    lines = [
        f"### On the wall at v_n = {speeds} c (`docs/{name}`)",
        "",
        f"{numbers['pairs']} pairs of impacts; two disks at v_n = "
        f"{', '.join(f'{v:g}' for v in numbers['disk_vn'])} c.",
        "",
    ]
    for lattice, entry in numbers["lattices"].items():
        lines += [
            f"#### {lattice}",
            "",
            "| gamma (nominal) | cot gamma, disks | e, disks | e, wall | difference | "
            "beta, disks | beta, wall | difference | vibration: disk, 2nd disk | "
            "vibration: disk, wall |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        verdicts = {"e": [], "beta": []}
        for j, gamma in enumerate(entry["gamma_deg"]):
            kept = {
                (q, t): robust_at(robust.get(t), lattice, gamma, q)
                for q in ("e", "beta")
                for t in ("disk", "wall")
            }

            def cell(key: str, j=j, kept=kept) -> str:
                quantity, target = key.split("_")[0], key.split("_")[-1]
                shown = (
                    kept[(quantity, "disk")] and kept[(quantity, "wall")]
                    if target == "difference"
                    else kept.get((quantity, target), True)
                )
                return pm(entry[key][j], entry[key + "_error"][j]) if shown else "withheld"

            for q in ("e", "beta"):
                both = kept[(q, "disk")] and kept[(q, "wall")]
                verdicts[q].append(entry[f"{q}_verdict"][j] if both else "withheld")
            lines.append(
                f"| {gamma:.1f} | {cell('cot_gamma_disk')} | {cell('e_disk')} | "
                f"{cell('e_wall')} | {cell('e_difference')} ({verdicts['e'][j]}) | "
                f"{cell('beta_disk')} | {cell('beta_wall')} | {cell('beta_difference')} "
                f"({verdicts['beta'][j]}) | "
                f"{entry['vibration_disk_disk'][j]:.3f}, {entry['vibration_wall_disk'][j]:.3f} | "
                f"{entry['vibration_disk_wall'][j]:.3f}, {entry['vibration_wall_wall'][j]:.3f} |"
            )
        kinds = ("same", "undecided", "differs", "withheld")
        counts = {v: verdicts["e"].count(v) for v in kinds}
        beta_counts = {v: verdicts["beta"].count(v) for v in kinds}
        lines += [
            "",
            f"e: the same at {counts['same']} angles, undecided at {counts['undecided']}, "
            f"different at {counts['differs']}, withheld at {counts['withheld']}; beta: the same "
            f"at {beta_counts['same']}, undecided at {beta_counts['undecided']}, different at "
            f"{beta_counts['differs']}, withheld at {beta_counts['withheld']}.",
            "",
        ]
    lines += [
        "Walton's law and the compliant model fitted the measured way (e per angle, K from "
        "the disks' measured inertia, each angle weighted by the standard error of its mean "
        "beta), each target over the angles whose mean measured cot gamma lies in the range "
        "both targets cover (`angles`), with the model-free measures beside them "
        f"(analysis.estimates). chi2/dof above {CHI2_LIMIT:g}: the law does not describe the "
        "data, and the parameter gets its systematic error (half its range over the eight "
        "fitting choices) after its seed error.",
        "",
        *fit_rows(numbers["fits"]),
        "",
        *mu_difference_lines(numbers.get("mu_difference", {})),
        f"![e, two disks and the wall at {speeds} c]({figure_dir}/binary_e_{name}.png)",
        "",
        f"![beta, two disks and the wall at {speeds} c]({figure_dir}/binary_beta_{name}.png)",
        "",
    ]
    return lines


def mu_difference_lines(differences: dict) -> list[str]:
    """Walton's mu of two disks less the wall's, with both errors and the verdict."""
    lines = []
    for lattice, d in differences.items():
        low, high = d["cot_gamma_range"]
        systematic = (
            f" +- {d['systematic']:.3f} (the fitting choices: the spread of the difference "
            "over the same choice on both)"
            if d["fits_fail"]
            else ""
        )
        lines += [
            f"- {lattice}: Walton's mu (the measured way), two disks less the wall, over cot "
            f"gamma {low:.3f} to {high:.3f} ({len(d['gamma_deg_disk'])} and "
            f"{len(d['gamma_deg_wall'])} angles): {pm(d['value'], d['sd'])} (seed error, both "
            f"studies resampled together){systematic}; {d['z']:.1f} combined errors: "
            f"**{d['verdict']}** (the same within {SAME:g}, differs beyond {DIFFERENT:g}).",
        ]
    return lines + ([""] if lines else [])
