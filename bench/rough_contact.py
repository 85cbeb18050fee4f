"""What sets the resolution a rough contact needs (issue 46, first question).

Runs impacts of one reading at several disk resolutions and seeds, and
measures from each run's dump what the result.json does not hold:

- the contact force on every disk surface point (``a V0 exp(-a l)``, l its
  distance to the wall's surface polyline, as pair polyline/exp computes it):
  how many points carry the force at its peak (the participation number
  (sum F)^2 / sum F^2), how many separate patches, and their widths in R;
- where the disk's vibration sits in wavenumber at the last frame: its
  velocity field, rigid motion removed, averaged over square cells of side s;
  the kinetic energy left in the cell means is what a lattice of spacing
  about s could hold, the rest lives at shorter wavelengths.

- the triangles of the disk's spring network that turn over (signed area
  of opposite sign to the start's) and that fall below half their area at
  rest, the most at one frame, and the largest compression of a disk spring
  before any turned; with the barrier (--area-floor), result.json's count of
  triangles inside it (every step) and the smallest area ratio.

One row per impact goes to runs.csv in runs/bench/rough_contact/ (with
--docs in docs/rough_contact/; resumable: rows already there are skipped; a
failed impact gets a row with its error); each impact's folder and dump are
removed after its analysis. --summary writes summary.csv (means and t-based
errors per reading and N), summary_link.csv (Spearman of the disk's vibration
against the turned area) and summary_steps.csv (the per-seed steps Q(N) -
Q(N/2) with t-based errors). The commands of the committed tables:
docs/rough_contact.md.
"""

from __future__ import annotations

import argparse
import csv
import json
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.spatial import Delaunay
from scipy.stats import spearmanr

from bench.common import RUNS, bench_parser, paired_steps, refuse
from builder.scene import N_DISK, PAPER, SceneSpec
from ground.checks import OutFolder, Range
from ground.errors import InputError
from ground.launch import LammpsError
from ground.paths import ROOT
from runner.impact import run_impact
from runner.options import RunOptions

SURFACE, INTERIOR = 1, 2  # LAMMPS atom types of the disk (scene.json atom_types)
WALL_SURFACE = 3
FORCE_FLOOR = 1e-3  # a point carries force if it has this share of the largest
REFERENCE_SPACING = 0.06733868435442993  # the 800-point disk's spacing, R
CELLS = (1.0, 2.0, 4.0)  # cell sides in 800-point spacings
DUMP_INTERVAL = 0.2  # R/c between dump frames, about
COLUMNS = (
    "label n_disk seed gamma_deg vn roughness roughness_length h e beta vibration_disk "
    "vibration_wall contact_time touches energy_drift f_peak n_eff_peak n_touch_peak patches_peak "
    "patch_width_peak patch_points_peak n_eff_mean inverted_max inverted_surface "
    "first_inversion_step max_compression ke_vib "
    + " ".join(f"coarse_{c:g}" for c in CELLS)
    + " area_floor below_half_max in_barrier_max area_ratio_min error"
).split()


def read_dump(path: Path):
    """Frames of a LAMMPS text dump (id mol type mass x y z vx vy vz), sorted by id."""
    text = path.read_text().split("ITEM: TIMESTEP\n")[1:]
    for block in text:
        lines = block.split("\n", 8)
        step = int(lines[0])
        data = np.array(lines[8].split(), dtype=float).reshape(-1, 10)
        yield step, data


def contact_forces(points, polyline, a, v0, cutoff):
    """Force magnitude on each point from the polyline (closest segment or vertex)."""
    start, end = polyline[:-1], polyline[1:]
    seg = end - start
    ss = (seg**2).sum(axis=1)
    near = np.abs(points[:, None, 0] - start[None, :, 0]) < 2.0 * cutoff + np.sqrt(ss)[None, :]
    force = np.zeros(len(points))
    rows = np.nonzero(near.any(axis=1))[0]
    for i in rows:
        cols = np.nonzero(near[i])[0]
        u = points[i] - start[cols]
        t = np.clip((u * seg[cols]).sum(axis=1) / ss[cols], 0.0, 1.0)
        d = np.sqrt(((u - t[:, None] * seg[cols]) ** 2).sum(axis=1)).min()
        if d < cutoff:
            force[i] = a * v0 * np.exp(-a * d)
    return force


def patches(force, arc):
    """Separate runs of force-carrying points around the surface row: their
    number and their widths (points, and F-weighted sd of arc position, in R)."""
    carrying = force > FORCE_FLOOR * force.max()
    n = len(force)
    if carrying.all():
        return 1, [n], [np.nan]
    start = np.nonzero(~carrying)[0][0]  # walk the ring from a free point
    order = np.roll(np.arange(n), -start)
    runs, current = [], []
    for i in order:
        if carrying[i]:
            current.append(i)
        elif current:
            runs.append(current)
            current = []
    if current:
        runs.append(current)
    widths = []
    for run in runs:
        s = np.arange(len(run)) * arc
        w = force[run]
        mean = (w * s).sum() / w.sum()
        widths.append(float(np.sqrt((w * (s - mean) ** 2).sum() / w.sum())))
    return len(runs), [len(r) for r in runs], widths


def coarse_fractions(pos, vel, sides):
    """Share of the vibrational kinetic energy that cell means of side s keep
    (4 grid offsets averaged), for each s."""
    total = (vel**2).sum()
    shares = []
    for side in sides:
        kept = []
        for offset in ((0, 0), (0.5, 0), (0, 0.5), (0.5, 0.5)):
            cell = np.floor(pos / side + np.array(offset)).astype(int)
            _, index, counts = np.unique(cell, axis=0, return_inverse=True, return_counts=True)
            index = index.ravel()
            sums = np.zeros((len(counts), 2))
            np.add.at(sums, index, vel)
            kept.append(((sums**2).sum(axis=1) / counts).sum() / total)
        shares.append(float(np.mean(kept)))
    return shares


def springs_of(folder: Path) -> tuple[np.ndarray, np.ndarray]:
    """Every spring's atom rows (0-based, the dump sorted by id) and natural length."""
    text = (folder / "scene.data").read_text()
    coeffs = text.split("Bond Coeffs", 1)[1].split("\n", 2)[2].split("\n\n", 1)[0]
    natural = np.array(coeffs.split(), dtype=float).reshape(-1, 4)[:, 1]
    bonds = text.split("Bonds\n", 1)[1].split("\nAngle Coeffs", 1)[0]  # --area-floor's after
    bonds = np.array(bonds.split(), dtype=int).reshape(-1, 4)
    return bonds[:, 2:] - 1, natural[bonds[:, 1] - 1]


def disk_triangles(folder: Path, positions: np.ndarray, disk: np.ndarray) -> np.ndarray:
    """The disk's triangles whose three edges are springs (atom rows, 0-based)."""
    bonds = springs_of(folder)[0]
    springs = {tuple(sorted(b)) for b in bonds.tolist()}
    rows = np.nonzero(disk)[0]
    simplices = rows[Delaunay(positions[rows]).simplices]
    keep = [
        all(tuple(sorted((t[i], t[(i + 1) % 3]))) in springs for i in range(3))
        for t in simplices.tolist()
    ]
    return simplices[np.array(keep)]


def signed_areas(positions: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    a, b, c = (positions[triangles[:, i]] for i in range(3))
    return (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])


def analyse(folder: Path) -> dict:
    """Contact patches over the run and the last frame's vibration spectrum."""
    scene = json.loads((folder / "scene.json").read_text())
    lmp = dict(
        line.split()[1:4:2]
        for line in (folder / "scene.lmp").read_text().splitlines()
        if line.startswith("variable")
    )
    a, v0, cutoff = float(lmp["contact_a"]), float(lmp["contact_V0"]), float(lmp["cutoff"])
    best, n_effs, weights, last = None, [], [], None
    triangles, sign, inverted, first_inversion, at_surface = None, None, 0, np.nan, 0
    below_half = 0  # the most triangles at once below half their area at rest
    for _, data in read_dump(folder / "dump.lammpstrj"):
        last = data
        types = data[:, 2]
        if triangles is None:
            triangles = disk_triangles(folder, data[:, 4:6], data[:, 1] == 1)
            rest = signed_areas(data[:, 4:6], triangles)
            sign = np.sign(rest)
            pairs, natural = springs_of(folder)
            in_disk = data[pairs[:, 0], 1] == 1
            pairs, natural = pairs[in_disk], natural[in_disk]
            compression = 0.0
        length = np.linalg.norm(data[pairs[:, 0], 4:6] - data[pairs[:, 1], 4:6], axis=1)
        areas = signed_areas(data[:, 4:6], triangles)
        turned = np.sign(areas) != sign
        below_half = max(below_half, int((areas / rest < 0.5).sum()))
        flipped = int(turned.sum())
        at_surface = max(at_surface, int((types[triangles[turned]] == SURFACE).any(axis=1).sum()))
        if flipped and not inverted:
            first_inversion = _
        inverted = max(inverted, flipped)
        if not inverted:  # the largest strain the lattice met while whole
            compression = max(compression, float((1.0 - length / natural).max()))
        wall = data[types == WALL_SURFACE]
        wall = wall[np.argsort(wall[:, 0])]
        surf = data[types == SURFACE]
        force = contact_forces(surf[:, 4:6], wall[:, 4:6], a, v0, cutoff)
        total = force.sum()
        if total == 0.0:
            continue
        n_effs.append(total**2 / (force**2).sum())
        weights.append(total)
        if best is None or total > best[0]:
            best = (total, force, surf)
    row = {"n_eff_mean": float(np.average(n_effs, weights=weights)) if n_effs else np.nan}
    row["inverted_max"] = inverted
    row["below_half_max"] = below_half
    row["inverted_surface"] = at_surface
    row["max_compression"] = compression
    row["first_inversion_step"] = first_inversion
    if best is not None:
        total, force, surf = best
        centre = surf[:, 4:6].mean(axis=0)
        angle = np.arctan2(surf[:, 5] - centre[1], surf[:, 4] - centre[0])
        order = np.argsort(angle)
        arc = 2.0 * np.pi / len(surf)
        count, points, widths = patches(force[order], arc)
        row.update(
            f_peak=float(total),
            n_eff_peak=float(total**2 / (force**2).sum()),
            n_touch_peak=int((force > FORCE_FLOOR * force.max()).sum()),
            patches_peak=count,
            patch_width_peak=float(np.nanmean(widths)),
            patch_points_peak=float(np.mean(points)),
        )
    disk = last[last[:, 1] == 1]
    m, pos, vel = disk[:, 3], disk[:, 4:6], disk[:, 7:9]
    com = (m[:, None] * pos).sum(axis=0) / m.sum()
    vcm = (m[:, None] * vel).sum(axis=0) / m.sum()
    r, v = pos - com, vel - vcm
    lz = (m * (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0])).sum()
    omega = lz / (m * (r**2).sum(axis=1)).sum()
    vib = v - omega * np.stack([-r[:, 1], r[:, 0]], axis=1)
    row["ke_vib"] = float(0.5 * (m[:, None] * vib**2).sum())
    sides = [c * REFERENCE_SPACING for c in CELLS]
    for c, share in zip(CELLS, coarse_fractions(pos, vib, sides)):
        row[f"coarse_{c:g}"] = share
    row["h"] = float(scene["disk_spacing"])
    return row


SUMMARY = (
    "e",
    "beta",
    "vibration_disk",
    "below_half_max",
    "in_barrier_max",
    "area_ratio_min",
    "coarse_1",
    "inverted_max",
    "max_compression",
    "n_eff_peak",
    "patch_width_peak",
)


def summarise(table: Path, out: Path) -> None:
    """Per reading and resolution: means over seeds with t-based standard errors,
    and the share of impacts in which a triangle of the disk turned over."""
    with table.open() as handle:
        every = list(csv.DictReader(handle))
    runs = [r for r in every if not r.get("error")]  # failed impacts: counted, not averaged
    groups: dict[tuple[str, int], list[dict]] = {}
    for run in runs:
        groups.setdefault((run["label"], int(run["n_disk"])), []).append(run)
    rows = []
    for (label, n), group in groups.items():
        failed = [
            r for r in every if r["label"] == label and int(r["n_disk"]) == n and r.get("error")
        ]
        row = {"label": label, "n_disk": n, "seeds": len(group), "failed": len(failed)}
        row["h"] = f"{float(group[0]['h']):.4g}"
        for name in SUMMARY:
            values = np.array([float(r[name] or "nan") for r in group])
            row[name] = f"{values.mean():.4g}"
            row[f"{name}_se"] = f"{values.std(ddof=1) / np.sqrt(len(values)):.2g}"
        count = np.array([float(r["inverted_max"] or 0) for r in group])
        row["inverted_share"] = f"{(count > 0).mean():.3g}"
        # the turned-over triangles' area, R^2: count times a triangle's, sqrt(3) h^2 / 4
        area = count * np.sqrt(3.0) / 4.0 * float(group[0]["h"]) ** 2
        row["turned_area"] = f"{area.mean():.3g}"
        row["turned_area_se"] = f"{area.std(ddof=1) / np.sqrt(len(area)):.2g}"
        lost = np.array([float(r["vibration_disk"]) + float(r["vibration_wall"]) for r in group])
        row["vibration_both"] = f"{lost.mean():.4g}"
        row["vibration_both_se"] = f"{lost.std(ddof=1) / np.sqrt(len(lost)):.2g}"
        vib = np.array([float(r["vibration_disk"]) for r in group])
        row["vibration_disk_unturned"] = (
            f"{vib[count == 0].mean():.3g}" if (count == 0).any() else ""
        )
        rows.append(row)
    with out.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    links = []
    for label in dict.fromkeys(r["label"] for r in runs):
        group = [r for r in runs if r["label"] == label]
        area = [float(r["inverted_max"] or 0) * float(r["h"]) ** 2 for r in group]
        vib = [float(r["vibration_disk"]) for r in group]
        rho, p = spearmanr(vib, area) if len(set(area)) > 1 else (np.nan, np.nan)
        links.append(
            {
                "label": label,
                "impacts": len(group),
                "spearman_vibration_turned_area": f"{rho:.3g}",
                "p": f"{p:.2g}",
            }
        )
    with out.with_name(out.stem + "_link.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, list(links[0]))
        writer.writeheader()
        writer.writerows(links)
    steps = paired_steps(runs, ("e", "beta", "vibration_disk"))
    with out.with_name(out.stem + "_steps.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, list(steps[0]))
        writer.writeheader()
        writer.writerows(steps)
    print(links)
    shown = (
        "label",
        "n_disk",
        "seeds",
        "e",
        "e_se",
        "vibration_disk",
        "coarse_1",
        "inverted_share",
        "inverted_max",
        "max_compression",
        "patch_width_peak",
    )
    print("  ".join(shown))
    for row in rows:
        print("  ".join(str(row[k]) for k in shown))


# The readings measured (docs/rough_contact.md): scene fields besides n_disk and seed.
# "p": one surface per seed at every N, the contact's lengths fixed in R;
# "floor": the barrier against turned-over triangles (--area-floor).
PROFILE = {
    "roughness_length": 0.2,
    "roughness_profile": "continuous",
    "contact_scaling": "physical",
}
READINGS = {
    "L0.2p": PROFILE,
    "L0.2p_floor0.5": {**PROFILE, "area_floor": 0.5},
    "L0.2p_floor0.3": {**PROFILE, "area_floor": 0.3},
    "smooth_vn0.25_floor0.5": {"roughness": 0.0, "vn": 0.25, "area_floor": 0.5},
    "smooth_floor0.5": {"roughness": 0.0, "area_floor": 0.5},
    "L0.2": {"roughness_length": 0.2},
    "smooth": {"roughness": 0.0},
    "L0.2_vn0.05": {"roughness_length": 0.2, "vn": 0.05},
    "smooth_vn0.25": {"roughness": 0.0, "vn": 0.25},
    "L0.2_triangular": {"roughness_length": 0.2, "lattice": "triangular"},
}
GAMMA_DEG = 45.0
SEEDS = Range(1, 64, integer=True)  # seeds 1 to this
TABLES = ROOT / "docs" / "rough_contact"


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    for action in parser._actions:
        if action.dest == "docs":
            action.help = (
                "write the tables into docs/rough_contact/; default: runs/bench/rough_contact/"
            )
    parser.add_argument(
        "--reading", choices=sorted(READINGS), help="the scene to run (required to run impacts)"
    )
    parser.add_argument(
        "--n-disk",
        type=N_DISK,
        nargs="+",
        default=[800, 1600, 3200, 6400],
        help=f"disk resolutions, each {N_DISK.describe()} (default: 800 1600 3200 6400)",
    )
    parser.add_argument(
        "--seeds", type=SEEDS, default=8, help=f"seeds 1 to this, {SEEDS.describe()} (default: 8)"
    )
    parser.add_argument(
        "--scratch",
        type=OutFolder(),
        default=None,
        help="where the impacts run, each folder removed after its analysis "
        "(default: runs/bench/rough_contact_scratch)",
    )
    parser.add_argument(
        "--summary", action="store_true", help="only summarise runs.csv into summary.csv"
    )
    return parser


def widen(table: Path) -> None:
    """Rewrite a runs.csv written before a column existed with every column
    (the new ones empty), so that rows can be appended to it."""
    if not table.exists():
        return
    with table.open() as handle:
        reader = csv.DictReader(handle)
        if reader.fieldnames == list(COLUMNS):
            return
        rows = list(reader)
    with table.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, COLUMNS)
        writer.writeheader()
        writer.writerows(rows)


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    tables = TABLES if args.docs else RUNS / "rough_contact"
    table = tables / "runs.csv"
    try:
        if args.summary and args.reading:
            raise InputError("--reading runs impacts; --summary only summarises the table")
        if not args.summary and not args.reading:
            raise InputError("--reading is required to run impacts (or give --summary)")
        if args.summary and not table.is_file():
            raise InputError(f"--summary: no {table} to summarise")
    except InputError as error:
        return refuse(__file__, error)
    if args.summary:
        summarise(table, tables / "summary.csv")
        return 0
    scratch = args.scratch or RUNS / "rough_contact_scratch"
    done = set()
    if table.exists():
        with table.open() as handle:
            done = {(r["label"], int(r["n_disk"]), int(r["seed"])) for r in csv.DictReader(handle)}
    tables.mkdir(parents=True, exist_ok=True)
    fields = {"roughness": 0.03, "gamma_deg": GAMMA_DEG, **READINGS[args.reading]}
    for n in args.n_disk:
        for seed in range(1, args.seeds + 1):
            if (args.reading, n, seed) in done:
                continue
            spec = SceneSpec(n_disk=n, seed=seed, **{**PAPER, **fields})
            options = RunOptions().for_scene(spec)
            check = options.check_steps
            divisors = [k for k in range(1, check + 1) if check % k == 0]
            every = min(divisors, key=lambda k: abs(k * options.step - DUMP_INTERVAL))
            folder = scratch / f"{args.reading}_n{n}_s{seed}"
            row = {
                "label": args.reading,
                "n_disk": n,
                "seed": seed,
                "vn": spec.vn,
                "roughness": spec.roughness,
                "roughness_length": spec.roughness_length,
                "area_floor": spec.area_floor,
            }
            try:
                result = run_impact(spec, folder, replace(options, dump_every=every))
            except LammpsError as error:  # a row saying why, and on to the next
                row["error"] = str(error).splitlines()[0][:300]
            else:
                row.update({k: result.get(k) for k in COLUMNS if k in result})
                row.update(analyse(folder))
            shutil.rmtree(folder, ignore_errors=True)
            widen(table)
            new = not table.exists()
            with table.open("a", newline="") as handle:
                writer = csv.DictWriter(handle, COLUMNS, extrasaction="ignore")
                if new:
                    writer.writeheader()
                writer.writerow(
                    {k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()}
                )
            shown = ("e", "vibration_disk", "inverted_max", "in_barrier_max", "error")
            print(n, seed, {k: row.get(k) for k in shown}, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
