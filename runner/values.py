"""What every option of a study may be: one table for the study file and the
command line.

Each option of a study (its grid, its scene, its run) has a ``Value`` here:
a number in a ``ground.checks.Range``, one of some words, or either. A
study file's values are checked against it (each value of an axis too, in
any position), and runner study's options take it as their type, so that a
file and the command line refuse the same values with the same words. The
scene's and the run's come from their declarations (builder.scene.SCENE_OPTIONS,
builder.run_options.RUN_OPTIONS); the grid is the study's own.
"""

from __future__ import annotations

from builder.declared import Value  # noqa: F401 (the study file's and the tests' too)
from builder.materials import STUDY_LATTICES
from builder.run_options import RUN_OPTIONS
from builder.scene import ANGLE, SCENE_OPTIONS, SEED, VN
from ground.checks import Range

# The grid's own numbers (runner.study.Study.validate reads them too).
SAMPLES = Range(1, 10_000, integer=True)
ANGLES = Range(2, 1_000, integer=True)
COT_GAMMA = Range(0.03, 100.0)  # 0.6 to 88.3 degrees (studies/sliding_branch.toml)

# [grid]: runner.study.Study's grid. vn may be an axis (a study each); the
# lists (many) are the study's own axes.
GRID = {
    "lattices": Value(words=tuple(STUDY_LATTICES), many=True),
    "angles": Value(ANGLES),
    "cot_gamma": Value(COT_GAMMA, many=True),
    "gamma_deg": Value(ANGLE, many=True),
    "samples": Value(SAMPLES),
    "first_seed": Value(SEED),
    "vn": Value(VN),
    "speeds": Value(VN, many=True),
}
# [scene]: the scene's options a study takes; [run]: every run option.
SCENE = {option.name: option.value for option in SCENE_OPTIONS if option.study}
RUN = {option.name: option.value for option in RUN_OPTIONS}
VALUES = {"grid": GRID, "scene": SCENE, "run": RUN}
