"""Names a study file may give, as plain data: the readings of the scene by
name (docs/model.md section 8), the kinds of page and the sections of a results
page. Reading a study file (runner.study.file) checks its names against
these without importing what makes the pages (analysis.kinds,
pages.sections, analysis.kinds.readings use them from here).
"""

from __future__ import annotations

import itertools

from .scene import FIRST_READING, PAPER

# The kinds of page a study file may ask for (its ``kind``): ``results`` (the
# default), or a readings study's page made from its table (analysis.kinds).
READINGS_KINDS = (
    "scene_readings",
    "model_readings",
    "fact_sensitivity",
    "wall_width",
    "grazing_wall",
    "resolution",
    "references",
)
KINDS = ("results", *READINGS_KINDS)
# A lattice's page fits it with at least FIT_ANGLES angles of FIT_SEEDS
# impacts or more (a mean and its error at each: analysis.statistics.estimates);
# a resolution study fits every level, so its file is held to it before any run.
FIT_ANGLES, FIT_SEEDS = 3, 2
# The sections a results page may have, in the order it has them
# (pages.results.results_page; a study file's `sections` picks some).
SECTIONS = (
    "findings",  # a binary study's (analysis.binary_findings)
    "earlier_runs",
    "statistics",
    "claims",
    "fits",
    "measures",
    "nu",
    "wall_ends",
    "grazing",
    "readings",
    "wall_comparison",  # a binary study's (pages.binary)
    "normals",  # a binary study's: e and beta at every normal (analysis.normal_check)
)

N_WALL = (800, 1600, "density")
WALL_KA = (1.0, 10.0, "same-c")
WALL_FIXED = ("sides", "sides+bottom")


def wall_label(n_wall, wall_ka, wall_fixed: str) -> str:
    """A wall as the pages name it: ``points_ka_held`` (``800_1ka_sides``)."""
    ka = wall_ka if isinstance(wall_ka, str) else f"{wall_ka:g}ka"
    return f"{n_wall}_{ka}_{wall_fixed.replace('+', '-')}"


# Every reading of the wall, in the order of the scene readings' table.
WALLS = {
    wall_label(*w): dict(zip(("n_wall", "wall_ka", "wall_fixed"), w))
    for w in itertools.product(N_WALL, WALL_KA, WALL_FIXED)
}
# The readings of the model: the first reading, one choice changed at a time,
# and the pair the trials point at (the disk's mass moved mu most; a
# regular disk with its own surface is the construction that could make it slip).
MODEL_CHANGES = {
    "first-read": {},
    "disk-mass": {"contact_mass": "disk"},
    "spring-speed": {"speed_unit": "spring"},
    "both-directions": {"roughness_direction": "both"},
    "random-row": {"surface_row": "random"},
    "lattice-surface": {"regular_surface": "lattice"},
    "disk-mass+lattice-surface": {"contact_mass": "disk", "regular_surface": "lattice"},
}
# Relative to the first reading, not to today's default.
MODELS = {name: {**FIRST_READING, **change} for name, change in MODEL_CHANGES.items()}
# How the model is carried to finer disks (docs/model.md, "The model as the
# resolution grows"): the roughness's correlation length (0.048 R: the rms
# slope, roughness / length, of independent draws 2 pi / 93 R apart, the
# 800-point disk's surface spacing, sqrt(2) roughness / spacing) and the
# contact's scaling; "continuum" changes neither with the spacing, the other
# two take the paper's per-point reading of one of them. Each names all four
# options that carry the body to finer disks (builder.scene.BODY), as the
# default is no longer the paper's: "paper" is the paper's scene, a draw per
# surface point and the contact following the spacing; "profile-floor" is
# today's default at target wall.
ROUGHNESS_LENGTH = 0.048
# The continuous surface's correlation length: 0.2 R, whose roughness a rough
# contact resolves near 25,600 points (docs/model.md).
PROFILE_LENGTH = 0.2
PAPER_SLOPE_LENGTH = 0.06
LIMITS = {
    "continuum": {**PAPER, "roughness_length": ROUGHNESS_LENGTH},
    "point-roughness": dict(PAPER),
    "fixed-contact": {**PAPER, "roughness_length": ROUGHNESS_LENGTH, "contact_scaling": "fixed"},
    # Every length physical (issue 46): one continuous surface per seed, the
    # same at every resolution (builder/profile.py), of correlation length
    # PROFILE_LENGTH, and the contact's lengths fixed in R; "smooth" is its
    # baseline without roughness, which separates the elasticity and the
    # contact from the roughness.
    "profile": {
        "roughness_length": PROFILE_LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.0,
    },
    # (its surface options profile's, as resolution_profile ran it after
    # profile: without roughness they change nothing)
    "smooth": {
        "roughness": 0.0,
        "roughness_length": PROFILE_LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.0,
    },
    # the profile with a barrier against the triangles turning inside out
    # (area_floor 0.5: docs/rough_contact.md, "The barrier"): the lattice's
    # artefact removed, the small-strain moduli unchanged
    "profile-floor": {
        "roughness_length": PROFILE_LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.5,
    },
    # the floor's surfaces of twice and 3.3 times the slope (L = 0.1 R and
    # the paper's 0.06 R): friction against the rms slope
    "slope0.3-floor": {
        "roughness_length": 0.1,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.5,
    },
    "paper-slope-floor": {
        "roughness_length": PAPER_SLOPE_LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.5,
    },
    # the paper's slope (0.5, the mean of its disk's 0.61 and its wall's 0.39
    # at 800 points: bench/surface_slopes.py) as a continuous profile
    "paper-slope": {
        "roughness_length": PAPER_SLOPE_LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.0,
    },
    # the paper's scene (builder.scene.PAPER): the default before issue 46,
    # which the studies of the paper's scene pin
    "paper": dict(PAPER),
}
# What the disk hits in the symmetric references (analysis/kinds/references.py):
# a second disk, its own image, that image held, a wall built like a disk's
# surface, the paper's wall (the paper's body: a binary scene's default).
REFERENCES = {
    "pair": {"target": "disk", "partner": "independent"},
    "image": {"target": "disk", "partner": "image"},
    "image-held": {"target": "disk", "partner": "image-held"},
    "surface": {"target": "disk", "partner": "surface"},
    "wall": {"target": "wall", "partner": "independent", **PAPER},
}
# The references that meet one disk, not a pair: run at half the pair's speed
# (analysis/kinds/references.py); here, so that the kind and its page share them.
ONE_BODY = ("image-held", "surface", "wall")
# The named readings a study file's [scene] may give, by key.
NAMED = {"wall": WALLS, "model": MODELS, "limit": LIMITS, "reference": REFERENCES}
