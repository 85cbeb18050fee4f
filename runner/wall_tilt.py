"""The letter's mechanism for e > 1, checked from dumps: the wall's tilt under the disk.

    python -m runner tilt [--tables docs/studies/grazing] [--gamma G] [--dump-every 10]
                          [--docs | --out FOLDER]

From a grazing study's committed tables (runner study grazing), at the angle
of the largest mean e (or --gamma), the impact with the largest e and the
one with the smallest are run again, on the study's own scenes and settings
(runner.study.Study.spec), with a dump. For each, analysis/impact/tilt.py measures
the tilt that the wall's deformation adds to its surface under the disk,
frame by frame, its mean over the contact weighted by the contact force,
and the share of the normal approach speed that this tilt adds from the
tangential motion, tan(gamma) tan(tilt). The page (docs/wall_tilt/ with
--docs, runs/wall_tilt/ otherwise) has the numbers, a figure of the tilt
against time for both impacts, and their e checked against the table's.
"""

from __future__ import annotations

import argparse
import csv
import json
from dataclasses import replace
from pathlib import Path

import numpy as np

from analysis.impact.tilt import surface_tilt, tilt_effect, tilted_e
from builder.scene import ANGLE
from ground.checks import InPath, OutFolder, Range
from ground.errors import InputError
from ground.gate import grant, make_folder, write_figure, write_text
from ground.paths import ROOT, study_docs
from pages.report import shown_path
from pages.text import markdown_table

from .impact import run_impact
from .study import Study, runs_folder
from .study.provenance import machine

DUMP_EVERY = Range(1, 10_000, integer=True)


def pick(rows: list[dict], gamma: float | None) -> tuple[float, dict, dict]:
    """The angle (the largest mean e unless given), its impacts of largest and smallest e."""
    by_angle: dict[float, list[dict]] = {}
    for r in rows:
        by_angle.setdefault(float(r["gamma_deg"]), []).append(r)
    if gamma is None:
        gamma = max(by_angle, key=lambda g: np.mean([float(r["e"]) for r in by_angle[g]]))
    elif gamma not in by_angle:
        angles = " ".join(f"{g:g}" for g in sorted(by_angle))
        raise InputError(f"--gamma must be one of the study's angles ({angles}), got {gamma:g}")
    these = sorted(by_angle[gamma], key=lambda r: float(r["e"]))
    return gamma, these[-1], these[0]


def run(study: Study, row: dict, folder: Path, dump_every: int) -> dict:
    job = {
        "lattice": row["study_lattice"],
        "seed": int(row["seed"]),
        "gamma": float(row["gamma_deg"]),
        "vn": float(row["vn"]),
    }
    options = replace(study.options, dump_every=dump_every, route="lmp")
    result = run_impact(study.spec(job), folder, options)
    tilt = surface_tilt(folder)
    window = (tilt.time >= result["contact_start"]) & (tilt.time <= result["contact_end"])
    numbers = tilt_effect(folder, tilt, float(row["gamma_deg"]))
    numbers["largest_tilt_deg"] = float(np.degrees(np.nanmax(np.abs(tilt.tilt[window]))))
    numbers["e_tilted"] = tilted_e(result, np.radians(numbers["mean_tilt_deg"]))
    return {"row": row, "result": result, "tilt": tilt, "numbers": numbers, "window": window}


def draw(runs: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for one, colour in zip(runs, ("C3", "C0"), strict=False):
        t, r = one["tilt"], one["result"]
        ax.plot(t.time, np.degrees(t.tilt), color=colour, label=f"seed {r['seed']}, e {r['e']:.3f}")
        ax.axvspan(r["contact_start"], r["contact_end"], color=colour, alpha=0.08)
    ax.axhline(0.0, color="grey", lw=0.6)
    ax.set_xlabel("time, R / c")
    ax.set_ylabel("tilt of the wall under the disk, degrees")
    ax.legend(fontsize=8)
    fig.tight_layout()
    write_figure(fig, path, 120)
    plt.close(fig)


def add_tilt_arguments(parser: argparse.ArgumentParser) -> None:
    """runner tilt's options."""
    parser.add_argument(
        "--tables",
        type=InPath(needs=("impacts.csv", "study.json")),
        default=None,
        help="a grazing study's tables: impacts.csv and study.json (default: docs/studies/grazing)",
    )
    parser.add_argument(
        "--gamma",
        type=ANGLE,
        default=None,
        help=f"one of the study's angles, {ANGLE.describe()} (default: the largest mean e's)",
    )
    parser.add_argument(
        "--dump-every",
        type=DUMP_EVERY,
        default=10,
        help=f"steps between dump frames, {DUMP_EVERY.describe()} (default: 10)",
    )
    where = parser.add_mutually_exclusive_group()
    where.add_argument(
        "--docs", action="store_true", help="write the page into docs/wall_tilt/ (the committed)"
    )
    where.add_argument(
        "--out",
        type=OutFolder(lammps=False),
        default=None,
        help="write the page, figure and series into this folder (default: runs/wall_tilt/)",
    )


def wall_tilt(args: argparse.Namespace) -> Path:
    """Run the two impacts again and write the page; returns its path.

    Raises
    ------
    ground.errors.InputError
        If the tables are missing or --gamma is not one of their angles.
    """
    # the default is checked here; a given folder was by its type
    tables = Path(args.tables) if args.tables else study_docs("grazing")
    if not (tables / "impacts.csv").is_file() or not (tables / "study.json").is_file():
        raise InputError(f"--tables: {tables} holds no study's impacts.csv and study.json")
    try:
        with (tables / "impacts.csv").open() as handle:
            rows = list(csv.DictReader(handle))
        if not rows:
            raise ValueError("no impact in it")
        for line, row in enumerate(rows, start=2):
            if not all(np.isfinite(float(row[k] or "nan")) for k in ("seed", "gamma_deg", "e")):
                raise ValueError(f"line {line}: seed, gamma_deg or e not a finite number")
    except (OSError, ValueError, KeyError, TypeError, csv.Error) as error:
        raise InputError(
            f"--tables: {tables / 'impacts.csv'} is not a study's table ({error}); "
            "give a grazing study's tables (runner study grazing)"
        ) from None
    gamma, high, low = pick(rows, args.gamma)
    study = Study.from_json(tables / "study.json")
    if args.docs:  # the tilt's own committed page (make's target), through the gate
        grant(ROOT / "docs" / "wall_tilt")
    folder = args.out or (ROOT / "docs" if args.docs else runs_folder()) / "wall_tilt"
    make_folder(folder)
    name = f"wall_tilt_{tables.name}"
    work = runs_folder() / "wall_tilt" / "runs" / name
    runs = [run(study, row, work / f"s{row['seed']}", args.dump_every) for row in (high, low)]
    header = [
        "seed",
        "e (table)",
        "e (rerun)",
        "largest tilt in contact, deg",
        "force-weighted tilt, deg",
        "tan(gamma) tan(tilt)",
        "e against the tilted normal",
    ]
    table = [
        [
            one["row"]["seed"],
            f"{float(one['row']['e']):.4f}",
            f"{one['result']['e']:.4f}",
            f"{one['numbers']['largest_tilt_deg']:.2f}",
            f"{one['numbers']['mean_tilt_deg']:+.3f}",
            f"{one['numbers']['approach_share']:+.3f}",
            f"{one['numbers']['e_tilted']:.4f}",
        ]
        for one in runs
    ]
    figure = folder / f"{name}.png"
    draw(runs, figure)
    series = {
        f"s{one['row']['seed']}": {
            "time": one["tilt"].time.tolist(),
            "tilt_deg": np.degrees(one["tilt"].tilt).round(5).tolist(),
        }
        for one in runs
    }
    write_text(folder / f"{name}.json", json.dumps(series) + "\n")
    body = (
        f"Study `{study.name}` (tables `{shown_path(tables)}`), gamma = {gamma:g} degrees, the "
        "angle of the largest mean e unless --gamma; the impacts of largest and smallest e "
        "there, run again on the study's scenes and settings with a dump every "
        f"{args.dump_every} steps. Tilt: the slope of the wall surface points' displacement "
        "within 0.5 R of the disk centre's x (analysis/impact/tilt.py), positive where the surface "
        "rises in +x, ahead of the disk. Force-weighted: its mean over the contact weighted "
        "by the disk's wall-normal contact force. tan(gamma) tan(tilt): the share of the "
        "normal approach speed that the tilt adds from the tangential motion (the disk meets "
        "the tilted surface at v_n cos(tilt) + v_t sin(tilt)), which a rebound along the "
        "tilted normal returns as wall-normal speed; the letter's mechanism needs it "
        "comparable to 1 - e, or to e - 1 where e passes 1. e against the tilted normal: the "
        "rebound's e in the frame of the force-weighted tilt; where the tilt explains e > 1, "
        "this one is below 1.\n\n"
        + markdown_table(header, table)
        + f"\n\n![tilt against time]({figure.name})\n\n*The tilt under the disk against time; "
        "shaded: each impact's contact. Series: "
        f"`{name}.json`.*\n"
    )
    command = f"python -m runner tilt --tables {shown_path(tables)} --dump-every {args.dump_every}"
    command += f" --gamma {gamma:g}" if args.gamma is not None else ""
    command += " --docs" if args.docs else ""
    path = folder / f"{name}.md"
    write_text(
        path,
        f"# The tilt of the wall under the disk\n\nGenerated by `{command}` on {machine()}."
        f"\n\n{body}\n",
    )
    return path
