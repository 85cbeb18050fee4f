"""The numbers of the resolution study's page (analysis.resolution) and its
figures; the prose is analysis/templates/resolution.md.j2.

Per reading (analysis.readings.LIMITS), lattice and number of disk points:
the model-free measures and Walton's measured-way fit of every study
(analysis.estimates.study_estimates on that resolution's impacts alone, with
its seed-bootstrap errors), then, per quantity, a weighted straight line in
the spacing h = sqrt(800 / N) through the resolutions from 800 points up,
whose intercept is the estimate of the limit N -> infinity.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .estimates import study_estimates
from .readings import Setup, markdown_table
from .render import render

FIGURE_CURVES = "resolution_curves.png"
FIGURE_TRENDS = "resolution_trends.png"
RESAMPLES = 200
# The quantities followed against N: (key, label); ``extract`` reads them.
QUANTITIES = (
    ("e_normal", "e near normal incidence (cot gamma >= 1)"),
    ("mu", "Walton's mu (measured way)"),
    ("beta0", "Walton's beta0 (measured way)"),
    ("mu_eff_top", "mu_eff at the sliding branch's top"),
    ("e_grazing", "e at grazing incidence (3 smallest cot gamma)"),
)
# The extrapolation uses the resolutions from this many points up.
EXTRAPOLATE_FROM = 800
# Two numbers agree when they differ by less than this many combined errors.
AGREE = 2.0
CHI2_LIMIT = 2.0


def finished(rows: list[dict]) -> list[dict]:
    return [r for r in rows if not r.get("error") and r.get("e") not in (None, "")]


def extract(entry: dict) -> dict[str, tuple[float, float]]:
    """(value, seed-bootstrap sd) of each of QUANTITIES from a fits.json lattice entry."""
    walton = entry["walton"]["measured"]
    measures = entry["measures"]
    out = {
        key: (measures[key]["value"], measures[key]["sd"])
        for key in measures
        if key in dict(QUANTITIES)
    }
    out["mu"] = (walton["mu"], walton["mu_sd"])
    out["beta0"] = (walton["beta0"], walton["beta0_sd"])
    out["mu_chi2"] = (walton["chi2"], float("nan"))
    return out


def summaries(rows: list[dict]) -> dict[tuple[str, str, int], dict]:
    """(limit, lattice, n_disk) -> its quantities, impacts, seeds, failures and drift."""
    out = {}
    keys = sorted({(r["limit"], r["study_lattice"], int(r["n_disk"])) for r in rows})
    for limit, lattice, n_disk in keys:
        group = [
            r
            for r in rows
            if r["limit"] == limit and r["study_lattice"] == lattice and int(r["n_disk"]) == n_disk
        ]
        done = finished(group)
        entry = {
            "impacts": len(group),
            "failed": len(group) - len(done),
            "seeds": len({r["seed"] for r in group}),
            "dt": float(done[0]["dt"]) if done else float("nan"),
            "drift": max((abs(float(r["energy_drift"])) for r in done), default=float("nan")),
            "drifted": sum(r["drift_exceeded"] in ("True", "true", "1") for r in done),
        }
        if done:
            fits, _ = study_estimates(done, resamples=RESAMPLES, compliant=False)
            entry.update(extract(fits["lattices"][lattice]))
        out[(limit, lattice, n_disk)] = entry
    return out


def extrapolate(points: list[tuple[int, float, float]]) -> dict | None:
    """Weighted line q = q_inf + A h, h = sqrt(800 / N), through (N, q, sd)
    with N >= EXTRAPOLATE_FROM; None with fewer than three such points."""
    use = [(n, q, s) for n, q, s in points if n >= EXTRAPOLATE_FROM and s > 0 and np.isfinite(q)]
    if len(use) < 3:
        return None
    n, q, s = (np.array(v, float) for v in zip(*use, strict=True))
    h = np.sqrt(800.0 / n)
    design = np.stack([np.ones_like(h), h], axis=1) / s[:, None]
    coef, *_ = np.linalg.lstsq(design, q / s, rcond=None)
    covariance = np.linalg.inv(design.T @ design)
    chi2 = float(np.sum(((q - design @ coef * s) / s) ** 2) / (len(q) - 2))
    return {
        "limit": float(coef[0]),
        "limit_sd": float(np.sqrt(covariance[0, 0])),
        "slope": float(coef[1]),
        "slope_sd": float(np.sqrt(covariance[1, 1])),
        "chi2": chi2,
        "points": len(q),
        "from": int(n.min()),
        "to": int(n.max()),
    }


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
    for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=_order):
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
            points = [
                (n, *summary[(limit, lattice, n)][q])
                for n in ns
                if q in summary[(limit, lattice, n)]
            ]
            line = extrapolate(points)
            at_800 = next(((v, s) for n, v, s in points if n == 800), None)
            finest = (points[-1][0], points[-1][1]) if points else None
            verdicts[(limit, lattice, q)] = {
                "name": name,
                "line": line,
                "text": verdict(line, at_800, finest),
            }
    return tables, verdicts


def _order(key: tuple[str, str]) -> tuple[int, str]:
    limits = ("continuum", "point-roughness", "fixed-contact")
    return (limits.index(key[0]) if key[0] in limits else len(limits), key[1])


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
        verdicts.items(), key=lambda kv: (_order(kv[0][:2]), kv[0][2])
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


def means_by_angle(rows: list[dict], limit: str, lattice: str) -> dict[int, list[tuple]]:
    """N -> [(cot gamma, e mean, e se, beta mean, beta se)] over the seeds."""
    out: dict[int, list[tuple]] = {}
    mine = [r for r in finished(rows) if r["limit"] == limit and r["study_lattice"] == lattice]
    for n in sorted({int(r["n_disk"]) for r in mine}):
        at_n = [r for r in mine if int(r["n_disk"]) == n]
        points = []
        for gamma in sorted({float(r["gamma_deg"]) for r in at_n}):
            here = [r for r in at_n if float(r["gamma_deg"]) == gamma]
            e = np.array([float(r["e"]) for r in here])
            beta = np.array([float(r["beta"]) for r in here])
            cot = float(np.mean([float(r["cot_gamma"]) for r in here]))
            se = lambda a: a.std(ddof=1) / np.sqrt(len(a)) if len(a) > 1 else np.nan  # noqa: E731
            points.append((cot, e.mean(), se(e), beta.mean(), se(beta)))
        out[n] = points
    return out


def draw_curves(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [
        (limit, lattice)
        for limit, lattice in sorted({(r["limit"], r["study_lattice"]) for r in rows}, key=_order)
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
        for limit, lattice in sorted({(k[0], k[1]) for k in summary}, key=_order):
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


def body(rows: list[dict], setup: Setup, figures: Path) -> str:
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
