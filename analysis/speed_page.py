"""The speed study's page and figures, from its tables (analysis.speed's numbers)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from builder.materials import STUDY_LATTICES as LATTICES

from .figures import LABELS, STYLE
from .page import pm
from .sections import failure_section, genuine, outcome_note, tables_where, wall_end_section
from .speed import shear_over_bulk

# Gerl and Zippelius, Phys. Rev. E 59, 2361 (1999), cond-mat/9808258.
GERL_ZIPPELIUS = (
    "Gerl and Zippelius (Phys. Rev. E 59, 2361, 1999) found, for 2-D elastic disks whose only "
    "loss is to their vibrations, e falling as the impact speed rises, and falling further for "
    "a lower shear modulus against the bulk modulus"
)


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
    fig.savefig(paths[0], dpi=120)
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
    fig.savefig(paths[1], dpi=120)
    plt.close(fig)
    return paths


def order_section(numbers: dict, lattice_specs: dict) -> list[str]:
    """The lattices by e at near-normal incidence beside their order by G / B."""
    speeds = numbers["speeds"]
    ratio = {
        k: shear_over_bulk(s["lattice"], s.get("k2_over_k1")) for k, s in lattice_specs.items()
    }
    present = [k for k in numbers["lattices"] if k in ratio]
    by_ratio = sorted(present, key=lambda k: ratio[k])
    lines = [
        "## Against Gerl and Zippelius",
        "",
        GERL_ZIPPELIUS + ". Here, e at near-normal incidence "
        f"(gamma = {numbers['gamma_deg'][0]:g} deg) per lattice and speed, the lattices in "
        "increasing shear over bulk modulus G / B (the axes' frame, calibration/materials.json; "
        "Gerl and Zippelius: e increasing down the table):",
        "",
        "| lattice | G / B | " + " | ".join(f"v_n = {v:g}" for v in speeds) + " |",
        "|---|---|" + "---|" * len(speeds),
    ]
    for k in by_ratio:
        data = numbers["lattices"][k]
        cells = [pm(data["e"][i][0], data["e_error"][i][0]) for i in range(len(speeds))]
        lines.append(f"| {k} | {ratio[k]:.3f} | " + " | ".join(cells) + " |")
    lines += ["", *trend_lines(numbers, present), *order_lines(numbers, by_ratio), ""]
    return lines


def trend_lines(numbers: dict, lattices: list[str]) -> list[str]:
    """e from the slowest to the fastest impact, in errors, per lattice."""
    parts, falls = [], 0
    for k in lattices:
        data = numbers["lattices"][k]
        e0, e1 = data["e"][0][0], data["e"][-1][0]
        s0, s1 = data["e_error"][0][0], data["e_error"][-1][0]
        drop = (e0 - e1) / np.hypot(s0, s1)
        falls += drop > 2.0
        parts.append(f"{k} {e0:.3f} to {e1:.3f} ({drop:+.0f} errors)")
    speeds = numbers["speeds"]
    return [
        f"- **The trend**: from v_n = {speeds[0]:g} to {speeds[-1]:g} c, e at near-normal "
        f"incidence goes {'; '.join(parts)}: it falls by more than two errors on {falls} of "
        f"the {len(lattices)} lattices (Gerl and Zippelius: falls). Where it is flat, the "
        "power-law table's range shows it."
    ]


def order_lines(numbers: dict, by_ratio: list[str]) -> list[str]:
    """Per speed, the pairs of lattices whose e differs by more than two combined
    errors: how many are in the order of G / B (the lower G / B, the lower e)."""
    cells = []
    for i, v in enumerate(numbers["speeds"]):
        e = [numbers["lattices"][k]["e"][i][0] for k in by_ratio]
        s = [numbers["lattices"][k]["e_error"][i][0] for k in by_ratio]
        agree = against = 0
        for a in range(len(e)):
            for b in range(a + 1, len(e)):
                if abs(e[b] - e[a]) > 2 * np.hypot(s[a], s[b]):
                    agree += e[b] > e[a]
                    against += e[b] < e[a]
        cells.append(f"{v:g}: {agree} in order, {against} against")
    return [
        "- **The order by G / B**: pairs of lattices whose e differs by more than two "
        "combined errors, in the order Gerl and Zippelius found (lower G / B, lower e) or "
        "against it, per v_n: " + "; ".join(cells) + "."
    ]


def resolution_section(rows: list[dict], failed: list[dict], speeds: list[float]) -> list[str]:
    """Per speed: failures, energy drifts above the guard, the largest drift."""
    lines = [
        "## Where the contact stops being resolved",
        "",
        "Per speed: the impacts that failed (a disk point inside the wall, a disk sliding "
        "off it), those whose energy drift exceeds --max-drift (`drift_exceeded`: the "
        "step is too large for them), and the largest |drift|. The speed above which the "
        "default run stops resolving the contact is measured on its own by `python "
        "bench/stability.py --parts speeds` (docs/benchmarks/stability_speeds.md).",
        "",
        "| v_n | impacts | failed | drift above the guard | largest drift |",
        "|---|---|---|---|---|",
    ]
    for v in speeds:
        mine = [r for r in rows if math.isclose(float(r["vn"]), v)]
        lost = [f for f in genuine(failed) if math.isclose(float(f.get("vn") or "nan"), v)]
        drift = [abs(float(r["energy_drift"])) for r in mine] or [float("nan")]
        above = sum(str(r["drift_exceeded"]) == "True" for r in mine)
        lines.append(f"| {v:g} | {len(mine)} | {len(lost)} | {above} | {max(drift):.2g} |")
    return lines + [""]


def power_law_section(numbers: dict) -> list[str]:
    lines = [
        "## The power law",
        "",
        "1 - e = A v_n^p, fitted in log-log over the widest run of consecutive speeds (at least "
        "three) with a reduced chi^2 at most 2 against the seed-bootstrap errors of the means; "
        "p's error is its spread over the seed resamples (every speed of a seed together). "
        "None: no run of three speeds fits.",
        "",
        "| lattice | gamma, deg | speeds | p | A | reduced chi^2 |",
        "|---|---|---|---|---|---|",
    ]
    for lattice, data in numbers["lattices"].items():
        for gamma, law in zip(numbers["gamma_deg"], data["power_law"], strict=True):
            if not law:
                lines.append(f"| {lattice} | {gamma:g} | none | - | - | - |")
                continue
            lines.append(
                f"| {lattice} | {gamma:g} | {law['v_low']:g} to {law['v_high']:g} "
                f"({law['points']}) | {pm(law['p'], law['p_error'])} | {law['A']:.3g} | "
                f"{law['chi2']:.2f} |"
            )
    return lines + [""]


def means_section(numbers: dict) -> list[str]:
    lines = [
        "## e, beta0 and mu against the speed",
        "",
        "Means over seeds +- their seed-bootstrap errors. beta0: beta at the sticking angle "
        f"(gamma = {numbers['sticking_gamma']:g} deg); mu: the friction the sliding angle "
        f"(gamma = {numbers['sliding_gamma']:g} deg) implies on Walton's sliding branch, "
        "(1 + beta) / ((1 + e) K cot gamma) with the disk's own K.",
        "",
        "| lattice | v_n | impacts | "
        + " | ".join(f"e, {g:g} deg" for g in numbers["gamma_deg"])
        + " | beta0 | mu |",
        "|---|---|---|" + "---|" * (len(numbers["gamma_deg"]) + 2),
    ]
    for lattice, data in numbers["lattices"].items():
        for i, v in enumerate(numbers["speeds"]):
            cells = [pm(e, s) for e, s in zip(data["e"][i], data["e_error"][i], strict=True)]
            lines.append(
                f"| {lattice} | {v:g} | {sum(data['impacts'][i])} | "
                + " | ".join(cells)
                + f" | {pm(data['beta0'][i], data['beta0_error'][i])} | "
                f"{pm(data['mu'][i], data['mu_error'][i])} |"
            )
    return lines + [""]


def page(
    info: dict,
    rows: list[dict],
    failed: list[dict],
    numbers: dict,
    figure_dir: str,
    made_by: str,
    tables: str,
    preset: str,
) -> str:
    """The speed study's page (markdown)."""
    near = near_side_counts(rows)
    lines = [
        f"# e and beta against the impact speed: study `{info['name']}`",
        "",
        f"{len(rows)} impacts: lattices {', '.join(info['lattices'])}; v_n = "
        f"{', '.join(f'{v:g}' for v in numbers['speeds'])} c; angles "
        f"{', '.join(f'{g:g}' for g in numbers['gamma_deg'])} degrees (near-normal, sticking, "
        f"sliding); {info['samples']} samples, the same seeds at every speed and angle; "
        f"velocity Verlet, dt = {info['options']['dt']} R/c. {outcome_note(failed)}. "
        f"Tables{tables_where(tables, preset)}: `impacts.csv` (one row per impact, "
        "the paper study's columns), `speed.json` (every number on this page, with its "
        "error), `failed.csv`. "
        f"Made by `{made_by}`.",
        "",
        "Every error is the standard deviation over 200 resamples of whole seeds (a seed's "
        "impacts at every speed, angle and lattice together), as on the results page.",
        "",
        *power_law_section(numbers),
        *order_section(numbers, {k: LATTICES[k] for k in numbers["lattices"]}),
        *means_section(numbers),
        *resolution_section(rows, failed, numbers["speeds"]),
        "## Figures",
        "",
        f"![1 - e against v_n]({figure_dir}/speed_e.png)",
        "",
        "*1 - e against v_n, log axes, one panel per angle; lines: the power laws over their "
        "range. Error bars: seed-bootstrap errors.*",
        "",
        f"![beta0 and mu against v_n]({figure_dir}/speed_beta0_mu.png)",
        "",
        "*beta at the sticking angle and mu_eff at the sliding angle against v_n.*",
        "",
    ]
    if near:
        lines += wall_end_section(near, info.get("wall_width", 8.0))
    lines += failure_section(failed)
    return "\n".join(lines).rstrip("\n") + "\n"


def near_side_counts(rows: list[dict]) -> list[dict]:
    """Per lattice, speed and angle: the impacts, and those whose disk centre
    came within 1 R of a held side (analysis.table.NEAR_SIDE)."""
    from .table import NEAR_SIDE

    out: dict = {}
    for r in rows:
        key = (f"{r['study_lattice']}, v_n {float(r['vn']):g}", float(r["gamma_deg"]))
        entry = out.setdefault(
            key, {"study_lattice": key[0], "gamma_deg": key[1], "near_side": 0, "samples": 0}
        )
        entry["samples"] += 1
        entry["near_side"] += float(r["side_clearance"]) < NEAR_SIDE
    return [m for m in out.values() if m["near_side"]]
