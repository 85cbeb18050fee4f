"""The resolution study's page (analysis.kinds.resolution's numbers): per reading
and lattice the quantities against N, their limits with the form's band,
the paper's claims per resolution, the differences between resolutions and
the multilevel plan, two figures and two CSV tables beside them; the prose
is pages/templates/resolution.md.j2, the tables pages.resolution_tables."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.kinds.readings import LIMITS, Setup
from analysis.kinds.resolution import (
    DRIFT_SHARE,
    FAILED_SHARE,
    QUANTITIES,
    RESAMPLES,
    TARGETS,
    finished,
    limits,
    means_by_angle,
    multilevel,
    order,
    summaries,
)
from analysis.statistics import extrapolation, plateau
from analysis.statistics.estimates import CHI2_LIMIT
from analysis.statistics.resolution_claims import CLAIMS, claims_table
from analysis.statistics.seeds import BOOTSTRAP_FROM
from ground.digits import rounded
from ground.gate import write_figure

from . import resolution_tables as tables
from .render import render
from .text import markdown_table

TITLE = "The continuum limit: e, beta and friction against the disk's resolution"
FIGURE_CURVES = "resolution_curves.png"
FIGURE_TRENDS = "resolution_trends.png"
LIMITS_CSV = "limits.csv"
LEVELS_CSV = "levels.csv"
# The page stays below this many bytes: past it, the tables against N are
# left to levels.csv.
PAGE_BYTES = 20_000
# What each reading of the study is (a reading not named here: its options).
READINGS = {
    "continuum": "the roughness a Gaussian profile of correlation length 0.048 R along each "
    "surface, drawn anew at each N (its rms slope is that of the paper's draw per point at 800 "
    "points), the contact's a times the spacing and its energy per length of surface held at "
    "the 800-point disk's",
    "point-roughness": "the paper's roughness, drawn point by point, whose slopes grow as "
    "1 / spacing; the contact as in continuum",
    "fixed-contact": "the paper's contact, a R = 300 and V0 = a M c^2 R / 2 at every "
    "resolution (refused beyond 3,200 points, where exp(-a r) is not resolved at the cutoff); "
    "the roughness as in continuum",
}


def reading_text(name: str) -> str:
    if name in READINGS:
        return READINGS[name]
    options = LIMITS.get(name)
    return f"options {options}" if options else "a reading of the rows"


def coverage(summary: dict) -> list[dict]:
    """Per reading and lattice: its levels with their seeds."""
    out = []
    for reading, lattice in sorted({k[:2] for k in summary}, key=order):
        ns = sorted(n for (li, la, n) in summary if (li, la) == (reading, lattice))
        seeds = [(n, summary[(reading, lattice, n)]["seeds"]) for n in ns]
        out.append(
            {
                "reading": reading,
                "lattice": lattice,
                "levels": ", ".join(f"{n:,} ({k})" for n, k in seeds),
            }
        )
    return out


def walton_chi2(summary: dict) -> dict:
    """Walton's chi2/dof over the levels from 800 points: per way its range,
    and how many of the levels' fits fail (above CHI2_LIMIT) of how many."""
    values = {"measured": [], "paper": []}
    for (_, _, n), s in summary.items():
        if n >= extrapolation.FIT_FROM and "chi2" in s:
            for way in values:
                values[way].append(s["chi2"][way])
    out = {way: (min(v), max(v)) if v else (float("nan"),) * 2 for way, v in values.items()}
    every = [x for v in values.values() for x in v]
    out["failing"] = sum(x > CHI2_LIMIT for x in every)
    out["fits"] = len(every)
    return out


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
        curves = rounded(means_by_angle(rows, limit, lattice))  # drawn as written
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
    fig.suptitle(
        "means over seeds; error bars: standard error of the mean, sd / sqrt(n) over the "
        "angle's n seeds (what the seed jackknife of a mean gives)",
        fontsize=9,
    )
    fig.tight_layout()
    write_figure(fig, path, 100)
    plt.close(fig)


def draw_trends(summary: dict, found: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    shown = ("e_normal", "mu", "beta0", "mu_branch")
    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 3.6))
    for ax, q in zip(axes, shown, strict=True):
        for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=order):
            points = [
                (n, *rounded(s["values"][q]), bool(s["excluded"]))  # drawn as written
                for (li, la, n), s in sorted(summary.items())
                if (li, la) == (limit, lattice) and q in s["values"]
            ]
            if not points:
                continue
            n, v, sd, out = (np.array(x) for x in zip(*points, strict=True))
            h = extrapolation.spacing(n)
            line = ax.errorbar(h, v, sd, marker="o", ms=3, label=f"{limit}, {lattice}")
            colour = line[0].get_color()
            if out.any():
                ax.plot(h[out], v[out], "x", color="k", ms=8)
            fit = rounded(found[(limit, lattice, q)])
            x = np.linspace(0.0, 1.0, 30)
            for form, style in (("h", ":"), ("h2", "--")) if fit["status"] == "limit" else ():
                f = fit["forms"].get(form)
                if f and f["describes"]:
                    ax.plot(x, f["limit"] + f["c"] * x ** f["p"], ls=style, color=colour, lw=0.8)
        ax.set_xlabel("spacing over the 800-point disk's, sqrt(800 / N)")
        ax.set_title(q, fontsize=10)
    axes[0].legend(fontsize=6)
    fig.suptitle(
        f"error bars: seed bootstrap sd at {BOOTSTRAP_FROM}+ seeds, seed jackknife below; "
        "dotted: Q0 + c h, dashed: Q0 + c h^2 (where a limit is given and they describe the "
        "levels); x: left out",
        fontsize=8,
    )
    fig.tight_layout()
    write_figure(fig, path, 100)
    plt.close(fig)


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its two figures and two CSV tables go into ``figures``."""
    summary = summaries(rows)
    wanted = tuple(dict.fromkeys([q for q, _ in QUANTITIES] + [c[2] for c in CLAIMS]))
    found = limits(summary, wanted, rows)
    quantities = {k: v for k, v in found.items() if k[2] in dict(QUANTITIES)}
    shown = {k: v for k, v in quantities.items() if v["status"] != "too few"}
    too_few = sorted({k[:2] for k, v in quantities.items() if v["status"] == "too few"}, key=order)
    pairs = sorted({k[:2] for k in summary}, key=order)
    levels = {pair: multilevel(rows, summary, *pair) for pair in pairs}
    figures = Path(figures)
    figures.mkdir(parents=True, exist_ok=True)
    draw_curves(rows, figures / FIGURE_CURVES)
    draw_trends(summary, found, figures / FIGURE_TRENDS)
    tables.write_limits_csv(found, figures / LIMITS_CSV)
    tables.write_levels_csv(summary, figures / LEVELS_CSV)
    readings = sorted({r for r, _ in pairs}, key=lambda r: order((r, "")))
    per_n = [
        {
            "reading": r,
            "lattice": la,
            "table": markdown_table(*tables.level_rows(summary, r, la, extrapolation.FIT_FROM)),
        }
        for r, la in pairs
    ]
    text = render_page(setup, rows, summary, found, shown, too_few, levels, readings, per_n)
    if len(text.encode()) > PAGE_BYTES:
        text = render_page(setup, rows, summary, found, shown, too_few, levels, readings, [])
    return text


def shorter_step(rows: list[dict]) -> list[dict]:
    """The rows run at a shorter step than their level's (reading and N)
    longest: impacts that a triangle crossing the area barrier made run again
    at half the step (runner.impact, barrier_halvings)."""
    longest: dict[tuple, float] = {}
    for row in rows:
        if row.get("dt"):
            key = (row["reading"], row["n_disk"])
            longest[key] = max(longest.get(key, 0.0), float(row["dt"]))
    return [r for r in rows if r.get("dt") and float(r["dt"]) < longest[r["reading"], r["n_disk"]]]


def render_page(setup, rows, summary, found, shown, too_few, levels, readings, per_n) -> str:
    """The template with the page's numbers; ``per_n`` empty: the tables
    against N only in levels.csv."""
    return render(
        "resolution.md.j2",
        study=setup.study,
        impacts=len(rows),
        failed=len(rows) - len(finished(rows)),
        halved=len(shorter_step(rows)),
        coverage=coverage(summary),
        readings=[{"name": r, "text": reading_text(r)} for r in readings],
        excluded=[
            {"reading": k[0], "lattice": k[1], "n": k[2], "why": s["excluded"]}
            for k, s in sorted(summary.items())
            if s["excluded"]
        ],
        short=[
            dict(zip(("reading", "lattice", "n"), k), seeds=s["seeds"], angles=s["short_angles"])
            for k, s in sorted(summary.items())
            if s["short_angles"]
        ],
        walton=walton_chi2(summary),
        limits=tables.limits_table(shown),
        friction=tables.friction_table(summary),
        normal_from=plateau.NORMAL_FROM,
        grazing=plateau.GRAZING,
        too_few=too_few,
        claims=[
            {"reading": r, "table": tables.claims_markdown(claims_table(summary, found, r))}
            for r in readings
        ],
        differences=tables.differences_table(levels),
        plans=tables.plans_table(levels),
        per_n=per_n,
        figures=setup.figures,
        curves=FIGURE_CURVES,
        trends=FIGURE_TRENDS,
        limits_csv=LIMITS_CSV,
        levels_csv=LEVELS_CSV,
        resamples=RESAMPLES,
        bootstrap_from=BOOTSTRAP_FROM,
        fit_from=extrapolation.FIT_FROM,
        p_value=extrapolation.P_VALUE,
        agree=extrapolation.AGREE,
        power_bounds=extrapolation.POWER_BOUNDS,
        chi2_limit=CHI2_LIMIT,
        drift_share=DRIFT_SHARE,
        failed_share=FAILED_SHARE,
        targets=TARGETS,
    )
