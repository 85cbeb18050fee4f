"""Strips of each lattice for the material calibration (docs/model.md section 3).

A strip is L x W spacings, pulled along x by grips at its two ends, with free
long sides. Lengths are in units of the spacing d, and ka = m = 1: the
calibration is scale-free, and the wave speed it finds, c^2 = factor ka d^2/m,
gives the factor for any spacing.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ground.checks import Range
from ground.errors import InputError, require_choice

from . import bodies
from .lammps_data import network_data_text
from .scene import K2_OVER_K1
from .triangles import ANGLE_STYLE, barrier_triangles

GRIP = 1.5  # grips: the points within this many spacings of an end
TYPE_NAMES = {1: "strip", 2: "left grip", 3: "right grip"}


@dataclass
class StripSpec:
    lattice: str = "random"
    seed: int = 1
    k2_over_k1: float = 3.0 / 7.0  # square lattice
    angle_deg: float = 0.0  # lattice axes against the pulling direction
    length: float = 80.0  # spacings
    width: float = 24.0  # spacings
    kb_over_ka: float = 1e-3

    def validate(self) -> None:
        require_choice("lattice", self.lattice, bodies.LATTICES)
        K2_OVER_K1.check("k2_over_k1", self.k2_over_k1)
        Range(-180.0, 180.0).check("angle_deg", self.angle_deg)
        if not (self.length >= 4 * GRIP + 4 and self.width >= 4):
            raise InputError(
                f"length must be >= {4 * GRIP + 4} and width >= 4 spacings, "
                f"got {self.length} x {self.width}"
            )


def lattice_strip(
    lattice: str, length: float, width: float, angle_deg: float, k2_over_k1: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points, springs and stiffness of a triangular or square lattice strip.

    Springs come from the lattice: nearest neighbours (1), and for the square
    lattice both diagonals of every complete cell (k2/k1).
    """
    if lattice == "square":
        basis = np.array([[1.0, 0.0], [0.0, 1.0]])
        steps = {(1, 0): 1.0, (0, 1): 1.0}
    else:
        basis = np.array([[1.0, 0.0], [0.5, np.sqrt(3.0) / 2.0]])
        steps = {(1, 0): 1.0, (0, 1): 1.0, (-1, 1): 1.0}
    turn = np.radians(angle_deg)
    rotation = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    n = int(np.ceil(length + width)) + 2
    i, j = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1), indexing="ij")
    cells = np.stack([i.ravel(), j.ravel()], axis=1)
    points = cells @ basis @ rotation.T
    eps = 1e-9
    keep = (np.abs(points[:, 0]) <= length / 2 + eps) & (np.abs(points[:, 1]) <= width / 2 + eps)
    cells, points = cells[keep], points[keep]
    index = {tuple(c): k for k, c in enumerate(cells.tolist())}
    pairs, stiffness = [], []
    for (a, b), k in index.items():
        for (da, db), weight in steps.items():
            other = index.get((a + da, b + db))
            if other is not None:
                pairs.append((k, other))
                stiffness.append(weight)
        if lattice == "square":
            corners = [index.get((a + da, b + db)) for da, db in ((1, 0), (0, 1), (1, 1))]
            if None not in corners:
                pairs += [(k, corners[2]), (corners[0], corners[1])]
                stiffness += [k2_over_k1, k2_over_k1]
    return points, np.sort(np.array(pairs), axis=1), np.array(stiffness)


def drop_loose_points(points, pairs, stiffness):
    """Remove points held by fewer than two springs (corners of rotated lattices)."""
    while True:
        degree = np.bincount(pairs.ravel(), minlength=len(points))
        loose = degree < 2
        if not loose.any():
            return points, pairs, stiffness
        keep = ~loose[pairs].any(axis=1)
        new_index = np.cumsum(~loose) - 1
        points, pairs, stiffness = points[~loose], new_index[pairs[keep]], stiffness[keep]


def make_strip(spec: StripSpec) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points (centred at the origin), springs and their stiffness in units of ka.

    Parameters
    ----------
    spec : StripSpec
        The calibration strip: lattice, size, direction, seed.

    Returns
    -------
    points : numpy.ndarray
        (n, 2) positions.
    springs : numpy.ndarray
        (m, 2) point indices.
    stiffness : numpy.ndarray
        (m,) spring constants in units of ka.
    """
    spec.validate()
    if spec.lattice == "random":
        rng = np.random.default_rng(np.random.SeedSequence(spec.seed).spawn(1)[0])
        points, outline, _ = bodies.random_rectangle(rng, 1.0, spec.length, spec.width)
        points = points + [0.0, spec.width / 2.0]
        body = bodies.assemble(points, np.zeros(len(points), int), outline, outline, 1.0)
        return points, body.springs, body.stiffness
    points, pairs, stiffness = lattice_strip(
        spec.lattice, spec.length, spec.width, spec.angle_deg, spec.k2_over_k1
    )
    return drop_loose_points(points, pairs, stiffness)


def write_strip(spec: StripSpec, folder: Path | str, area_floor: float = 0.0) -> Path:
    """strip.data and strip.lmp (the gauge geometry for decks/stretch.lmp);
    with ``area_floor`` > 0 the barrier's angles too, k = ka (builder/triangles.py),
    to show that they leave the moduli as they are.

    Parameters
    ----------
    spec : StripSpec
        The calibration strip.
    folder : pathlib.Path or str
        Where the two files go; created if missing.

    Returns
    -------
    pathlib.Path
        ``folder``.
    """
    points, pairs, stiffness = make_strip(spec)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    half = spec.length / 2.0
    types = np.ones(len(points), int)
    types[points[:, 0] <= -half + GRIP] = 2
    types[points[:, 0] >= half - GRIP] = 3
    title = f"calibration strip: {asdict(spec)}"
    (folder / "strip.data").write_text(
        network_data_text(
            title,
            points,
            np.zeros_like(points),
            types,
            TYPE_NAMES,
            np.ones(len(points), int),
            pairs,
            stiffness,
            spec.kb_over_ka,
            "class2",
            pad=1.0,
            angles=barrier_triangles(points, pairs, [(np.arange(len(points)), 1.0)], area_floor)
            if area_floor > 0.0
            else None,
        )
    )
    # Gauges in the middle third, away from the grips and the free edges.
    (folder / "strip.lmp").write_text(
        "# Strip geometry written by the builder (spacings)\n"
        f"variable gauge_x   index {spec.length / 6.0!r}\n"
        f"variable band      index 1.5\n"
        f"variable inner_y   index {spec.width / 4.0!r}\n"
        f"variable edge_y    index {spec.width / 2.0 - 1.5!r}\n"
        f"variable length    index {spec.length!r}\n"
        + (f"variable angles    index {ANGLE_STYLE}\n" if area_floor > 0.0 else "")
    )
    return folder
