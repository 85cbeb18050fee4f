"""The references' page (analysis.kinds.references computes its numbers): its
tables' cells, its figure, and the prose of pages/templates/references.md.j2."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.kinds.readings import ONE_BODY, Setup
from analysis.kinds.references import (
    CHI2_LIMIT,
    ORDER,
    QUANTITIES,
    QUESTIONS,
    RESAMPLES,
    first_robust,
    group_key,
    numbers,
)
from ground.gate import write_figure

from .render import render
from .text import markdown_table, pm

TITLE = "Two disks against the symmetric references"
FIGURE = "references_speed.png"  # e and the contact time against the pair's speed
NAMES = {"e_first": "e", "contact_time": "the contact time", "mu": "Walton's mu"}
DIGITS = {"e_first": 3, "contact_time": 2, "mu": 3}
WITHHELD = "withheld (an e not robust to the normal)"


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
    write_figure(fig, figure, 110)
    plt.close(fig)


def body(rows: list[dict], setup: Setup, figures: Path, figure: str) -> str:
    """The page's body; its figure ``figure`` into ``figures``."""
    n = numbers(rows, RESAMPLES)
    value, error, fits, checks = n["value"], n["error"], n["fits"], n["checks"]
    speeds, present = n["speeds"], n["present"]

    def cell(q: str, key: str) -> str:
        if key not in fits:
            return "-"
        robust, spread = first_robust(checks, key)
        if q == "e_first" and not robust:
            return f"withheld (normals differ by {spread:.3f})"
        return plus_minus(value[(q, key)], error[(q, key)], DIGITS[q])

    def mu_cell(key: str) -> str:
        fit = fits.get(key)
        if fit is None:
            return "-"
        if fit["failing"]:
            return (
                f"{fit['mu']:.3f} +- {fit['sd']:.3f} +- {fit['systematic']:.3f} sys "
                f"(fails: chi2/dof {fit['chi2']:.1f}; mu on the sliding branch "
                f"{pm(fit['mu_branch']['value'])})"
            )
        return f"{fit['mu']:.3f} +- {fit['sd']:.3f} (chi2/dof {fit['chi2']:.1f})"

    def by_speed(make) -> str:
        lines = [[f"{s:g}", *(make(group_key(r, s)) for r in present)] for s in speeds]
        return markdown_table(["v_n, c", *present], lines)

    comparison_rows = [
        [
            f"{c['speed']:g}",
            c["question"],
            f"{c['a']} - {c['b']}",
            NAMES[c["quantity"]],
            plus_minus(c["difference"], c["error"], DIGITS[c["quantity"]]),
            "withheld (an e not robust to the normal)"
            if c["verdict"] == "withheld"
            else c["verdict"],
        ]
        for c in n["comparisons"]
    ]
    draw(n, speeds, Path(figures) / figure)
    return render(
        "references.md.j2",
        study=setup.study,
        angles=[f"{g:g}" for g in n["angles"]],
        impacts=n["impacts"],
        failed=n["failed"],
        stuck=n["stuck"],
        aim=n["aim"],
        resamples=RESAMPLES,
        chi2_limit=CHI2_LIMIT,
        references=present,
        one_body=ONE_BODY,
        speeds=[f"{s:g}" for s in speeds],
        figures=setup.figures,
        figure=figure,
        e_table=by_speed(lambda key: cell("e_first", key)),
        time_table=by_speed(lambda key: cell("contact_time", key)),
        mu_table=by_speed(mu_cell),
        comparison_table=markdown_table(
            ["v_n, c", "question", "difference", "of", "value +- error", "verdict"],
            comparison_rows,
        ),
        questions=QUESTIONS,
        quantities=[(q, NAMES[q]) for q in QUANTITIES],
        counts=n["counts"],
        largest=n["largest"],
        angle_tables=[(f"{s:g}", angle_table(checks, s)) for s in speeds],
    )


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its figure into ``figures``."""
    return body(rows, setup, figures, FIGURE)
