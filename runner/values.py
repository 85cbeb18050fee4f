"""What every option of a study may be: one table for the study file and the
command line.

Each option of a study (its grid, its scene, its run) has an entry here: a
``Value``, a number in a ``ground.checks.Range``, one of some words, or
either. A study file's values are checked against it (each value of an axis
too, in any position), and runner study's options take it as their type, so
that a file and the command line refuse the same values with the same words.
The ranges themselves are defined beside what uses them (builder.scene,
runner.options); an option added there needs its line here
(tests/cli/test_refusals.py fails until it has one).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass

from builder.bodies import LATTICES as BODY_LATTICES
from builder.materials import STUDY_LATTICES
from builder.scene import (
    ANGLE,
    CONTACT_A,
    CONTACT_SCALINGS,
    MODEL_READINGS,
    N_DISK,
    N_WALL,
    PARTNERS,
    RADIUS,
    ROUGHNESS,
    ROUGHNESS_LENGTH,
    SEED,
    TARGETS,
    VN,
    WALL_DENSITY,
    WALL_FIXED_CHOICES,
    WALL_KA,
    WALL_SAME_C,
    WALL_WIDTH,
)
from ground.checks import Range
from ground.errors import InputError

from .options import (
    AUTO,
    CONTACTS,
    DRIFT,
    DT,
    DUMP_EVERY,
    INTEGRATORS,
    NPROCS,
    NRESPA,
    ROUTES,
    RULES,
    SPRINGS,
    STEPS,
    STOP_RULES,
    TMAX,
)

# The grid's own numbers (runner.study.Study.validate reads them too).
SAMPLES = Range(1, 10_000, integer=True)
ANGLES = Range(2, 1_000, integer=True)
COT_GAMMA = Range(0.05, 100.0)  # 0.6 to 87 degrees


@dataclass(frozen=True)
class Value:
    """A number in ``numbers``, or one of ``words`` (the same type and value:
    0 is a word of ``every``, 0.0 and false are not); ``many``: a list of
    distinct such values."""

    numbers: Range | None = None
    words: tuple = ()
    many: bool = False

    def describe(self) -> str:
        """The allowed values in words, as the command line says them."""
        if self.numbers is None:
            text = "one of " + ", ".join(map(str, self.words))
        else:
            text = " or ".join([self.numbers.describe(), *map(repr, self.words)])
        return f"a list of distinct values, each {text}" if self.many else text

    def allows(self, value) -> bool:
        if any(type(value) is type(word) and value == word for word in self.words):
            return True
        return self.numbers is not None and self.numbers.contains(value)

    def check(self, name: str, value):
        """``value`` if allowed, else InputError naming ``name`` and what it may be."""
        if self.many:
            if not isinstance(value, (list, tuple)) or not value:
                raise InputError(f"{name} must be {self.describe()}, got {value!r}")
            for each in value:
                if not self.allows(each):
                    raise InputError(f"{name} must be {self.describe()}, got {each!r} in {value!r}")
            if len({repr(v) for v in value}) != len(value):
                raise InputError(f"{name} names a value twice, got {value!r}")
            return value
        if not self.allows(value):
            raise InputError(f"{name} must be {self.describe()}, got {value!r}")
        return value

    def __call__(self, text: str):
        """argparse's type: a word, or the text as a number in ``numbers``."""
        for word in self.words:
            if str(word) == text:
                return word
        if self.numbers is None:
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text!r}")
        try:
            return self.numbers(text)
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text}") from None

    @property
    def __name__(self) -> str:  # argparse names a type by it in some messages
        return "value"


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
# [scene]: Study's scene options (builder.scene.SceneSpec's readings).
SCENE = {
    "n_disk": Value(N_DISK),
    "radius": Value(RADIUS),
    "roughness": Value(ROUGHNESS),
    "roughness_length": Value(ROUGHNESS_LENGTH, (0.0, 0)),  # 0: each point on its own
    "wall_width": Value(WALL_WIDTH),
    "contact_a": Value(CONTACT_A),
    "contact_scaling": Value(words=CONTACT_SCALINGS),
    "n_wall": Value(N_WALL, (WALL_DENSITY,)),
    "wall_ka": Value(WALL_KA, (WALL_SAME_C,)),
    "wall_fixed": Value(words=WALL_FIXED_CHOICES),
    **{name: Value(words=tuple(choices)) for name, choices in MODEL_READINGS.items()},
    "target": Value(words=TARGETS),
    "partner_lattice": Value(words=tuple(BODY_LATTICES)),
    "partner": Value(words=PARTNERS),
}
# [run]: runner.options.RunOptions. every and check: 0 is the default's spacing.
RUN = {
    "dt": Value(DT, (AUTO,)),  # auto: the step follows the spacing (RunOptions.for_scene)
    "integrator": Value(words=INTEGRATORS),
    "nrespa": Value(NRESPA),
    "contact": Value(words=CONTACTS),
    "rule": Value(words=RULES),
    "springs": Value(words=tuple(SPRINGS)),
    "tmax": Value(TMAX),
    "every": Value(STEPS, (0,)),
    "check": Value(STEPS, (0,)),
    "dump_every": Value(DUMP_EVERY),
    "stop_rule": Value(words=STOP_RULES),
    "nprocs": Value(NPROCS),
    "route": Value(words=ROUTES),
    "max_drift": Value(DRIFT),
}
VALUES = {"grid": GRID, "scene": SCENE, "run": RUN}
