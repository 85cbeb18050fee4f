"""The scene readings' page (analysis.kinds.scene_readings's numbers): the
readings side by side, their ranking, the figure of e and beta per wall."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np

from analysis.kinds.readings import (
    N_WALL,
    WALL_FIXED,
    WALL_KA,
    Setup,
    distance_from_text,
    wall_label,
)
from analysis.kinds.scene_readings import (
    BANDS,
    BETA0_NEAR,
    BETA0_PAPER,
    E_NEAR,
    E_PAPER,
    ENDS_NEAR,
    label,
    rank_summaries,
    standard_errors,
    summaries_of,
    summarise,
)
from analysis.table import mean_rows
from ground.gate import write_figure

from .render import render
from .text import markdown_table

TITLE = "The readings of the scene"
FIGURE = "scene_readings.png"


def fmt(pair) -> str:
    value, se = pair
    return "-" if not np.isfinite(value) else f"{value:.3f} +- {se:.3f}"


def table_row(reading: str, lattice: str, s: dict) -> list[str]:
    walton = s.get("walton")
    causes = "; ".join(f"{n} {c}" for c, n in sorted(s["causes"].items())) or "-"
    if "total_miss" not in s:
        return [reading, lattice, str(s["impacts"]), str(s["failed"])] + ["-"] * 13 + [causes]
    return [
        reading,
        lattice,
        str(s["impacts"]),
        str(s["failed"]),
        *(fmt(s[f"e {name}"]) for name, _, _ in BANDS),
        f"{walton['mu']:.3f} +- {walton['mu_sd']:.3f}" if walton else "-",
        f"{walton['beta0']:.3f} +- {walton['beta0_sd']:.3f}" if walton else "-",
        f"{walton['chi2']:.1f}" if walton else "-",
        f"{s['contact_time']:.1f}",
        f"{s['touches']:g}",
        f"{100 * s['ends_share']:.0f} %",
        f"{s['seconds']:.2f}",
        f"{s['steps']:.0f}",
        f"{s['e_miss']:.3f}",
        f"{s['beta0_miss']:.3f}",
        f"{s['facts_met']}",
        f"{s['total_miss']:.2f} +- {s['total_miss_se']:.2f}",
        causes,
    ]


def draw(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(N_WALL), 2, figsize=(11, 3.2 * len(N_WALL)), sharex=True)
    colours = dict(zip(WALL_KA, ("tab:blue", "tab:orange", "tab:green")))
    styles = dict(zip(WALL_FIXED, ("-", "--")))
    for i, n_wall in enumerate(N_WALL):
        for wall_ka, wall_fixed in itertools.product(WALL_KA, WALL_FIXED):
            name = wall_label(n_wall, wall_ka, wall_fixed)
            done = [
                r
                for r in rows
                if r["reading"] == name and r["study_lattice"] == "random" and not r.get("error")
            ]
            if not done:
                continue
            means = mean_rows(done)
            psi = [m["cot_gamma"] for m in means]
            for ax, key in zip(axes[i], ("e", "beta")):
                ax.errorbar(
                    psi,
                    [m[key] for m in means],
                    standard_errors(done, key),
                    color=colours[wall_ka],
                    ls=styles[wall_fixed],
                    marker="o",
                    ms=3,
                    label=f"ka {wall_ka if isinstance(wall_ka, str) else f'{wall_ka:g}x'}, "
                    f"{wall_fixed} held",
                )
        axes[i][0].axhline(E_PAPER, color="grey", lw=0.8)
        axes[i][1].axhline(BETA0_PAPER, color="grey", lw=0.8)
        axes[i][0].set_ylabel(f"e, wall of {n_wall}" + (" points" if n_wall != "density" else ""))
        axes[i][1].set_ylabel("beta")
    for ax in axes[-1]:
        ax.set_xscale("log")
        ax.set_xlabel("cot gamma")
    axes[0][1].legend(fontsize=7)
    fig.suptitle(
        "Random disk on every reading of the wall (grey: the paper's e = 0.8, beta0 = 0.56)"
    )
    fig.tight_layout()
    write_figure(fig, path, 110)
    plt.close(fig)


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its figure goes into ``figures``."""
    labels = [label(c) for c in setup.choices]
    summaries = summaries_of(rows, labels)
    ranking = rank_summaries(summaries)
    study, rerun = setup.study, setup.rerun
    then = rerun.get("then_lattices", ())
    header = [
        "reading (points_ka_held)",
        "disk",
        "impacts",
        "failed",
        *(f"e, cot gamma {name}" for name, _, _ in BANDS),
        "Walton mu",
        "Walton beta0",
        "chi2/dof",
        "median contact, R/c",
        "median touches",
        "near a side",
        "LAMMPS s",
        "steps",
        "e miss",
        "beta0 miss",
        "facts met",
        "total miss",
        "failures by cause",
    ]
    table = [table_row(r, "random", summaries[r]) for r in labels]
    # the readings that lattice ran on: the best of the ranking when it ran,
    # which the weights of the fits (analysis.statistics.fits.means) have moved since
    for lattice in then:
        for reading in ranking:
            these = [r for r in rows if r["reading"] == reading and r["study_lattice"] == lattice]
            if these:
                table.append(table_row(reading, lattice, summarise(these)))
    draw(rows, figures / FIGURE)
    return render(
        "scene_readings.md.j2",
        study=study,
        rerun=rerun,
        table=markdown_table(header, table),
        ranking=[
            {
                "reading": r,
                **summaries[r],
                "away": distance_from_text(r),
            }
            for r in ranking
        ],
        e_paper=E_PAPER,
        beta0_paper=BETA0_PAPER,
        e_near=E_NEAR,
        beta0_near=BETA0_NEAR,
        ends_near=ENDS_NEAR,
        figures=setup.figures,
        figure=FIGURE,
    )
