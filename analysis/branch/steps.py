"""mu on the sliding branch from one resolution to the next, seed by seed.

Studies that run the same seeds and surfaces at several resolutions (the
sliding branch's levels, studies/sliding_branch*.toml) give each level's
branch and mu on it (``sliding``, ``measures``); the step between two
levels is the difference of their mu, each on its own branch, with the
seed bootstrap drawing the same seeds at both (a seed's surface is the same
at every level, so their errors are correlated and the step's is smaller
than either's).

    python -m analysis.branch.steps docs/studies/sliding_branch_1600 \\
        docs/studies/sliding_branch_3200

With --angles, the mean mu_eff over those angles at every level instead:
where a level's rows hold no branch, or the branches differ, the same
angles still give a paired step (angles chosen after seeing the rows: the
step is of those angles, not of a branch).
"""

from __future__ import annotations

import argparse
import csv
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..statistics.estimates import lattice_constants
from ..statistics.measures import measures
from ..statistics.seeds import SeedTable, resample_indices, seed_tables
from ..statistics.sliding import constant_p, per_seed_mu_eff, sliding_branch

RESAMPLES = 2000


@dataclass(frozen=True)
class Level:
    """One level's impacts, its lattice's constants and the angles its
    friction is read at."""

    table: SeedTable
    nu: float  # the calibration's Poisson ratio
    K: float  # 1 + M R^2 / I, measured
    chosen: np.ndarray  # (angles,) bool: the sliding branch, or the angles asked for
    complete: int = 0  # the level's seeds with an impact at every angle (before any left out)

    def without(self, seed: int) -> Level:
        """The level with one seed left out."""
        return replace(self, table=self.table.take(np.flatnonzero(self.table.seeds != seed)))


def level(folder: Path, angles: list[float] | None = None, lattice: str = "random") -> Level:
    """A level's table, constants and sliding branch (or ``angles``, in
    degrees, fixed), from its committed impacts.csv."""
    with (folder / "impacts.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    table = seed_tables(rows)[lattice]
    nu, _, K = lattice_constants(rows, lattice)
    complete = int(np.all(np.isfinite(table.values["beta"]), axis=1).sum())
    if angles is None:
        return Level(table, nu, K, sliding_branch(table, K)[0], complete)
    chosen = np.isin(np.round(table.gamma_deg, 4), np.round(angles, 4))
    if chosen.sum() != len(angles):
        raise ValueError(f"{folder.name} does not have every angle of {angles}")
    return Level(table, nu, K, chosen, complete)


def steps(
    folders: list[Path], resamples: int = RESAMPLES, angles: list[float] | None = None
) -> list[dict]:
    """Each level's mu on its branch (or the mean mu_eff over ``angles``,
    the same at every level) and each step's difference, with seed
    bootstrap errors that draw the same seeds at every level.

    Raises
    ------
    ValueError
        If the levels do not share their seeds, or lack one of ``angles``.
    """
    levels = [level(f, angles) for f in folders]
    seeds = levels[0].table.seeds
    if any(not np.array_equal(x.table.seeds, seeds) for x in levels):
        raise ValueError("the levels do not run the same seeds")

    def mus(index: np.ndarray | None) -> np.ndarray:
        return np.array(
            [
                measures(x.table if index is None else x.table.take(index), x.K, x.chosen)[
                    "mu_branch"
                ]
                for x in levels
            ]
        )

    best = mus(None)
    draws = np.array([mus(index) for index in resample_indices(len(seeds), resamples)])
    out = []
    for i, folder in enumerate(folders):
        x = levels[i]
        # whether one constant describes the chosen angles, seed by seed
        p = constant_p(per_seed_mu_eff(x.table, x.K)[:, x.chosen]) if x.chosen.sum() > 1 else None
        row = {"level": folder.name, "mu": best[i], "sd": _sd(draws[:, i]), "p_constant": p}
        if i and np.isfinite(best[i]) and np.isfinite(best[i - 1]):
            row.update(step=best[i] - best[i - 1], step_sd=_sd(draws[:, i] - draws[:, i - 1]))
        out.append(row)
    return out


def _sd(values: np.ndarray) -> float:
    """The spread of the resamples that hold a branch (NaN if none does)."""
    finite = values[np.isfinite(values)]
    return float(finite.std(ddof=1)) if finite.size > 1 else float("nan")


def add_level_arguments(
    parser: argparse.ArgumentParser, angles_help: str, required: bool = True
) -> None:
    """The level folders and --angles, as every command over the levels takes them."""
    parser.add_argument(
        "folders", nargs="+", type=Path, help="docs/studies/<level>/, coarsest first"
    )
    parser.add_argument("--angles", nargs="+", type=float, required=required, help=angles_help)


def main(argv: list[str] | None = None) -> int:
    """Print mu on the sliding branch at each level and the steps between them."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    add_level_arguments(
        parser,
        "the mean mu_eff over these angles (degrees) at every level, not each level's own branch",
        required=False,
    )
    args = parser.parse_args(argv)
    what = "mean mu_eff over the angles" if args.angles else "mu on the branch"
    try:
        rows = steps(args.folders, angles=args.angles)
    except ValueError as error:
        parser.error(str(error))
    for row in rows:
        if not np.isfinite(row["mu"]):
            print(f"{row['level']}: no sliding branch in the rows")
            continue
        step = f"; step {row['step']:+.4f} +- {row['step_sd']:.4f}" if "step" in row else ""
        p = row["p_constant"]
        one = f" (one constant over them: p {p:.3f})" if p is not None else ""
        print(f"{row['level']}: {what} {row['mu']:.4f} +- {row['sd']:.4f}{one}{step}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
