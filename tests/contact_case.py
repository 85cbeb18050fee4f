"""Configurations of points above a rough polyline, and their LAMMPS forces."""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np

from ground.launch import mpi_environment, mpi_launcher
from reference.contact import inside
from tests.helpers import ROOT

DECK = ROOT / "tests" / "decks" / "contact_forces.lmp"
A, V0, CUTOFF = 300.0, 150.0, 0.0673


def random_case(seed: int, n_vertices: int = 40, n_points: int = 60):
    """A rough polyline (spacing 0.067, roughness 0.03) and points above it,
    a few hundredths of a spacing to beyond the cutoff."""
    rng = np.random.default_rng(seed)
    x = np.arange(n_vertices) * 0.0673 - 0.0673 * (n_vertices - 1) / 2
    vertices = np.stack([x, 0.03 * rng.standard_normal(n_vertices)], axis=1)
    px = rng.uniform(x[2], x[-3], 4 * n_points)
    py = np.interp(px, x, vertices[:, 1]) + rng.uniform(-0.02, 0.09, len(px))
    points = np.stack([px, py], axis=1)
    from reference.contact import closest_features

    gap = np.linalg.norm(closest_features(points, vertices)[2], axis=1)
    keep = ~inside(points, vertices) & (gap > 0.004)
    return vertices, points[keep][:n_points]


def write_data(path: Path, vertices: np.ndarray, points: np.ndarray) -> Path:
    """Vertices get tags 1..n (type 3), points the following tags (type 1)."""
    xy = np.concatenate([vertices, points])
    types = np.concatenate([np.full(len(vertices), 3), np.full(len(points), 1)])
    lo, hi = (xy.min(axis=0) - 0.5).tolist(), (xy.max(axis=0) + 0.5).tolist()
    lines = [
        f"contact test case\n\n{len(xy)} atoms\n0 bonds\n3 atom types\n1 bond types\n\n",
        f"{lo[0]!r} {hi[0]!r} xlo xhi\n{lo[1]!r} {hi[1]!r} ylo yhi\n-0.5 0.5 zlo zhi\n\n",
        "Masses\n\n1 1.0\n2 1.0\n3 1.0\n\nAtoms # bond\n\n",
    ]
    lines += [
        f"{i + 1} 1 {t} {x!r} {y!r} 0.0\n"
        for i, (t, (x, y)) in enumerate(zip(types.tolist(), xy.tolist()))
    ]
    path.write_text("".join(lines))
    return path


def lammps_forces(
    tmp: Path, vertices, points, rule="lever", nprocs=1, command=None, env=None, extra=()
) -> tuple[float, np.ndarray, np.ndarray]:
    """Energy and forces (on vertices, on points) from LAMMPS, run as a program."""
    data = write_data(tmp / "case.data", vertices, points)
    out = tmp / f"forces_{rule}_{nprocs}.dump"
    launcher = mpi_launcher(nprocs)
    command = command or ["lmp"]
    log = tmp / "log.lammps"
    args = [
        "-in",
        str(DECK),
        "-log",
        str(log),
        "-screen",
        "none",
        "-nocite",
        "-var",
        "data",
        str(data),
        "-var",
        "out",
        str(out),
        "-var",
        "nvert",
        str(len(vertices)),
        "-var",
        "rule",
        rule,
        *extra,
    ]
    proc = subprocess.run(
        launcher + command + args,
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**mpi_environment(), **(env or {})},
    )
    if proc.returncode != 0:
        errors = (
            [line for line in log.read_text().splitlines() if line.startswith("ERROR")]
            if log.exists()
            else []
        )
        raise RuntimeError(errors[0] if errors else proc.stdout[-2000:] + proc.stderr[-2000:])
    f = np.loadtxt(out, skiprows=9)[:, 1:]
    energy = float(Path(f"{out}.energy").read_text())
    return energy, f[: len(vertices)], f[len(vertices) :]


def lammps_virial(tmp: Path, vertices, points, rule="lever", nprocs=1, extra=()):
    """Forces (on vertices, on points) and the pair's virial (xx, yy, xy) as
    LAMMPS tallies it, globally (compute pressure) and summed over the atoms
    (compute stress/atom): the deck writes both beside the forces."""
    _, on_vertices, on_points = lammps_forces(tmp, vertices, points, rule, nprocs, extra=extra)
    path = tmp / f"forces_{rule}_{nprocs}.dump.virial"
    values = np.array(path.read_text().split(), dtype=float)
    return on_vertices, on_points, values[:3], values[3:]
