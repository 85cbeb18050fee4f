"""A study's impacts by seed, and the seed bootstrap (MODEL.md section 6).

One seed's disk and wall serve every angle of a study (and, on a common wall,
every lattice's wall), so the impacts of one seed are not independent of each
other: beta correlates between neighbouring angles. Errors therefore come
from resampling whole seeds: a resample draws the study's seeds with
replacement and takes each drawn seed's impacts at every angle of every
lattice together. Any number computed from the impacts (a mean, a fitted
parameter, a difference between lattices) gets as its error the standard
deviation of its values over the resamples.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .table import AVERAGED

# The quantities of impacts.csv that are averaged per lattice and angle.
QUANTITIES = (*AVERAGED, "side_clearance")
# The generator of the resamples: a fixed seed, so that a page is made again
# with the same errors.
RNG_SEED = 0


@dataclass(frozen=True)
class SeedTable:
    """One lattice's impacts as (seed, angle) arrays, NaN where an impact is
    missing (failed or not run)."""

    seeds: np.ndarray  # (S,) the study's seeds, the same for every lattice
    gamma_deg: np.ndarray  # (A,) the lattice's angles, increasing
    values: dict[str, np.ndarray]  # quantity -> (S, A)

    def take(self, index: np.ndarray) -> SeedTable:
        """The table of the seeds at ``index`` (with repeats: a resample)."""
        return SeedTable(
            self.seeds[index], self.gamma_deg, {k: v[index] for k, v in self.values.items()}
        )

    def counts(self) -> np.ndarray:
        """Impacts per angle."""
        return np.sum(np.isfinite(self.values["beta"]), axis=0)

    def mean(self, quantity: str) -> np.ndarray:
        """Mean of a quantity per angle over the seeds that have it (NaN if none)."""
        values = self.values[quantity]
        count = np.sum(np.isfinite(values), axis=0)
        total = np.nansum(values, axis=0)
        return np.where(count > 0, total / np.maximum(count, 1), np.nan)

    def standard_error(self, quantity: str) -> np.ndarray:
        """sd / sqrt(n) of a quantity per angle (NaN below two impacts)."""
        values = self.values[quantity]
        count = np.sum(np.isfinite(values), axis=0)
        mean = self.mean(quantity)
        squares = np.nansum((values - mean) ** 2, axis=0)
        return np.where(
            count > 1, np.sqrt(squares / np.maximum(count - 1, 1) / np.maximum(count, 1)), np.nan
        )


def seed_tables(rows: list[dict], quantities=QUANTITIES) -> dict[str, SeedTable]:
    """Every lattice's impacts as a ``SeedTable``, all on the study's seeds.

    Parameters
    ----------
    rows : list of dict
        One row per impact (impacts.csv); numbers may be strings.
    quantities : sequence of str
        The columns to take.

    Returns
    -------
    dict
        Study lattice name -> SeedTable; the seeds are the union over the
        lattices, in increasing order, so that index i is one seed in every
        table (a resample takes a seed's impacts of every lattice together).
    """
    seeds = np.array(sorted({int(float(r["seed"])) for r in rows}))
    seed_index = {s: i for i, s in enumerate(seeds)}
    tables = {}
    for lattice in sorted({r["study_lattice"] for r in rows}):
        mine = [r for r in rows if r["study_lattice"] == lattice]
        gammas = np.array(sorted({float(r["gamma_deg"]) for r in mine}))
        angle_index = {g: j for j, g in enumerate(gammas)}
        values = {q: np.full((len(seeds), len(gammas)), np.nan) for q in quantities}
        for r in mine:
            i, j = seed_index[int(float(r["seed"]))], angle_index[float(r["gamma_deg"])]
            for q in quantities:
                values[q][i, j] = float(r[q]) if r[q] != "" else np.nan  # binary: no side
        tables[lattice] = SeedTable(seeds, gammas, values)
    return tables


def resample_indices(seeds: int, resamples: int, rng_seed: int = RNG_SEED) -> np.ndarray:
    """(resamples, seeds) indices of seeds drawn with replacement."""
    rng = np.random.default_rng(rng_seed)
    return rng.integers(0, seeds, size=(resamples, seeds))


def seed_draws(
    tables: dict[str, SeedTable],
    statistic: Callable[[dict[str, SeedTable]], dict],
    resamples: int = 200,
    rng_seed: int = RNG_SEED,
) -> dict[str, np.ndarray]:
    """A study's numbers on every resample of whole seeds (``seed_bootstrap``
    gives their standard deviations): key -> (resamples, ...) array."""
    seeds = len(next(iter(tables.values())).seeds)
    draws: dict = {}
    for index in resample_indices(seeds, resamples, rng_seed):
        out = statistic({name: table.take(index) for name, table in tables.items()})
        for key, value in out.items():
            draws.setdefault(key, []).append(np.asarray(value, float))
    return {key: np.array(values) for key, values in draws.items()}


def seed_bootstrap(
    tables: dict[str, SeedTable],
    statistic: Callable[[dict[str, SeedTable]], dict],
    resamples: int = 200,
    rng_seed: int = RNG_SEED,
) -> dict:
    """Standard deviations of a study's numbers over resamples of whole seeds.

    Parameters
    ----------
    tables : dict
        ``seed_tables`` of the study.
    statistic : callable
        Maps tables to a dict of numbers or arrays (fixed shapes); NaN where a
        resample leaves a number undefined.
    resamples : int
        Number of resamples, each drawing the study's seeds with replacement.
    rng_seed : int
        Seed of the resamples' generator (reproducible errors).

    Returns
    -------
    dict
        The keys of ``statistic``'s dict: the standard deviation (ddof 1) of
        each over the resamples where it is defined.
    """
    sd = {}
    for key, values in seed_draws(tables, statistic, resamples, rng_seed).items():
        finite = np.sum(np.isfinite(values), axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            spread = np.nanstd(np.where(finite > 1, values, 0.0), axis=0, ddof=1)
        sd[key] = np.where(finite > 1, spread, np.nan)
    return sd
