"""Two runs of one study's seeds in distribution: paired differences of the
ensemble means per lattice and angle.

A rough impact is chaotic: a change of the order in which LAMMPS sums its
forces (another neighbour list, another atom order) changes the last digits,
and within the contact those grow until one impact is no longer comparable
with the same impact run before. Its ensemble is: the same seeds give the
same disks and walls, so each seed's difference of e (or beta) between the
two runs is one paired sample, and their mean over the seeds with its
standard error says whether the change moved the ensemble mean
(bench/step_ensemble.py does the same for two time steps).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .seeds import seed_tables


@dataclass(frozen=True)
class PairedDifference:
    """One lattice, angle and quantity: the two runs' means over the seeds
    both finished, and the mean paired difference (after - before) with its
    standard error over those seeds."""

    lattice: str
    gamma_deg: float
    quantity: str
    seeds: int
    before: float
    after: float
    difference: float
    standard_error: float

    @property
    def z(self) -> float:
        """The difference in standard errors (0 where both are exactly equal)."""
        if self.standard_error == 0.0:
            return 0.0 if self.difference == 0.0 else np.inf
        return self.difference / self.standard_error


def paired_differences(
    before: list[dict], after: list[dict], quantities: tuple[str, ...] = ("e", "beta")
) -> list[PairedDifference]:
    """Every lattice, angle and quantity of two studies' impacts.csv rows.

    Parameters
    ----------
    before, after : list of dict
        The rows of the same study run twice (impacts.csv; numbers may be
        strings); only seeds finished in both count, per angle.
    quantities : tuple of str
        The columns to compare.

    Returns
    -------
    list of PairedDifference
        By lattice, angle (increasing) and quantity.

    Raises
    ------
    ValueError
        If the two have no lattice and angle in common.
    """
    old, new = seed_tables(before, quantities), seed_tables(after, quantities)
    out = []
    for lattice in sorted(set(old) & set(new)):
        a, b = old[lattice], new[lattice]
        seed_in_b = {int(s): i for i, s in enumerate(b.seeds)}
        rows_a = [i for i, s in enumerate(a.seeds) if int(s) in seed_in_b]
        rows_b = [seed_in_b[int(a.seeds[i])] for i in rows_a]
        for j, gamma in enumerate(a.gamma_deg):
            match = np.flatnonzero(np.isclose(b.gamma_deg, gamma, rtol=0.0, atol=1e-9))
            if not len(match):
                continue
            for quantity in quantities:
                x = a.values[quantity][rows_a, j]
                y = b.values[quantity][rows_b, match[0]]
                both = np.isfinite(x) & np.isfinite(y)
                if both.sum() < 2:
                    continue
                d = y[both] - x[both]
                out.append(
                    PairedDifference(
                        lattice,
                        float(gamma),
                        quantity,
                        int(both.sum()),
                        float(x[both].mean()),
                        float(y[both].mean()),
                        float(d.mean()),
                        float(d.std(ddof=1) / np.sqrt(len(d))),
                    )
                )
    if not out:
        raise ValueError("the two studies have no lattice and angle in common")
    return out


def impact_differences(before: list[dict], after: list[dict], quantity: str) -> np.ndarray:
    """after - before of ``quantity`` for every impact (lattice, seed, angle)
    in both: how far the change moved single impacts."""

    def key(row: dict) -> tuple:
        speed = round(float(row.get("vn") or "nan"), 9)
        return (
            row["study_lattice"],
            int(float(row["seed"])),
            round(float(row["gamma_deg"]), 6),
            speed,
        )

    old = {key(r): float(r[quantity]) for r in before}
    return np.array([float(r[quantity]) - old[key(r)] for r in after if key(r) in old])


def summary(differences: list[PairedDifference], within: float = 2.0) -> dict:
    """How many differences lie beyond ``within`` standard errors, against the
    share a normal distribution puts there (the cells share seeds, so they
    are not independent), and the largest.

    Returns
    -------
    dict
        ``cells``, ``beyond`` (count), ``expected`` (count), ``largest_z``
        and where it is (``largest_at``).
    """
    from scipy.stats import norm

    z = np.array([abs(d.z) for d in differences])
    worst = differences[int(np.argmax(z))]
    return {
        "cells": len(differences),
        "beyond": int(np.sum(z > within)),
        "expected": float(len(differences) * 2.0 * norm.sf(within)),
        "largest_z": float(z.max()),
        "largest_at": f"{worst.lattice} {worst.quantity} at {worst.gamma_deg:g} degrees",
    }
