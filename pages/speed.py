"""The speed study's page and figures, from its tables (analysis.speed's
numbers; the prose: pages/templates/speed.md.j2)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis import speed
from analysis.impact.failures import outcome
from builder.materials import STUDY_LATTICES as LATTICES
from ground.gate import write_figure

from .command import made_by
from .figures import LABELS, STYLE
from .render import render


def draw(numbers: dict, folder: Path) -> list[Path]:
    """1 - e against v_n (one panel per angle) and beta0, mu against v_n."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    folder.mkdir(parents=True, exist_ok=True)
    v = np.array(numbers["speeds"])
    angles = numbers["gamma_deg"]
    fig, axes = plt.subplots(1, len(angles), figsize=(4.2 * len(angles), 4.2), squeeze=False)
    for j, (ax, gamma) in enumerate(zip(axes[0], angles, strict=True)):
        for lattice, data in numbers["lattices"].items():
            colour, marker = STYLE.get(lattice, ("k", "o"))
            y = 1.0 - np.array(data["e"])[:, j]
            err = np.array(data["e_error"])[:, j]
            shown = y > 0
            ax.errorbar(
                v[shown], y[shown], err[shown], fmt=marker, color=colour, label=LABELS[lattice]
            )
            law = data["power_law"][j]
            if law:
                x = np.geomspace(law["v_low"], law["v_high"], 50)
                ax.plot(x, law["A"] * x ** law["p"], "-", color=colour, lw=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("v_n / c")
        ax.set_title(f"gamma = {gamma:g} deg (cot {1 / np.tan(np.radians(gamma)):.3g})")
    axes[0][0].set_ylabel("1 - e")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    paths = [folder / "speed_e.png"]
    write_figure(fig, paths[0], 120)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(9.6, 4.2))
    for lattice, data in numbers["lattices"].items():
        colour, marker = STYLE.get(lattice, ("k", "o"))
        for ax, key in zip(axes, ("beta0", "mu"), strict=True):
            ax.errorbar(
                v, data[key], data[key + "_error"], fmt=marker + "-", color=colour,
                label=LABELS[lattice], lw=0.8,
            )  # fmt: skip
    axes[0].set_ylabel(f"beta at gamma = {numbers['sticking_gamma']:g} deg (beta0)")
    axes[1].set_ylabel(f"mu_eff at gamma = {numbers['sliding_gamma']:g} deg (mu)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("v_n / c")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    paths.append(folder / "speed_beta0_mu.png")
    write_figure(fig, paths[1], 120)
    plt.close(fig)
    return paths


def text(study, numbers: dict) -> str:
    """The speed page (Markdown) of a study's tables (pages.kinds.StudyTables)
    and its numbers (analysis.speed.estimates)."""
    order = speed.by_shear_over_bulk(numbers, {k: LATTICES[k] for k in numbers["lattices"]})
    by_ratio = [o["lattice"] for o in order]
    page = render(
        "speed.md.j2",
        info=study.info,
        rows=study.rows,
        numbers=numbers,
        outcome=outcome(study.failed),
        tables=study.tables,
        preset=study.preset,
        made_by=made_by(study.info, study.preset),
        resamples=study.resamples,
        power_law_points=speed.POWER_LAW_POINTS,
        power_law_chi2=speed.POWER_LAW_CHI2,
        beyond=speed.BEYOND,
        order=order,
        # the trend in the study's order of lattices, the pairs in G / B's
        trend=speed.trend(numbers, [k for k in numbers["lattices"] if k in by_ratio]),
        counts=speed.order_counts(numbers, by_ratio),
        by_speed=speed.outcomes(study.rows, study.failed, numbers["speeds"]),
        figures=study.shown_figures,
        near=speed.near_side_counts(study.rows),
    )
    return page.rstrip("\n") + "\n"
