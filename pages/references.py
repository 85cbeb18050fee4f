"""The references study's page (analysis.references' numbers): e near normal
incidence, the contact time and Walton's mu of each reference against the
speed, the questions' differences, e per angle; its figure. The prose:
pages/templates/references.md.j2."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.normal_check import robustness
from analysis.readings import Setup
from analysis.references import (
    CHI2_LIMIT,
    ONE_BODY,
    ORDER,
    RESAMPLES,
    comparisons,
    findings,
    finished,
    group_key,
    grouped,
    joint_numbers,
    walton,
)

from .render import render
from .text import markdown_table

TITLE = "Two disks against the symmetric references"
FIGURE = "references_speed.png"


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


def draw(numbers: dict, speeds: list[float], figures: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    value, error = numbers["value"], numbers["error"]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for reference in ORDER:
        keys = [group_key(reference, s) for s in speeds]
        shown = [(s, k) for s, k in zip(speeds, keys, strict=True) if ("e_normal", k) in value]
        if not shown:
            continue
        x = [s for s, _ in shown]
        for ax, q in zip(axes, ("e_normal", "contact_time"), strict=True):
            ax.errorbar(
                x,
                [value[(q, k)] for _, k in shown],
                [error[(q, k)] for _, k in shown],
                marker="o",
                capsize=2,
                label=reference,
            )
    for ax, label in zip(
        axes, ("e, cot gamma >= 1", "contact time, R/c, first angle"), strict=True
    ):
        ax.set_xscale("log")
        ax.set_xlabel("the pair's relative speed v_n, c")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(figures / FIGURE, dpi=110)
    plt.close(fig)


def page(rows: list[dict], setup: Setup, figures) -> str:
    done = finished(rows)
    groups = grouped(done)
    speeds = sorted({float(k.split("@")[1]) for k in groups})
    numbers = joint_numbers(groups, RESAMPLES)
    value, error = numbers["value"], numbers["error"]
    fits = {key: walton(group, RESAMPLES) for key, group in groups.items()}
    checks = {key: robustness(group, RESAMPLES) for key, group in groups.items()}
    present = [r for r in ORDER if any(group_key(r, s) in groups for s in speeds)]

    def cell(q: str, key: str) -> str:
        return plus_minus(value[(q, key)], error[(q, key)], 3 if q == "e_normal" else 2)

    speed_rows = {
        q: [
            [
                f"{s:g}",
                *(cell(q, group_key(r, s)) if group_key(r, s) in groups else "-" for r in present),
            ]
            for s in speeds
        ]
        for q in ("e_normal", "contact_time")
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
    compared = comparisons(value, error, fits, groups, speeds)
    comparison_rows = [
        [
            f"{c['speed']:g}",
            c["question"],
            f"{c['a']} - {c['b']}",
            c["of"],
            plus_minus(c["value"], c["error"], 2 if c["of"] == "contact_time" else 3),
            c["verdict"],
        ]
        for c in compared
    ]
    draw(numbers, speeds, Path(figures))
    return render(
        "references.md.j2",
        study=setup.study,
        impacts=len(rows),
        failed=len(rows) - len(done),
        resamples=RESAMPLES,
        chi2_limit=CHI2_LIMIT,
        references=present,
        one_body=ONE_BODY,
        speeds=[f"{s:g}" for s in speeds],
        figures=setup.figures,
        figure=FIGURE,
        e_table=markdown_table(["v_n, c", *present], speed_rows["e_normal"]),
        time_table=markdown_table(["v_n, c", *present], speed_rows["contact_time"]),
        mu_table=markdown_table(["v_n, c", *present], mu_rows),
        comparison_table=markdown_table(
            ["v_n, c", "question", "difference", "of", "value +- error", "verdict"],
            comparison_rows,
        ),
        findings=findings(compared),
        angle_tables=[(f"{s:g}", angle_table(checks, s)) for s in speeds],
    )
