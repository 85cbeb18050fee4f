"""The materials table: which strips to stretch, and their results summarised."""

from __future__ import annotations

import json
import os
import tempfile
from concurrent.futures import ProcessPoolExecutor
from datetime import date
from pathlib import Path

import numpy as np

from builder.materials import (
    TABLE,
    square_bulk_modulus,
    square_poisson_ratio,
    square_ratio_for_poisson,
    square_shear_modulus,
    square_wave_speed_factor,
)
from builder.strips import StripSpec
from ground import gate
from ground.provenance import git_revision, lammps_program_version

from .stretch import Stretch, run_stretch

STUDY_POISSON = (0.1, 0.3)  # square lattices of the study, along their axes
RANDOM_STRIP = dict(length=120.0, width=40.0)


def strip_specs(random_seeds: int, square_ratios: list[float]) -> list[StripSpec]:
    specs = [StripSpec("random", seed=seed, **RANDOM_STRIP) for seed in range(1, random_seeds + 1)]
    # the triangular lattice at 45 degrees too: its isotropy, measured
    specs += [StripSpec("triangular", angle_deg=a) for a in (0.0, 45.0)]
    for ratio in square_ratios:
        specs += [StripSpec("square", k2_over_k1=ratio, angle_deg=a) for a in (0.0, 45.0)]
    return specs


def _stretch(job: tuple[StripSpec, str]) -> Stretch:
    spec, folder = job
    return run_stretch(spec, folder)


def stretch_all(specs: list[StripSpec], workers: int = 2) -> list[Stretch]:
    with tempfile.TemporaryDirectory() as tmp:
        jobs = [(spec, os.path.join(tmp, str(i))) for i, spec in enumerate(specs)]
        with ProcessPoolExecutor(workers) as pool:
            return list(pool.map(_stretch, jobs))


def theory(lattice: str, ratio: float | None, angle: float) -> dict:
    """Closed forms for a strip pulled at ``angle``; G is the shear modulus of
    the frame at 45 degrees to the pull (``Stretch.shear_modulus``)."""
    if lattice == "triangular":
        k = np.sqrt(3.0) / 4.0  # the Lame constants, both
        return {"c2": 1.0, "nu": 1.0 / 3.0, "E": 2.0 / np.sqrt(3.0), "G": k, "B": 2.0 * k}
    if lattice == "square":
        c2 = square_wave_speed_factor(ratio, angle)
        return {
            "c2": c2,
            "nu": square_poisson_ratio(ratio, angle),
            "E": c2,
            "G": square_shear_modulus(ratio, angle + 45.0),
            "B": square_bulk_modulus(ratio),
        }
    return {}


def summarise(results: list[Stretch]) -> list[dict]:
    """One entry per lattice, ratio and direction: means, SDs and SEs over strips."""
    groups: dict[tuple, list[Stretch]] = {}
    for r in results:
        ratio = r.spec.k2_over_k1 if r.spec.lattice == "square" else None
        groups.setdefault((r.spec.lattice, ratio, r.spec.angle_deg), []).append(r)
    entries = []
    for (lattice, ratio, angle), runs in groups.items():
        entry = {
            "lattice": lattice,
            "k2_over_k1": ratio,
            "angle_deg": angle,
            "samples": len(runs),
            "strip": [runs[0].spec.length, runs[0].spec.width],
        }
        for name, values in (
            ("c2", [r.c2 for r in runs]),
            ("nu", [r.nu for r in runs]),
            ("E", [r.e_modulus for r in runs]),
            ("density_d2", [r.inner_density for r in runs]),
            ("nu_gauge", [r.nu_gauge for r in runs]),
            ("c2_strip", [r.c2_strip for r in runs]),
            ("G", [r.shear_modulus for r in runs]),
            ("B", [r.bulk_modulus for r in runs]),
            ("G_over_B", [r.shear_modulus / r.bulk_modulus for r in runs]),
        ):
            values = np.array(values)
            sd = float(values.std(ddof=1)) if len(values) > 1 else 0.0
            entry[name] = float(values.mean())
            entry[f"{name}_sd"] = sd
            entry[f"{name}_se"] = sd / np.sqrt(len(values))
        entry["nonlinearity"] = max(r.nonlinearity for r in runs)
        entry["imbalance"] = max(r.imbalance for r in runs)
        entry["theory"] = theory(lattice, ratio, angle)
        entries.append(entry)
    return entries


def provenance() -> dict:
    return {
        "command": "make calibrate",
        "lammps": lammps_program_version(),
        "git_revision": git_revision(),
        "date": str(date.today()),
        "protocol": "5 steps of 2e-4 strain, critical viscous damping, settled over "
        "10 time constants of the slowest mode; quadratic fits",
    }


def calibrate(
    random_seeds: int = 12, extra_ratios: tuple[float, ...] = (), path: Path = TABLE
) -> dict:
    ratios = [square_ratio_for_poisson(nu) for nu in STUDY_POISSON] + list(extra_ratios)
    results = stretch_all(strip_specs(random_seeds, ratios))
    table = {**provenance(), "materials": summarise(results)}
    gate.write_text(path, json.dumps(table, indent=1) + "\n")
    return table


def anisotropy(materials: list[dict]) -> list[dict]:
    """Shear and bulk moduli of each lattice along its axes and at 45 degrees.

    A strip pulled at angle a gives the shear modulus of the frame at a + 45
    (``Stretch.shear_modulus``): the 45-degree strip the axes' G, the axial
    strip the 45-degree frame's. A lattice pulled along its axes only (the
    random one, isotropic by construction: its sampler has no direction) has
    the one G in both frames.

    Parameters
    ----------
    materials : list of dict
        The entries of the materials table (``summarise``).

    Returns
    -------
    list of dict
        Per lattice and k2/k1: nu along the axes, G of the axes' frame and of
        the 45-degree frame, B, G/B of both, c at 45 degrees over c along the
        axes, the two G and B over rho c^2 (c along the axes, the study's unit),
        and G / (rho c^2) of an isotropic solid with the axial nu; ``theory``: the
        same from the closed forms; ``measured_45``: whether a 45-degree strip
        was pulled.
    """
    rows = []
    for axial in (e for e in materials if e["angle_deg"] == 0.0):
        diagonal = next(
            (
                e
                for e in materials
                if e["angle_deg"] == 45.0
                and e["lattice"] == axial["lattice"]
                and e["k2_over_k1"] == axial["k2_over_k1"]
            ),
            None,
        )

        def row(a: dict, d: dict) -> dict:
            return {
                "nu": a["nu"],
                "G_axes": d["G"],
                "G_45": a["G"],
                "B": a["B"],
                "B_45": d["B"],
                "G_over_B_axes": d["G"] / a["B"],
                "G_over_B_45": a["G"] / a["B"],
                "c_45_over_c": float(np.sqrt(d["c2"] / a["c2"])),
                "G_axes_over_rho_c2": d["G"] / a["E"],
                "G_45_over_rho_c2": a["G"] / a["E"],
                "B_over_rho_c2": a["B"] / a["E"],
                "isotropic_G_over_rho_c2": 1.0 / (2.0 * (1.0 + a["nu"])),
            }

        measured = row(axial, diagonal or axial)
        known = {}
        if axial["theory"] and diagonal is not None:
            known = row(axial["theory"], diagonal["theory"])
        if axial["samples"] > 1 and diagonal is None:  # per-strip errors where they exist
            measured["se"] = {key: axial[f"{key}_se"] for key in ("G", "B", "G_over_B")}
        rows.append(
            {
                "lattice": axial["lattice"],
                "k2_over_k1": axial["k2_over_k1"],
                "measured_45": diagonal is not None,
                **measured,
                "theory": known,
            }
        )
    return rows


def markdown(table: dict) -> str:
    """The tables for docs/calibration/materials.md."""

    def value(entry: dict, key: str) -> str:
        if entry["samples"] > 1:
            return f"{entry[key]:.4f} +- {entry[key + '_se']:.4f} (sd {entry[key + '_sd']:.4f})"
        return f"{entry[key]:.5f}"

    def known(entry: dict, key: str, digits: int) -> str:
        return f"{entry['theory'][key]:.{digits}f}" if key in entry["theory"] else "-"

    lines = [
        "| lattice | k2/k1 | pulled along | strips | c^2 (ka d^2/m) | nu | E (ka) "
        "| theory c^2 | theory nu | nonlinearity |",
        "|" + "---|" * 10,
    ]
    for e in table["materials"]:
        ratio = "-" if e["k2_over_k1"] is None else f"{e['k2_over_k1']:.4f}"
        direction = "x" if e["angle_deg"] == 0 else f"{e['angle_deg']:g} deg to the axes"
        lines.append(
            f"| {e['lattice']} | {ratio} | {direction} | {e['samples']} "
            f"| {value(e, 'c2')} | {value(e, 'nu')} | {value(e, 'E')} "
            f"| {known(e, 'c2', 5)} | {known(e, 'nu', 4)} | {e['nonlinearity']:.1e} |"
        )
    return "\n".join(lines) + "\n\n" + anisotropy_markdown(table["materials"])


def anisotropy_markdown(materials: list[dict]) -> str:
    """The shear and bulk moduli table (``anisotropy``): measured, (closed form)."""

    def cell(r: dict, key: str, digits: int = 4) -> str:
        text = f"{r[key]:.{digits}f}"
        short = key.replace("_axes", "").replace("_45", "")
        if "se" in r and short in r["se"]:
            text += f" +- {r['se'][short]:.{digits}f}"
        if key in r["theory"]:
            text += f" ({r['theory'][key]:.{digits}f})"
        return text

    lines = [
        "| lattice | k2/k1 | nu | G, axes (ka) | G, 45 deg (ka) | B (ka) | G/B, axes "
        "| G/B, 45 deg | c at 45 deg / c | G/(rho c^2), axes | G/(rho c^2), 45 deg "
        "| B/(rho c^2) | isotropic solid of this nu: G/(rho c^2) |",
        "|" + "---|" * 13,
    ]
    for r in anisotropy(materials):
        ratio = "-" if r["k2_over_k1"] is None else f"{r['k2_over_k1']:.4f}"
        name = r["lattice"] + ("" if r["measured_45"] else " (isotropic: one G)")
        lines.append(
            f"| {name} | {ratio} | {r['nu']:.4f} | {cell(r, 'G_axes')} | {cell(r, 'G_45')} "
            f"| {cell(r, 'B')} | {cell(r, 'G_over_B_axes')} | {cell(r, 'G_over_B_45')} "
            f"| {cell(r, 'c_45_over_c')} | {cell(r, 'G_axes_over_rho_c2')} "
            f"| {cell(r, 'G_45_over_rho_c2')} | {cell(r, 'B_over_rho_c2')} "
            f"| {r['isotropic_G_over_rho_c2']:.4f} |"
        )
    return "\n".join(lines)
