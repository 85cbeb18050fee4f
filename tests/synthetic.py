"""Synthetic impacts.csv rows with known answers, for the tests of the
statistics (the seed bootstrap, the fits, the claims table)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from analysis.table import COLUMNS, write_csv

# The study's angles: cot gamma from 10 down to 1/6, evenly in log.
PSI = np.geomspace(10.0, 1.0 / 6.0, 16)
GAMMA_DEG = np.round(np.degrees(np.arctan(1.0 / PSI)), 4)


def impact_rows(
    lattice: str,
    beta_of,
    e_of=lambda psi: 0.8,
    seeds: int = 40,
    offset_sd: float = 0.0,
    noise_sd: float = 0.02,
    inertia_ratio: float = 0.5,
    nu: float = 0.3,
    side_clearance: float = 3.0,
    ka_wall_over_disk: float = 1.0,
    rng_seed: int = 0,
) -> list[dict]:
    """One row per seed and angle: beta = beta_of(psi) + an offset that a seed
    shares across all its angles (sd ``offset_sd``) + independent noise (sd
    ``noise_sd``); e = e_of(psi) exactly.

    Parameters
    ----------
    lattice : str
        The study's name of the lattice.
    beta_of, e_of : callable
        The true beta and e at each cot gamma.
    seeds : int
        Seeds 1..seeds, each at every angle of ``PSI``.
    offset_sd, noise_sd : float
        The spread shared by a seed's angles and the spread of each impact.
    inertia_ratio, nu, side_clearance, ka_wall_over_disk : float
        The columns of the same names.
    rng_seed : int
        Seed of the random numbers.

    Returns
    -------
    list of dict
        Rows with every column of impacts.csv.
    """
    rng = np.random.default_rng(rng_seed)
    rows = []
    for seed in range(1, seeds + 1):
        offset = offset_sd * rng.standard_normal()
        for psi, gamma in zip(PSI, GAMMA_DEG):
            beta = float(beta_of(psi) + offset + noise_sd * rng.standard_normal())
            row = {name: "" for name in COLUMNS}
            row.update(
                study_lattice=lattice,
                lattice=lattice.split("_")[0],
                seed=seed,
                gamma_deg=float(gamma),
                cot_gamma=float(psi),
                vn=0.1,
                e=float(e_of(psi)),
                beta=beta,
                omega=flat_wall_spin(0.1 / psi, beta, inertia_ratio),
                vn_in_c=0.1,
                contact_time=10.0,
                touches=1,
                vibration_disk=0.05,
                vibration_wall=0.1,
                energy_drift=0.0,
                drift_exceeded=False,
                side_clearance=side_clearance,
                wall_width=8.0,
                n_wall_points=4000 + seed,
                ka_wall_over_disk=ka_wall_over_disk,
                disk_inertia_ratio=inertia_ratio,
                nu=nu,
                steps=1000,
                wall_seconds=1.0,
                dt=0.002,
            )
            rows.append(row)
    return rows


def flat_wall_spin(v_t: float, beta: float, inertia_ratio: float) -> float:
    """The spin after an impact on a flat wall (radius 1): the tangential
    impulse J_t turns the disk by J_t R / I0, so the contact point's velocity
    v_t' + w' = -beta v_t fixes w' (the impulse's normal is then the wall's,
    analysis.normal_check)."""
    v_out = v_t * (1.0 / inertia_ratio - beta) / (1.0 + 1.0 / inertia_ratio)
    return (v_out - v_t) / inertia_ratio


def write_tables(folder: Path, rows: list[dict], lattices: list[str], **study) -> Path:
    """impacts.csv, an empty failed.csv and study.json in ``folder``, as
    ``report_from_tables`` reads them."""
    folder.mkdir(parents=True, exist_ok=True)
    write_csv(rows, folder / "impacts.csv", COLUMNS)
    (folder / "failed.csv").write_text("lattice,seed,gamma,error\n")
    info = {
        "name": "synthetic",
        "lattices": lattices,
        "angles": len(PSI),
        "samples": max(int(r["seed"]) for r in rows),
        "vn": 0.1,
        "n_disk": 800,
        "options": {"dt": 0.002, "stop_rule": "predict", "max_drift": 0.05},
        **study,
    }
    (folder / "study.json").write_text(json.dumps(info))
    return folder
