"""Friction against the surface's rms slope on the sliding branch: a table
and a figure from the sliding-branch studies' committed tables.

Each folder is one study of studies/sliding_branch*.toml; its rms slope is
the continuous profile's, roughness / roughness_length (a Gaussian profile
of height sd h and correlation length L has slopes of sd h / L). The
folders of one slope are the levels of one chain (analysis.branch.limit):
each level's mean mu_eff over the angles and mu_eff at 80.5 degrees, with
the seeds' jackknife errors, and the limit where the levels give one.

    python -m pages.friction docs/studies/sliding_branch_slope015 \\
        docs/studies/sliding_branch_slope03 docs/studies/sliding_branch ... \\
        --angles 85.4 86.3 87 --docs

--docs writes the table and the figure into docs/friction/ (the committed
record, with the command that made them); --figure draws the figure elsewhere.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from analysis.branch.limit import ANGLES_HELP, MID_ANGLE, chain, n_disk
from analysis.branch.steps import Level, add_level_arguments
from analysis.statistics.measures import mu_eff
from ground.errors import InputError
from ground.gate import grant, make_folder, write_figure, write_text
from ground.paths import ROOT

NUMBERS = ("mu_eff_mean", f"mu_eff_{MID_ANGLE:g}")
DOCS = ROOT / "docs" / "friction"
FIGURE, PAGE = "friction_slope.png", "friction_slope.md"


def friction(x: Level) -> dict[str, float]:
    """The level's mean mu_eff over its chosen angles and mu_eff at 80.5 degrees."""
    means = [x.table.mean(k) for k in ("cot_gamma", "e", "beta")]
    each = mu_eff(*means, x.K)
    at = np.flatnonzero(np.round(x.table.gamma_deg, 4) == MID_ANGLE)
    middle = float(each[at[0]]) if at.size else float("nan")  # a level without the angle
    return {NUMBERS[0]: float(np.mean(each[x.chosen])), NUMBERS[1]: middle}


def rms_slope(folder: Path) -> float:
    """The continuous profile's rms slope, from the study's record."""
    study = json.loads((folder / "study.json").read_text())
    if study.get("roughness_profile") != "continuous":
        raise InputError(f"{folder}: not a continuous profile, whose slope is h / L")
    return round(study["roughness"] / study["roughness_length"], 3)


def by_slope(folders: list[Path], angles: list[float]) -> dict[float, dict]:
    """Each slope's chain (``analysis.branch.limit.chain`` of ``friction``),
    its levels coarsest first."""
    groups: dict[float, list[Path]] = {}
    for folder in folders:
        groups.setdefault(rms_slope(folder), []).append(folder)
    out = {}
    for slope, members in sorted(groups.items()):
        members.sort(key=n_disk)
        out[slope] = chain(members, angles, numbers=friction)
    return out


def table(chains: dict[float, dict]) -> str:
    """A markdown table: slope, N, the two numbers per level, and the limits."""
    lines = [
        "| rms slope | disk points | mean mu_eff over the angles | mu_eff at 80.5 degrees |",
        "|---|---|---|---|",
    ]
    for slope, found in chains.items():
        for i, n in enumerate(found["levels"]):
            cells = [f"{found['values'][k][i]:.3f} +- {found['sd'][k][i]:.3f}" for k in NUMBERS]
            lines.append(f"| {slope:g} | {n:,} | {' | '.join(cells)} |")
        limits = [found["limits"][k] for k in NUMBERS]
        if any(limit["status"] == "limit" for limit in limits):
            cells = [
                f"{x['value']:.3f} +- {x['stat']:.3f} +- {x['systematic']:.3f}"
                if x["status"] == "limit"
                else x["status"]
                for x in limits
            ]
            lines.append(f"| {slope:g} | limit | {' | '.join(cells)} |")
    return "\n".join(lines)


def draw(chains: dict[float, dict], path: Path, angles: list[float]) -> None:
    """mu against the rms slope: every level's, and the limit with its form's band."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.2))
    for key, colour, label in (
        (NUMBERS[0], "C0", f"mean mu_eff at {', '.join(f'{a:g}' for a in angles)} degrees"),
        (NUMBERS[1], "C1", "mu_eff at 80.5 degrees"),
    ):
        for slope, found in chains.items():
            for i, n in enumerate(found["levels"]):
                shift = 0.004 * np.log2(n / 800)  # the levels side by side
                ax.errorbar(
                    slope + shift,
                    found["values"][key][i],
                    found["sd"][key][i],
                    marker="o",
                    ms=3 + i,
                    color=colour,
                    alpha=0.45,
                    capsize=2,
                    label=label if slope == min(chains) and i == 0 else None,
                )
            limit = found["limits"][key]
            if limit["status"] == "limit":
                ax.errorbar(
                    slope - 0.01,
                    limit["value"],
                    float(np.hypot(limit["stat"], limit["systematic"])),
                    marker="s",
                    color=colour,
                    capsize=4,
                    label=f"{label}, limit N -> infinity",
                )
    ax.axhspan(0.13, 0.23, color="grey", alpha=0.15, label="the paper's mu 0.18 +- 0.05")
    ax.set_xlabel("rms slope of the surfaces")
    ax.set_ylabel("mu")
    ax.legend(fontsize=7)
    ax.set_title(
        "Friction against the surface's slope (32 R wall held at sides and bottom)\n"
        "markers grow with the disk points; errors: whole seeds left out",
        fontsize=8,
    )
    fig.tight_layout()
    write_figure(fig, path, 110, "the friction figure")
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Print friction against the rms slope as a table and, with --figure, draw it."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    add_level_arguments(parser, ANGLES_HELP)
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--figure", type=Path, help="the PNG to draw (through the write gate)")
    where.add_argument(
        "--docs", action="store_true", help=f"write {PAGE} and {FIGURE} into docs/friction/"
    )
    args = parser.parse_args(argv)
    try:
        chains = by_slope(args.folders, args.angles)
        text = table(chains)
        print(text)
        if args.docs:
            grant(DOCS)
            make_folder(DOCS, "the friction page")
            draw(chains, DOCS / FIGURE, args.angles)
            write_text(DOCS / PAGE, page(text, args), "the friction page")
            print(f"wrote {DOCS.relative_to(ROOT)}/{PAGE} and {FIGURE}")
        elif args.figure:
            draw(chains, args.figure, args.angles)
            print(f"wrote {args.figure}")
    except (ValueError, OSError, InputError, KeyError) as error:
        parser.error(str(error))
    return 0


def page(text: str, args: argparse.Namespace) -> str:
    """The committed page: the command, the table and the figure."""
    folders = " ".join(str(f) for f in args.folders)
    angles = " ".join(f"{a:g}" for a in args.angles)
    return (
        "# Friction against the surface's rms slope\n\n"
        f"Generated by `python -m pages.friction {folders} --angles {angles} --docs` "
        "from the studies' committed tables (pages/friction.py says how). mu_eff = "
        "(1 + beta) / ((1 + e) K cot gamma) from the per-angle means: the mean over "
        f"{angles} degrees (where the disk slides at the paper's slope) and at 80.5 degrees, "
        "on the 32 R wall held at its sides and bottom; errors: each seed "
        "left out at every level (the jackknife), limits with their statistical error "
        "and their form's band (analysis/branch/limit.py).\n\n"
        f"{text}\n\n![mu against the rms slope]({FIGURE})\n"
    )


if __name__ == "__main__":
    raise SystemExit(main())
