"""The binary page's comparison of two disks with the same disks on the wall
(analysis.binary_comparison's numbers): its section ``wall_comparison``,
its figures and its per-angle table comparison.csv beside the page. The
prose: pages/templates/binary.md.j2."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis import binary_comparison
from analysis.binary_comparison import DIFFERENT, SAME, THIS_STUDY
from analysis.statistics.estimates import CHI2_LIMIT
from analysis.table import rounded, write_csv
from ground.gate import write_figure

from .render import macro


def draw(numbers: dict, folder: Path | str, name: str) -> None:
    """e and beta against cot gamma, two disks (filled) beside the wall study
    ``name`` (open): binary_e_<name>.png, binary_beta_<name>.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for q, label in (("e", "e"), ("beta", "beta")):
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        ax.set_xscale("log")
        ax.set_xlabel("cot gamma (mean of the measured)")
        ax.set_ylabel(label)
        for colour, (lattice, entry) in zip(("C0", "C1", "C2", "C3"), numbers["lattices"].items()):
            for target, face in (("disk", colour), ("wall", "none")):
                x = np.asarray(entry[f"cot_gamma_{target}"])
                keep = x > 0
                ax.errorbar(
                    x[keep],
                    np.asarray(entry[f"{q}_{target}"])[keep],
                    yerr=np.asarray(entry[f"{q}_{target}_error"])[keep],
                    fmt="o" if target == "disk" else "s",
                    color=colour,
                    mfc=face,
                    capsize=2,
                    label=f"{lattice}, on {'a disk' if target == 'disk' else 'the wall'}",
                )
        ax.legend(fontsize=8)
        fig.tight_layout()
        write_figure(fig, folder / f"binary_{q}_{name}.png", 110)
        plt.close(fig)


TABLE = "comparison.csv"
# comparison.csv: a row per wall study, lattice and nominal angle; e, beta
# and their difference (blank where withheld) with their errors and verdicts,
# and each disk's vibration.
COMPARED = tuple(f"{q}_{k}" for q in ("e", "beta") for k in ("disk", "wall", "difference"))
VIBRATIONS = (
    "vibration_disk_disk",
    "vibration_wall_disk",
    "vibration_disk_wall",
    "vibration_wall_wall",
)
COLUMNS = (
    "wall",
    "lattice",
    "gamma_deg",
    "cot_gamma_disk",
    "cot_gamma_disk_error",
    *(f"{key}{s}" for key in COMPARED for s in ("", "_error")),
    "e_verdict",
    "beta_verdict",
    *VIBRATIONS,
)


def rows(by_wall: dict[str, dict], shown: dict[str, dict]) -> list[dict]:
    """comparison.csv's rows: per wall study, lattice and angle."""
    out = []
    for name, numbers in by_wall.items():
        for lattice, entry in numbers["lattices"].items():
            for j, gamma in enumerate(entry["gamma_deg"]):
                angle = shown[name][lattice]["angles"][j]
                row = {"wall": name, "lattice": lattice, "gamma_deg": gamma}
                for key in ("cot_gamma_disk", "cot_gamma_disk_error", *VIBRATIONS):
                    row[key] = entry[key][j]
                for key in COMPARED:
                    kept = angle["kept"][key]
                    row[key] = entry[key][j] if kept else ""
                    row[f"{key}_error"] = entry[f"{key}_error"][j] if kept else ""
                for q in ("e", "beta"):
                    row[f"{q}_verdict"] = angle["verdict"][q]
                out.append(rounded(row))
    return out


def section(
    by_wall: dict[str, dict], figure_dir: str, checks: dict | None = None, folder: Path = Path(".")
) -> str:
    """The page's section (Markdown): for each wall study, the comparison's
    counts, fits and figures, and per angle comparison.csv in ``folder``; e
    and beta withheld where the normals' check (``checks``,
    analysis.binary_comparison.normal_checks) finds them not robust."""
    by_wall = {name: numbers for name, numbers in by_wall.items() if numbers}
    if not by_wall:
        return ""
    checks = checks or {}
    shown = {
        name: {
            lattice: binary_comparison.shown(
                entry,
                lattice,
                {
                    "disk": checks.get(THIS_STUDY),
                    "wall": checks.get(f"the wall, docs/studies/{name}"),
                },
            )
            for lattice, entry in numbers["lattices"].items()
        }
        for name, numbers in by_wall.items()
    }
    aim = binary_comparison.aim(next(iter(by_wall.values())))
    write_csv(rows(by_wall, shown), Path(folder) / TABLE, COLUMNS)
    return macro(
        "binary.md.j2",
        "comparison",
        by_wall,
        figure_dir,
        shown,
        aim,
        CHI2_LIMIT,
        SAME,
        DIFFERENT,
        TABLE,
    )
