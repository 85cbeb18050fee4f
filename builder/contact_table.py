"""The pair variant of the contact as a LAMMPS ``pair_style table`` file.

E(r) = V0 exp(-a r) between a disk surface point and a wall surface point at
distance r (docs/model.md section 2, the design card). The table starts at a small
inner distance: a pair closer than that means a disk point has gone into the
wall, and LAMMPS stops with "Pair distance < table inner cutoff".
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

KEYWORD = "EXP"
INNER = 1e-3  # in R: the force there is a V0 exp(-0.3), far beyond any real contact
OUTER = 1.0  # in R: any lattice spacing fits below it
POINTS = 20000  # file resolution; spline error ~ (a h)^4 / 384 ~ 1e-10 at a = 300


def table_name(a: float, v0: float) -> str:
    return f"exp_a{a:g}_V{v0:g}.table"


def table_text(a: float, v0: float, radius: float = 1.0, points: int = POINTS) -> str:
    r = np.linspace(INNER * radius, OUTER * radius, points)
    energy = v0 * np.exp(-a * r)
    force = a * energy
    header = (
        f"# Contact repulsion E = V0 exp(-a r), F = -dE/dr (docs/model.md section 2)\n"
        f"# a = {a!r} / length, V0 = {v0!r} energy\n\n"
        f"{KEYWORD}\nN {points} R {float(r[0])!r} {float(r[-1])!r}\n\n"
    )
    rows = "".join(
        f"{i} {ri!r} {ei!r} {fi!r}\n"
        for i, (ri, ei, fi) in enumerate(zip(r.tolist(), energy.tolist(), force.tolist()), start=1)
    )
    return header + rows


def ensure_table(folder: Path | str, a: float, v0: float, radius: float = 1.0) -> Path:
    """The table for (a, V0) in ``folder``, written atomically if it is missing."""
    folder = Path(folder)
    path = folder / table_name(a, v0)
    if path.exists():
        return path
    folder.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".table-")
    with os.fdopen(fd, "w") as handle:
        handle.write(table_text(a, v0, radius))
    os.replace(tmp, path)
    return path
