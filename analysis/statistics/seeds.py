"""A study's impacts by seed, and the seed bootstrap (docs/model.md section 6).

One seed's disk and wall serve every angle of a study (and, on a common wall,
every lattice's wall), so the impacts of one seed are not independent of each
other: beta correlates between neighbouring angles. Errors therefore come
from resampling whole seeds: a resample draws the study's seeds with
replacement and takes each drawn seed's impacts at every angle of every
lattice together. Any number computed from the impacts (a mean, a fitted
parameter, a difference between lattices) gets as its error the standard
deviation of its values over the resamples.

A bootstrap of few seeds has few distinct resamples and is biased low (by
sqrt((n - 1) / n)); below ``BOOTSTRAP_FROM`` seeds the error is the
jackknife over whole seeds instead (``seed_errors`` chooses): every number
recomputed with each seed left out in turn, whose spread gives the standard
error (for a mean: exactly sd / sqrt(n)), with n - 1 degrees of freedom for
intervals (``interval_factor``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import stats

from ground.digits import TABLE_DIGITS

from ..table import AVERAGED

# The quantities of impacts.csv that are averaged per lattice and angle.
QUANTITIES = (*AVERAGED, "side_clearance")
# The generator of the resamples: a fixed seed, so that a page is made again
# with the same errors.
RNG_SEED = 0
# At this many seeds or more the seed bootstrap; below, the seed jackknife.
BOOTSTRAP_FROM = 16
# Intervals: this two-sided coverage, from t with n - 1 degrees of freedom.
COVERAGE = 0.95


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
        spread = np.sqrt(squares / np.maximum(count - 1, 1) / np.maximum(count, 1))
        return np.where(count > 1, as_written_error(spread, values), np.nan)


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
        sd[key] = as_written_error(np.where(finite > 1, spread, np.nan), values)
    return sd


def as_written_error(sd: np.ndarray, draws: np.ndarray) -> np.ndarray:
    """An error below the last written digit of its number (ground.digits:
    TABLE_DIGITS of the draws' mean) is 0: it is the rounding of values
    equal as written (a wall study's cot gamma, one angle to 1e-14), whose
    last bits each CPU sums differently."""
    draws = np.asarray(draws, float)
    finite = np.isfinite(draws)
    with np.errstate(invalid="ignore", divide="ignore"):
        # nanmean without its warning on an all-NaN column (no number: no quantum)
        scale = np.abs(np.sum(np.where(finite, draws, 0.0), axis=0) / np.sum(finite, axis=0))
        quantum = 10.0 ** (np.floor(np.log10(scale)) - (TABLE_DIGITS - 1))
    return np.where(np.isfinite(quantum) & (sd < quantum), 0.0, sd)


def error_method(seeds: int) -> str:
    """The error of a number resting on ``seeds`` whole seeds: "bootstrap" at
    BOOTSTRAP_FROM or more, "jackknife" below (module docstring)."""
    return "bootstrap" if seeds >= BOOTSTRAP_FROM else "jackknife"


def interval_factor(seeds: int, coverage: float = COVERAGE) -> float:
    """Errors to a two-sided interval of ``coverage`` for a number resting on
    ``seeds`` seeds: the t quantile with seeds - 1 degrees of freedom (1.96
    -> 3.18 at four seeds)."""
    if seeds < 2:
        return float("nan")
    return float(stats.t.ppf(0.5 + coverage / 2, seeds - 1))


def seed_jackknife(
    tables: dict[str, SeedTable], statistic: Callable[[dict[str, SeedTable]], dict]
) -> dict:
    """Jackknife standard errors of a study's numbers over whole seeds.

    Parameters
    ----------
    tables, statistic
        As for ``seed_bootstrap``.

    Returns
    -------
    dict
        The keys of ``statistic``'s dict: sqrt((n - 1) / n * sum_i (x_i -
        mean x)^2), x_i the number with seed i left out (its impacts at every
        angle of every lattice); NaN where a leave-one-out value is undefined
        or there are fewer than two seeds.
    """
    seeds = len(next(iter(tables.values())).seeds)
    if seeds < 2:
        return {}
    draws: dict = {}
    for left_out in range(seeds):
        index = np.delete(np.arange(seeds), left_out)
        out = statistic({name: table.take(index) for name, table in tables.items()})
        for key, value in out.items():
            draws.setdefault(key, []).append(np.asarray(value, float))
    sd = {}
    for key, values in draws.items():
        values = np.array(values)
        deviations = values - values.mean(axis=0)
        spread = np.sqrt((seeds - 1) / seeds * np.sum(deviations**2, axis=0))
        sd[key] = as_written_error(spread, values)
    return sd


def seed_errors(
    tables: dict[str, SeedTable],
    statistic: Callable[[dict[str, SeedTable]], dict],
    resamples: int = 200,
    rng_seed: int = RNG_SEED,
) -> tuple[dict, dict]:
    """The errors of a study's numbers by the method its seed count calls for
    (``error_method``), and a description of them for the page: kind, method,
    seeds, degrees of freedom and the factor to a 95 % interval."""
    seeds = len(next(iter(tables.values())).seeds)
    method = error_method(seeds)
    if method == "bootstrap":
        sd = seed_bootstrap(tables, statistic, resamples, rng_seed)
        kind = f"sd over {resamples} seed-bootstrap resamples of {seeds} seeds"
    else:
        sd = seed_jackknife(tables, statistic)
        kind = f"jackknife standard error over {seeds} seeds (each left out in turn)"
    return sd, {
        "kind": kind,
        "method": method,
        "seeds": seeds,
        "dof": seeds - 1,
        "interval_factor": interval_factor(seeds) if method == "jackknife" else 1.96,
    }
