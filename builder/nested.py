"""Nested interiors (issue 46's multilevel estimate): the Poisson-disk sample
of a finer level grown from the coarser level's points.

scipy's sampler (Bridson's algorithm) grows a sample from an active pool of
points, keeping every new point at least its radius from all others. A
sampler whose pool and grid start with the coarse sample's points grows the
finer sample from them: the union keeps the finer minimum distance, since the
coarse points are farther apart, and fills the gaps as scipy fills any space.
(Dropping the points of a separate fine sample that come too close to the
coarse ones instead leaves holes: 0.41 points per radius squared against
0.60, measured for 1,600 in a 2 R square.)
"""

from __future__ import annotations

import numpy as np
from scipy.stats import qmc

# A random interior at or below this many points per disk is drawn on its
# own; from twice it, each level grows from the level of half its points:
# the paper's 800-point disk is the base of every chain, and it is the plain
# disk, byte for byte.
BASE_N_DISK = 800


def coarser_level(n_points: int, base: int) -> int | None:
    """The level a nested sample of ``n_points`` grows from (half its points,
    rounded down), or None at a base level (fewer than twice ``base``)."""
    return n_points // 2 if n_points >= 2 * base else None


def grow(sampler: qmc.PoissonDisk, coarse: np.ndarray) -> np.ndarray:
    """``coarse``'s points inside the sampler's box and the points the
    sampler then adds around them until the space is full.

    The coarse points must be at least the sampler's radius apart; they go
    into its pool and grid (scipy's own attributes, the state its ``random``
    keeps between calls), so each grid cell, a radius over sqrt(2) wide,
    holds at most one of them, as scipy's grid requires.
    """
    low, high = sampler.l_bounds, sampler.u_bounds
    coarse = coarse[np.all((coarse >= low) & (coarse <= high), axis=1)]
    cells = ((coarse - low) / sampler.cell_size).astype(int)
    if len(np.unique(cells, axis=0)) != len(cells):
        raise ValueError("coarse points closer than the sampler's radius")
    for point, cell in zip(coarse, cells):
        sampler.sample_pool.append(point)
        sampler.sample_grid[tuple(cell)] = point
    added = sampler.fill_space()
    return np.concatenate([coarse, added.reshape(-1, coarse.shape[1])])
