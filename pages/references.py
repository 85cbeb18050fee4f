"""The numbers of the references' page (analysis.references) and its figure;
the prose is analysis/templates/references.md.j2.

Every group is one reference at one of the pair's relative speeds v_n (the
one-body references ran at v_n / 2). Errors resample whole seeds of all the
groups together (a seed's disk is the same in all of them), so that a
difference between two references has the error of the difference, with the
disks' own scatter shared by both taken out. Walton's mu is fitted per group
(analysis.estimates.study_estimates, its own seed bootstrap); a difference
of two mu combines their errors (and the systematic ones where a fit's
chi2/dof exceeds 2) in quadrature.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.binary_comparison import verdict
from analysis.estimates import study_estimates
from analysis.failures import impact_state
from analysis.normal_check import robustness
from analysis.readings import ONE_BODY, REFERENCES, Setup
from analysis.seeds import seed_bootstrap, seed_tables

from .render import render
from .text import markdown_table

TITLE = "Two disks against the symmetric references"
FIGURE = "references_speed.png"  # e and the contact time against the pair's speed
ORDER = tuple(REFERENCES)  # pair, image, image-held, surface, wall
RESAMPLES = 200
CHI2_LIMIT = 2.0
NAMES = {"e_first": "e", "contact_time": "the contact time", "mu": "Walton's mu"}
# The comparisons: (question, reference, reference)
QUESTIONS = (
    ("the two-body mapping", "image", "surface"),
    ("the wall's construction", "surface", "wall"),
    ("the partner's own disk", "pair", "image"),
    ("the partner's compliance, its shape kept", "image", "image-held"),
)


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
    incidence), per group, and the differences QUESTIONS asks, with joint
    seed errors."""
    rows = [row for group in groups.values() for row in group]
    tables = seed_tables(rows, ("e", "beta", "contact_time"))
    speeds = sorted({float(k.split("@")[1]) for k in groups})

    def statistic(ts) -> dict:
        out = {}
        for key, table in ts.items():
            out[("e_first", key)] = float(table.mean("e")[0])
            out[("contact_time", key)] = float(table.mean("contact_time")[0])
        for speed in speeds:
            for _, a, b in QUESTIONS:
                ka, kb = group_key(a, speed), group_key(b, speed)
                if ka in ts and kb in ts:
                    for q in ("e_first", "contact_time"):
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
        "mu_eff_top": entry["measures"]["mu_eff_top"],
    }


def plus_minus(value: float, error: float, digits: int = 3) -> str:
    if not np.isfinite(value):
        return "-"
    return f"{value:.{digits}f} +- {error:.{digits}f}"


def angle_table(checks: dict[str, dict | None], speed: float) -> str:
    """e per angle and reference at one speed: robust to the normal, or withheld."""
    present = [r for r in ORDER if checks.get(group_key(r, speed))]
    if not present:
        return ""
    first = next(iter(checks[group_key(present[0], speed)]["lattices"].values()))
    header = ["gamma, deg", *present]
    lines = []
    for j, gamma in enumerate(first["gamma_deg"]):
        cells = [f"{gamma:g}"]
        for reference in present:
            check = checks[group_key(reference, speed)]
            entry = next(iter(check["lattices"].values()))
            headline = "apse" if "apse" in check["normals"] else "fixed"
            value, error = entry[f"e_{headline}"][j], entry[f"e_{headline}_error"][j]
            if entry["e_robust"][j]:
                cells.append(plus_minus(value, error))
            else:
                cells.append(f"withheld (normals differ by {entry['e_spread'][j]:.3f})")
        lines.append(cells)
    return markdown_table(header, lines)


def draw(numbers: dict, speeds: list[float], figure: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    value, error = numbers["value"], numbers["error"]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for reference in ORDER:
        keys = [group_key(reference, s) for s in speeds]
        shown = [(s, k) for s, k in zip(speeds, keys, strict=True) if ("e_first", k) in value]
        if not shown:
            continue
        x = [s for s, _ in shown]
        for ax, q in zip(axes, ("e_first", "contact_time"), strict=True):
            ax.errorbar(
                x,
                [value[(q, k)] for _, k in shown],
                [error[(q, k)] for _, k in shown],
                marker="o",
                capsize=2,
                label=reference,
            )
    for ax, label in zip(
        axes, ("e at the first angle", "contact time, R/c, first angle"), strict=True
    ):
        ax.set_xscale("log")
        ax.set_xlabel("the pair's relative speed v_n, c")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(figure, dpi=110)
    plt.close(fig)


def first_robust(checks: dict[str, dict | None], key: str) -> tuple[bool, float]:
    """Whether the first angle's e of a group is robust to the normal, and
    by how much its normals differ."""
    check = checks.get(key)
    if not check:
        return False, float("nan")
    entry = next(iter(check["lattices"].values()))
    return bool(entry["e_robust"][0]), float(entry["e_spread"][0])


def body(rows: list[dict], setup: Setup, figures: Path, figure: str) -> str:
    """The page's body; its figure ``figure`` into ``figures``."""
    done = finished(rows)
    groups = grouped(done)
    speeds = sorted({float(k.split("@")[1]) for k in groups})
    numbers = joint_numbers(groups, RESAMPLES)
    value, error = numbers["value"], numbers["error"]
    fits = {key: walton(group, RESAMPLES) for key, group in groups.items()}
    checks = {key: robustness(group, RESAMPLES) for key, group in groups.items()}
    present = [r for r in ORDER if any(group_key(r, s) in groups for s in speeds)]

    def cell(q: str, key: str) -> str:
        robust, spread = first_robust(checks, key)
        if q == "e_first" and not robust:
            return f"withheld (normals differ by {spread:.3f})"
        return plus_minus(value[(q, key)], error[(q, key)], 3 if q == "e_first" else 2)

    speed_rows = {
        q: [
            [
                f"{s:g}",
                *(cell(q, group_key(r, s)) if group_key(r, s) in groups else "-" for r in present),
            ]
            for s in speeds
        ]
        for q in ("e_first", "contact_time")
    }
    mu_rows = []
    for s in speeds:
        cells = [f"{s:g}"]
        for r in present:
            fit = fits.get(group_key(r, s))
            if fit is None:
                cells.append("-")
            elif fit["failing"]:
                cells.append(
                    f"{fit['mu']:.3f} +- {fit['sd']:.3f} +- {fit['systematic']:.3f} sys "
                    f"(fails: chi2/dof {fit['chi2']:.1f}; mu_eff top "
                    f"{fit['mu_eff_top']['value']:.3f})"
                )
            else:
                cells.append(f"{fit['mu']:.3f} +- {fit['sd']:.3f} (chi2/dof {fit['chi2']:.1f})")
        mu_rows.append(cells)
    comparison_rows = []
    for s in speeds:
        for question, a, b in QUESTIONS:
            ka, kb = group_key(a, s), group_key(b, s)
            if ka not in groups or kb not in groups:
                continue
            for q, digits in (("e_first", 3), ("contact_time", 2)):
                d, err = value[(f"d_{q}", ka, kb)], error[(f"d_{q}", ka, kb)]
                word = verdict(d, err)
                robust = first_robust(checks, ka)[0] and first_robust(checks, kb)[0]
                if q == "e_first" and not robust:
                    word = "withheld (an e not robust to the normal)"
                said = plus_minus(d, err, digits)
                comparison_rows.append([f"{s:g}", question, f"{a} - {b}", NAMES[q], said, word])
            d_mu = fits[ka]["mu"] - fits[kb]["mu"]
            e_mu = float(np.hypot(fits[ka]["error"], fits[kb]["error"]))
            said, word = plus_minus(d_mu, e_mu), verdict(d_mu, e_mu)
            comparison_rows.append([f"{s:g}", question, f"{a} - {b}", NAMES["mu"], said, word])
    draw(numbers, speeds, Path(figures) / figure)
    findings = []
    for question, a, b in QUESTIONS:
        said = []
        for q in NAMES.values():
            verdicts = [r[5] for r in comparison_rows if r[1] == question and r[3] == q]
            if verdicts:
                counts = {w: verdicts.count(w) for w in ("same", "undecided", "differs")}
                withheld = len(verdicts) - sum(counts.values())
                said.append(
                    f"{q}: the same at {counts['same']}, undecided at {counts['undecided']}, "
                    f"differs at {counts['differs']}"
                    + (f", withheld at {withheld}" if withheld else "")
                    + f" of {len(verdicts)} speeds"
                )
        if said:
            findings.append(f"**{question}** ({a} against {b}): " + "; ".join(said))
    return render(
        "references.md.j2",
        study=setup.study,
        angles=[f"{g:g}" for g in sorted({float(r["gamma_deg"]) for r in done})],
        impacts=len(rows),
        failed=sum(impact_state(r["error"]) == "failed" for r in rows if r.get("error")),
        stuck=sum(impact_state(r["error"]) == "stuck" for r in rows if r.get("error")),
        resamples=RESAMPLES,
        chi2_limit=CHI2_LIMIT,
        references=present,
        one_body=ONE_BODY,
        speeds=[f"{s:g}" for s in speeds],
        figures=setup.figures,
        figure=figure,
        e_table=markdown_table(["v_n, c", *present], speed_rows["e_first"]),
        time_table=markdown_table(["v_n, c", *present], speed_rows["contact_time"]),
        mu_table=markdown_table(["v_n, c", *present], mu_rows),
        comparison_table=markdown_table(
            ["v_n, c", "question", "difference", "of", "value +- error", "verdict"],
            comparison_rows,
        ),
        findings=findings,
        angle_tables=[(f"{s:g}", angle_table(checks, s)) for s in speeds],
    )


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its figure into ``figures``."""
    return body(rows, setup, figures, FIGURE)
