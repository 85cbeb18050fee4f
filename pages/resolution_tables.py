"""The resolution page's tables (analysis.kinds.resolution's numbers in Markdown
and CSV): the limits, the paper's claims per resolution, the differences
between resolutions, the multilevel plan and each reading against N."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from analysis.kinds.resolution import FITTED, QUANTITIES, order
from analysis.statistics.extrapolation import FIT_FROM, FORMS
from ground.digits import rounded
from ground.gate import atomic

from .text import markdown_table, pm

FORM_NAMES = {"h": "Q0 + c h", "h2": "Q0 + c h^2", "power": "Q0 + c h^p"}
STEP = "{:+.3f} +- {:.3f}"


def steps_text(halvings: dict | None) -> str:
    if not halvings:
        return "-"
    before, last = STEP.format(*halvings["before"]), STEP.format(*halvings["last"])
    return f"{before}, then {last} (to {halvings['finest']:,})"


def limit_text(found: dict) -> str:
    """A quantity's verdict in the limit, in words."""
    status = found["status"]
    if status == "limit":
        if found["described_by"] == ["constant"]:
            return f"{found['value']:.3f} at every level"
        return (
            f"{found['value']:.3f} +- {found['stat']:.3f} +- {found['systematic']:.3f} form "
            f"({found['band'][0]:.3f} to {found['band'][1]:.3f})"
        )
    if status == "not converged":
        return f"not converged at N = {found['halvings']['finest']:,}"
    if status == "no form":
        return "undecided: no form describes the levels"
    if status == "not identified":
        levels = ", ".join(f"{n:,}" for n, _ in found["open_above"])
        lows = [low for _, low in found["open_above"]]
        rises = ", ".join(f"{n:,}" for n in found.get("rising", []))
        shape = (
            f"although beta rises from grazing to normal incidence at N = {rises}, seed by "
            "seed: not one plateau"
            if rises
            else "no rise of beta from grazing to normal incidence resolved"
        )
        if found.get("of") == "mu_branch":
            return (
                f"not identified: no sliding branch in the rows at N = {levels} (the two "
                f"most grazing angles' mu_eff differ; mu >= {min(lows):.3f} to "
                f"{max(lows):.3f} there, at the most grazing angle)"
            )
        fit = "fit with the seeds' covariance" if found.get("of") == "mu_gls" else "weighted fit"
        return (
            f"not identified by Walton's {fit}: no upper bound at N = {levels} (mu >= "
            f"{min(lows):.3f} to {max(lows):.3f}; {shape})"
        )
    return "too few levels from 800 points"


def form_text(fit: dict | None) -> str:
    if not fit:
        return "-"
    text = f"{fit['limit']:.3f} +- {fit['limit_sd']:.3f}"
    if fit["form"] == "power":
        text += f" (p {fit['p']:.2f}" + (", on its bound)" if fit["pinned"] else ")")
    return text + f", p-value {fit['p_value']:.2f}"


def limits_table(limits: dict) -> str:
    header = ["reading", "lattice", "quantity", "N -> infinity", "800 points above it"]
    header.append("last two steps")
    names = [k for k, _ in QUANTITIES]
    body = []
    for (reading, lattice, q), found in sorted(
        limits.items(), key=lambda kv: (order(kv[0][:2]), names.index(kv[0][2]))
    ):
        shift = pm(found["shift_800"], found["shift_800_sd"]) if "shift_800" in found else "-"
        body.append([reading, lattice, q, limit_text(found), shift, steps_text(found["halvings"])])
    return markdown_table(header, body)


def write_limits_csv(limits: dict, path: Path) -> None:
    """Every form's fit of every quantity (limits.csv beside the figures)."""
    columns = ["reading", "lattice", "quantity", "status", "levels", "form", "Q0", "Q0_sd"]
    columns += ["c", "c_sd", "p", "p_sd", "chi2_per_dof", "dof", "p_value", "describes"]
    with atomic(path) as temporary, temporary.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(columns)
        for (reading, lattice, q), found in sorted(limits.items()):
            for form in FORMS:
                fit = found["forms"].get(form)
                if not fit:
                    continue
                writer.writerow(
                    [reading, lattice, q, found["status"], " ".join(map(str, found["levels"]))]
                    + [form, *(f"{fit[k]:.5g}" for k in ("limit", "limit_sd", "c", "c_sd"))]
                    + [f"{fit[k]:.4g}" for k in ("p", "p_sd", "chi2")]
                    + [fit["dof"], f"{fit['p_value']:.3g}", fit["describes"]]
                )


def claims_markdown(table: list[dict]) -> str:
    """One reading's claims against N and in the limit."""
    ns = sorted({n for row in table for n in row["cells"] if n >= FIT_FROM})
    header = ["claim", *(f"{n:,}" for n in ns), "N -> infinity"]
    body = []
    for row in table:
        cells = [row["claim"]]
        for n in ns:
            cell = row["cells"].get(n)
            if cell and cell.get("note"):
                cells.append(f"{cell['verdict']} ({cell['note']})")
            else:
                cells.append(
                    f"{cell['verdict']} ({pm(cell['value'], cell['error'])})" if cell else "-"
                )
        limit = row["limit"]
        cells.append(
            f"{limit['verdict']} ({pm(limit['value'], limit['error'])})"
            if limit["value"] is not None
            else limit["verdict"]
        )
        body.append(cells)
    return markdown_table(header, body)


def differences_table(multilevel: dict) -> str:
    """Per reading, lattice and N: sd of the per-seed differences against the
    sd of Q(N), per group."""
    groups = ("e_normal", "e_grazing", "beta_normal", "beta_grazing")
    header = ["reading", "lattice", "N/2 -> N", "seeds", *groups]
    body = []
    for (reading, lattice), found in sorted(multilevel.items(), key=lambda kv: order(kv[0])):
        by_n = {g: {d["n"]: d for d in found["differences"][g]} for g in groups}
        for n in sorted(by_n["e_normal"]):
            if n < 1600:
                continue
            cells = [reading, lattice, f"{n // 2:,} -> {n:,}", str(by_n["e_normal"][n]["seeds"])]
            for g in groups:
                d = by_n[g].get(n)
                cells.append(f"{d['sd_difference']:.3f} / {d['sd_level']:.3f}" if d else "-")
            body.append(cells)
    return markdown_table(header, body)


def plans_table(multilevel: dict) -> str:
    header = ["reading", "lattice", "quantity +- target", "levels", "seeds per level"]
    header += ["cost (800-point seeds)", "the finest alone: seeds, cost"]
    body = []
    for (reading, lattice), found in sorted(multilevel.items(), key=lambda kv: order(kv[0])):
        for q, plan in found["plans"].items():
            body.append(
                [
                    reading,
                    lattice,
                    f"{q} +- {plan['target']:g}",
                    ", ".join(f"{n:,}" for n in plan["levels"]),
                    ", ".join(map(str, plan["seeds"])),
                    f"{plan['cost']:,.0f}",
                    f"{plan['finest_alone_seeds']}, {plan['finest_alone_cost']:,.0f}",
                ]
            )
    return markdown_table(header, body)


def level_rows(
    summary: dict, reading: str, lattice: str, start: int = 0
) -> tuple[list[str], list[list[str]]]:
    """One reading's levels from ``start`` points: seeds and errors, impacts,
    failures, impacts over the drift limit and the quantities."""
    header = ["N", "seeds (errors)", "impacts"]
    header += [q for q, _ in QUANTITIES] + ["Walton chi2/dof (measured, paper's)"]
    body = []
    for (li, la, n), s in sorted(summary.items()):
        if (li, la) != (reading, lattice) or n < start:
            continue
        method = s.get("errors", {}).get("method", "-")
        cells = [f"{n:,}" + (" (left out)" if s["excluded"] else ""), f"{s['seeds']} ({method})"]
        cells.append(f"{s['impacts']} ({s['failed']}; {s['drifted']})")
        for q, _ in QUANTITIES:
            value = s["values"].get(q)
            text = pm(*value) if value else "-"
            bounds = s.get("mu_bounds", {}).get("measured")
            if q == "mu" and value and bounds and math.isinf(bounds[1]):
                text = f">= {bounds[0]:.3f} (no upper bound; fit {value[0]:.3f})"
            elif q in FITTED and value:
                text += f" +- {s['systematic'][q]:.3f} sys"
            cells.append(text)
        chi2 = s.get("chi2")
        cells.append(f"{chi2['measured']:.1f}, {chi2['paper']:.1f}" if chi2 else "-")
        body.append(cells)
    return header, body


def write_levels_csv(summary: dict, path: Path) -> None:
    """Every level's table row (levels.csv beside the figures)."""
    with atomic(path) as temporary, temporary.open("w", newline="") as handle:
        writer = csv.writer(handle)
        first = True
        for reading, lattice in sorted({k[:2] for k in summary}, key=order):
            header, body = level_rows(summary, reading, lattice)
            if first:
                writer.writerow(["reading", "lattice", *header])
                first = False
            writer.writerows([reading, lattice, *row] for row in body)


def rise_text(rise: dict) -> str:
    """beta near normal minus beta at grazing incidence, with what it says."""
    if rise.get("on_plateau") is None:
        return "-"
    verdict = "no rise resolved" if rise["on_plateau"] else "rises"
    interval = "" if rise["seeds"] >= 8 else f", t {rise['threshold']:.2f}"
    return f"{pm(rise['value'], rise['sd'])} ({verdict}{interval})"


def friction_table(summary: dict) -> str:
    """Per reading, lattice and level from FIT_FROM: the seeds, beta's rise
    from grazing to normal incidence and mu_eff at the most grazing angle,
    each over the seeds (analysis.statistics.plateau)."""
    header = ["reading", "lattice", "N", "seeds", "beta: normal - grazing"]
    header += ["mu_eff at the most grazing angle", "Walton, seeds' covariance: mu", "beta0"]
    header.append("chi2/dof")
    body = []
    for (reading, lattice, n), s in sorted(
        summary.items(), key=lambda kv: (order(kv[0][:2]), kv[0][2])
    ):
        if n < FIT_FROM or "plateau" not in s:
            continue
        value, sd = s["values"]["mu_eff_grazing"]
        body.append(
            [reading, lattice, f"{n:,}", str(s["plateau"]["seeds"]), rise_text(s["plateau"])]
            + [f"{pm(value, sd)} ({s['grazing_deg']:g} degrees)"]
            + gls_cells(s.get("gls"))
        )
    return markdown_table(header, body)


def gls_cells(gls: dict | None) -> list[str]:
    """Walton fitted with the seeds' covariance (analysis.statistics.walton_gls):
    mu +- its seed error [its profile's two-error range], beta0, chi2/dof."""
    if gls is None:
        return ["-", "-", "-"]
    low, high = gls["mu_bounds"]
    upper = "no upper bound" if np.isinf(high) else f"{rounded(high):.3f}"
    return [
        f"{pm(gls['mu'], gls['mu_sd'])} [{rounded(low):.3f} to {upper}]",
        pm(gls["beta0"], gls["beta0_sd"]),
        f"{rounded(gls['chi2'] / gls['dof']):.1f}",
    ]
