"""e, beta and the fits against the disk's resolution (studies/resolution.toml,
docs/resolution.md).

The study runs the random and triangular disks from 200 to 12,800 points on
walls of twice their points, under three readings of how the model is carried
to finer disks (analysis.readings.LIMITS): "continuum" (a roughness profile of
fixed correlation length, the contact scaled with the spacing), and each of the
paper's per-point readings in turn. Fewer seeds where an impact costs more
(``plan``). The page (``page``, in analysis.resolution_page) gives per reading
and resolution the means against cot gamma, e near normal incidence, Walton's
mu and beta0, the grazing peak, and their extrapolation to N -> infinity.
"""

from __future__ import annotations

from dataclasses import replace

from .readings import Setup

TITLE = "The continuum limit: e, beta and friction against the disk's resolution"
COLUMNS = (
    "reading",
    "limit",
    "n_disk",
    "study_lattice",
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "vn",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "side_clearance",
    "energy_drift",
    "drift_exceeded",
    "n_wall_points",
    "disk_inertia_ratio",
    "nu",
    "steps",
    "dt",
    "error",
)
# Seeds are full up to this many disk points; beyond, they fall as the
# points grow (an impact's cost grows about as N^1.5), to at least MIN_SAMPLES.
FULL_SAMPLES_UP_TO = 1600
MIN_SAMPLES = 4
# The per-point readings are followed as far as this (the paper's fixed
# contact is refused beyond: its exponential is not resolved at the cutoff).
PER_POINT_UP_TO = 3200
# The triangular disk as far as this, the random one as far as the study goes.
TRIANGULAR_UP_TO = 6400


def label(choice: dict) -> str:
    """A combination's reading: ``continuum_n800``."""
    return f"{choice['limit']}_n{choice['n_disk']}"


def row_fields(choice: dict, setup: Setup) -> dict:
    return {"limit": choice["limit"], "n_disk": choice["n_disk"]}


def samples_at(n_disk: int, samples: int) -> int:
    """Seeds at ``n_disk`` points: ``samples`` up to FULL_SAMPLES_UP_TO, then
    falling as 1 / N, never below MIN_SAMPLES."""
    if n_disk <= FULL_SAMPLES_UP_TO:
        return samples
    return max(MIN_SAMPLES, round(samples * FULL_SAMPLES_UP_TO / n_disk))


def plan(choice: dict, study):
    """The combination's study as run, or None to skip it: seeds by cost; the
    per-point readings on the random disk up to PER_POINT_UP_TO; the
    triangular disk up to TRIANGULAR_UP_TO."""
    n_disk = choice["n_disk"]
    lattices = tuple(study.lattices)
    if choice["limit"] != "continuum":
        if n_disk > PER_POINT_UP_TO:
            return None
        lattices = tuple(x for x in lattices if x == "random")
    elif n_disk > TRIANGULAR_UP_TO:
        lattices = tuple(x for x in lattices if x != "triangular")
    if not lattices:
        return None
    return replace(study, lattices=lattices, samples=samples_at(n_disk, study.samples))


def page(rows: list[dict], setup: Setup, figures) -> str:
    from .resolution_page import body

    return body(rows, setup, figures)
