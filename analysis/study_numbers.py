"""The numbers of one study's tables, as its page shows them and fits.json
keeps them: the fits, claims and per-angle means of every study; e at
grazing incidence past the paper's last angle; two disks beside the same
disks on the wall. Rounded to the digits every CPU agrees on
(analysis.table.rounded); the pages (pages.kinds) only format them."""

from __future__ import annotations

from collections import Counter

from . import binary_comparison, grazing, normal_check
from .statistics.claims import claims
from .statistics.estimates import study_estimates
from .table import mean_rows, rounded


def results_numbers(rows: list[dict], resamples: int) -> tuple[dict, list[dict]]:
    """fits.json's fits, measures and claims, and means.csv's rows."""
    fits, errors = study_estimates(rows, resamples)
    fits["claims"] = claims(fits)
    # what the tables keep, and the page says, to the digits every CPU agrees on
    fits, errors = rounded(fits), rounded(errors)
    return fits, rounded(mean_rows(rows, errors))


def grazing_numbers(rows: list[dict], resamples: int) -> dict:
    """e at grazing incidence per lattice, with the normals' check of the same rows."""
    check = normal_check.robustness(rows, resamples)
    return rounded(grazing.grazing_numbers(rows, resamples, check))


def binary_numbers(
    rows: list[dict], readings: dict[str, tuple[dict, list[dict], list[dict]]], resamples: int
) -> dict:
    """Two disks beside the wall studies (and other pairs) among ``readings``
    (their tables, by name): the normals' checks, each wall study's
    comparison and, with grazing angles, the walls' e > 1 on the same seeds."""
    walls = {n: t[1] for n, t in readings.items() if t[0].get("target") != "disk"}
    pairs = {n: t[1] for n, t in readings.items() if t[0].get("target") == "disk"}
    out = {
        "normals": rounded(binary_comparison.normal_checks(rows, walls, pairs, resamples)),
        "wall_comparison": rounded(
            {
                name: binary_comparison.comparison(rows, wall, resamples)
                for name, wall in walls.items()
            }
        ),
    }
    if grazing.has_grazing_angles(rows):  # the walls' e > 1 beside the pairs'
        out["wall_grazing"] = {}
        for name, wall in walls.items():
            paired = binary_comparison.paired_rows(rows, wall)[1]
            out["wall_grazing"][name] = rounded(
                grazing.grazing_numbers(
                    paired, resamples, normal_check.robustness(paired, resamples)
                )
            )
    return out


def samples_done(info: dict, rows: list[dict], failed: list[dict]) -> int:
    """How many seeds are complete: every impact of the seed done or failed."""
    per_sample = len(info["lattices"]) * info["angles"]
    finished = Counter(int(float(r["seed"])) for r in rows)
    finished.update(int(float(f["seed"])) for f in failed)
    return sum(count >= per_sample for count in finished.values())
