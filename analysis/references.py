"""Two disks against the symmetric references (studies/binary_references.toml,
docs/binary_references.md): does two-body physics change e, beta and mu, and
does the way the wall is built?

Five readings (analysis.readings.REFERENCES) of what the disk hits, every
seed's disk the same in all five:

- ``pair``: a second, independent disk, the binary studies' pair, at v_n;
- ``image``: the disk's own image (``partner image``: the disk turned by 180
  degrees), a symmetric collision, at v_n;
- ``image-held``: that image held, rigid and immovable, at v_n / 2;
- ``surface``: a wall built like a disk's surface (``partner surface``: a held
  ring of radius 20 R at the disk's spacing and roughness, the contact acting
  both ways), at v_n / 2;
- ``wall``: the default wall (the clamped beam, one-sided contact), at v_n / 2.

The one-body references run at half the pair's relative speed (``plan``): in
the centre of mass each disk of a pair brings the contact v_n / 2. The
two-body compliant model maps the pair onto one disk against a rigid flat
at v_n / 2 (docs/model.md, "Two disks"); ``image`` against ``surface`` tests
it, ``surface`` against ``wall`` measures the wall's construction.
"""

from __future__ import annotations

from dataclasses import replace

from .readings import ONE_BODY, REFERENCES, Setup

COLUMNS = (
    "reading",
    "reference",
    "study_lattice",
    "lattice",
    "seed",
    "gamma_deg",
    "cot_gamma",
    "vn",
    "vn_in_c",
    "target",
    "target_held",
    "e",
    "beta",
    "omega",
    "contact_time",
    "vibration_disk",
    "vibration_wall",
    "side_clearance",
    "energy_drift",
    "drift_exceeded",
    "disk_inertia_ratio",
    "target_inertia_ratio",
    "n_disk_points",
    "n_target_points",
    "nu",
    "e_first_touch",
    "beta_first_touch",
    "cot_gamma_first_touch",
    "e_impulse",
    "beta_impulse",
    "cot_gamma_impulse",
    "impulse_tilt_deg",
    "steps",
    "dt",
    "error",
)
ORDER = tuple(REFERENCES)  # pair, image, image-held, surface, wall


def label(choice: dict) -> str:
    """A combination's reading: its reference's name."""
    return str(choice["reference"])


def row_fields(choice: dict, setup: Setup) -> dict:
    """Each row's reference and the pair's relative speed it stands beside."""
    return {"reference": choice["reference"]}


def plan(choice: dict, study):
    """The one-body references at half the pair's speed (each speed of the
    study's axis, or its v_n)."""
    if choice["reference"] not in ONE_BODY:
        return study
    return replace(study, vn=study.vn / 2.0, speeds=tuple(speed / 2.0 for speed in study.speeds))
