"""The resolution study's page (analysis.resolution's numbers): per reading
and lattice the quantities against N, their limits and verdicts, and two
figures; the prose is pages/templates/resolution.md.j2."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.readings import Setup
from analysis.resolution import (
    AGREE,
    CHI2_LIMIT,
    EXTRAPOLATE_FROM,
    QUANTITIES,
    RESAMPLES,
    finished,
    limit_lines,
    means_by_angle,
    order,
    summaries,
)

from .render import render
from .text import markdown_table

TITLE = "The continuum limit: e, beta and friction against the disk's resolution"
FIGURE_CURVES = "resolution_curves.png"
FIGURE_TRENDS = "resolution_trends.png"


def verdict(line: dict | None, at_800: tuple[float, float] | None, finest) -> str:
    """Whether a quantity has a limit and whether the 800-point value is at it."""
    if line is None:
        return "too few resolutions to extrapolate"
    if line["chi2"] > CHI2_LIMIT:
        return (
            f"no limit established: the line in the spacing fails (chi2/dof {line['chi2']:.1f}); "
            f"it moves by {finest[1] - at_800[0]:+.3f} from 800 to {finest[0]} points"
            if at_800 and finest
            else f"no limit established (chi2/dof {line['chi2']:.1f})"
        )
    trend = abs(line["slope"]) > AGREE * line["slope_sd"]
    words = f"limit {line['limit']:.3f} +- {line['limit_sd']:.3f}" + (
        " (a significant trend in the spacing)" if trend else " (no significant trend)"
    )
    if at_800 is not None:
        gap = at_800[0] - line["limit"]
        error = np.hypot(at_800[1], line["limit_sd"])
        words += (
            f"; the 800-point value is within {AGREE:g} errors of it"
            if abs(gap) < AGREE * error
            else f"; the 800-point value is {gap:+.3f} from it ({abs(gap) / error:.1f} errors)"
        )
    return words


def pm(value: float, sd: float, digits: int = 3) -> str:
    if not np.isfinite(value):
        return "-"
    return f"{value:.{digits}f} +- {sd:.{digits}f}"


def trend_tables(summary: dict) -> tuple[list[dict], dict]:
    """Per (limit, lattice): its rows against N (markdown) and per quantity its
    extrapolation and verdict."""
    tables, verdicts = [], {}
    lines = limit_lines(summary)
    for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=order):
        ns = sorted(n for (li, la, n) in summary if (li, la) == (limit, lattice))
        header = ["N", "seeds", "impacts (failed)", "dt", "max drift", *(q for q, _ in QUANTITIES)]
        body = []
        for n in ns:
            s = summary[(limit, lattice, n)]
            cells = [str(n), str(s["seeds"]), f"{s['impacts']} ({s['failed']})", f"{s['dt']:.4g}"]
            cells.append(f"{s['drift']:.1e}" + (f" ({s['drifted']} over)" if s["drifted"] else ""))
            cells += [pm(*s[q]) if q in s else "-" for q, _ in QUANTITIES]
            body.append(cells)
        tables.append({"limit": limit, "lattice": lattice, "table": markdown_table(header, body)})
        for q, name in QUANTITIES:
            found = lines[(limit, lattice, q)]
            verdicts[(limit, lattice, q)] = {
                "name": name,
                "line": found["line"],
                "text": verdict(found["line"], found["at_800"], found["finest"]),
            }
    return tables, verdicts


def verdict_table(verdicts: dict) -> str:
    header = [
        "reading",
        "lattice",
        "quantity",
        "N -> infinity (line in h from 800 points)",
        "chi2/dof",
        "verdict",
    ]
    body = []
    for (limit, lattice, q), v in sorted(
        verdicts.items(), key=lambda kv: (order(kv[0][:2]), kv[0][2])
    ):
        line = v["line"]
        body.append(
            [
                limit,
                lattice,
                q,
                pm(line["limit"], line["limit_sd"]) if line else "-",
                f"{line['chi2']:.1f}" if line else "-",
                v["text"],
            ]
        )
    return markdown_table(header, body)


def draw_curves(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [
        (limit, lattice)
        for limit, lattice in sorted({(r["limit"], r["study_lattice"]) for r in rows}, key=order)
    ]
    fig, axes = plt.subplots(2, len(panels), figsize=(4.2 * len(panels), 7), squeeze=False)
    for column, (limit, lattice) in enumerate(panels):
        curves = means_by_angle(rows, limit, lattice)
        colours = plt.cm.viridis(np.linspace(0, 0.9, max(len(curves), 1)))
        for colour, (n, points) in zip(colours, curves.items(), strict=True):
            cot, e, e_se, beta, beta_se = (np.array(v) for v in zip(*points, strict=True))
            axes[0, column].errorbar(cot, e, e_se, color=colour, marker="o", ms=3, label=f"N {n}")
            axes[1, column].errorbar(cot, beta, beta_se, color=colour, marker="o", ms=3)
        axes[0, column].set_title(f"{limit}, {lattice}", fontsize=10)
        for row, name in ((0, "e"), (1, "beta")):
            axes[row, column].set_xscale("log")
            axes[row, column].set_ylabel(name)
            axes[row, column].set_xlabel("cot gamma")
        axes[0, column].legend(fontsize=7)
    fig.suptitle("means over seeds, error bars: standard error of the mean over seeds", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def draw_trends(summary: dict, verdicts: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shown = ("e_normal", "mu", "beta0", "mu_eff_top")
    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 3.6))
    for ax, q in zip(axes, shown, strict=True):
        for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=order):
            ns = sorted(
                n
                for (li, la, n) in summary
                if (li, la) == (limit, lattice) and q in summary[(li, la, n)]
            )
            if not ns:
                continue
            v = np.array([summary[(limit, lattice, n)][q] for n in ns])
            h = np.sqrt(800.0 / np.array(ns))
            line = ax.errorbar(h, v[:, 0], v[:, 1], marker="o", ms=3, label=f"{limit}, {lattice}")
            fit = verdicts[(limit, lattice, q)]["line"]
            if fit:
                x = np.linspace(0.0, np.sqrt(800.0 / fit["from"]), 20)
                ax.plot(x, fit["limit"] + fit["slope"] * x, ls=":", color=line[0].get_color())
        ax.set_xlabel("spacing over the 800-point disk's, sqrt(800 / N)")
        ax.set_title(q, fontsize=10)
    axes[0].legend(fontsize=6)
    fig.suptitle(
        "error bars: sd over 200 seed-bootstrap resamples; dotted: line in h from 800 points",
        fontsize=9,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its two figures go into ``figures``."""
    summary = summaries(rows)
    tables, verdicts = trend_tables(summary)
    figures = Path(figures)
    figures.mkdir(parents=True, exist_ok=True)
    draw_curves(rows, figures / FIGURE_CURVES)
    draw_trends(summary, verdicts, figures / FIGURE_TRENDS)
    study = setup.study
    return render(
        "resolution.md.j2",
        study=study,
        impacts=len(rows),
        failed=len(rows) - len(finished(rows)),
        tables=tables,
        verdicts=verdict_table(verdicts),
        figures=setup.figures,
        curves=FIGURE_CURVES,
        trends=FIGURE_TRENDS,
        resamples=RESAMPLES,
        extrapolate_from=EXTRAPOLATE_FROM,
        agree=AGREE,
        chi2_limit=CHI2_LIMIT,
    )
