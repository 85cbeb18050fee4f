"""A scene: a disk placed above a wall, moving towards it at an angle.

Coordinates: the wall's top face is near y = 0 and its centre at x = 0; the
wall normal is +y; the disk moves with velocity (v_n tan gamma, -v_n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ground.checks import Range
from ground.errors import InputError

from . import bodies
from .declared import Option, by_name, with_options
from .materials import spring_constant
from .triangles import AREA_FLOOR

# LAMMPS atom types.
DISK_SURFACE, DISK_INTERIOR, WALL_SURFACE, WALL_INTERIOR, WALL_FIXED = 1, 2, 3, 4, 5
TYPE_NAMES = {
    DISK_SURFACE: "disk surface",
    DISK_INTERIOR: "disk interior",
    WALL_SURFACE: "wall surface",
    WALL_INTERIOR: "wall interior",
    WALL_FIXED: "wall fixed",
}
WALL_FIXED_CHOICES = ("sides", "sides+bottom", "all")
# The readings of the wall that the paper leaves open (docs/model.md section 8):
# n_wall is a number of points or "density" (the disk's number density), and
# wall_ka is the wall's spring constant over the random disk's (``wall_spring_constant``),
# or "same-c" (the ka that gives the wall the wave speed c). Neither depends on
# the disk's lattice, so that every lattice of a study meets the same wall.
WALL_DENSITY = "density"
WALL_SAME_C = "same-c"
# The readings of the model (docs/model.md section 8), each a SceneSpec field: its
# choices, the one this project first read the paper's text as first. The
# default (SceneSpec) is the rule's pick, which may be another.
MODEL_READINGS = {
    "contact_mass": ("point", "disk"),
    "speed_unit": ("c", "spring"),
    "roughness_direction": bodies.ROUGHNESS_DIRECTIONS,
    "surface_row": bodies.SURFACE_ROWS,
    "regular_surface": bodies.REGULAR_SURFACES,
}
# Each reading's default (the rule's pick: docs/model.md,
# docs/studies/model_readings/) and what its choices mean, in the order of
# the "made by" command line.
MODEL_OPTIONS = (
    ("contact_mass", "disk",
     "the m of the contact's V0 = a m c^2 R / 2: one point's mass, or the disk's"),
    ("speed_unit", "c", "the unit of --vn: c, the calibrated wave speed, or the disk springs' "
     "one-dimensional sound speed d sqrt(ka / m)"),
    ("roughness_direction", "normal",
     "surface points displaced along the surface normal, or in both directions"),
    ("surface_row", "even",
     "the disk's surface row evenly spaced on the circle, or a Poisson-disk sample of it"),
    ("regular_surface", "band", "the triangular and square disks' surface: a row joined to the "
     "lattice by a band of springs, or the lattice's own outermost points"),
)  # fmt: skip
# What a scene.json, result or impacts.csv row made before these options means.
FIRST_READING = {name: choices[0] for name, choices in MODEL_READINGS.items()}
# The ranges of the scene's numbers, for SceneSpec.validate and the command line
# (builder/cli.py) alike.
ANGLE = Range(0.0, 90.0, low_open=True, high_open=True, unit="degrees from the wall's normal")
SEED = Range(0, 2**32 - 1, integer=True)
RADIUS = Range(0.1, 10.0, unit="R, the unit of length")  # where the scaled step works (issue 44)
N_DISK = Range(50, 100_000, integer=True)
N_WALL = Range(50, 400_000, integer=True)
ROUGHNESS = Range(0.0, 0.1, unit="R")
K2_OVER_K1 = Range(0.0, 1000.0, low_open=True)
NU = Range(0.0, 0.99, low_open=True)
WALL_KA = Range(0.01, 1000.0, unit="the wall's ka over the random disk's")
WALL_WIDTH = Range(4.0, 100.0, unit="R")
CONTACT_A = Range(1.0, 10_000.0, unit="a R")
# The roughness's correlation length along the surface; 0 draws each point on
# its own (the paper). Below 0.005 R its profile needs more modes than points.
ROUGHNESS_LENGTH = Range(0.005, 1.0, unit="R, or 0: each point on its own")
# How the contact changes with the resolution (docs/model.md, "The model as
# the resolution grows"): "fixed", the paper's a R = contact_a and V0 at any
# number of points; "spacing", a times the spacing and the contact's energy
# per length of surface held at the 800-point disk's, which makes the contact
# harder as the disk is refined, towards a hard contact in the limit.
# "physical": every length of the contact fixed in R (a, and the cutoff at the
# 800-point scene's, PAPER_CUTOFF) and its pressure in proportion to the
# elastic modulus (``contact_energy``), so that only the sampling changes with N.
CONTACT_SCALINGS = ("spacing", "fixed", "physical")
# The rough surface: "sampled" at the row's points, a new draw at every
# resolution (``profile.correlated``); "continuous", one profile per seed, the
# same function of arc length at every resolution (builder/profile.py).
ROUGHNESS_PROFILES = ("sampled", "continuous")
# The disk at which every setting that follows the resolution is the paper's.
REFERENCE_N_DISK = 800
# The contact's cutoff with contact_scaling "physical": the paper's, the wall
# spacing of its 1,600 points over 8 R x 2 R (32 decay lengths at a R = 300).
PAPER_CUTOFF = bodies.triangular_spacing(2 * REFERENCE_N_DISK / (8.0 * 2.0))
# Where the default run resolves the contact (bench/stability.py,
# docs/benchmarks/stability_speeds.md, three seeds per point): every normal speed up
# to 0.4 c at speeds along the wall up to 0.8 c; at 0.5 c and 1.0 c along the
# wall segments stretch past the contact's reach. --vn stops at 0.3 c, the
# speed study's last (docs/studies/speed/speed.md).
VN = Range(0.0, 0.3, low_open=True, unit="units of c")
MAX_TANGENTIAL_SPEED = 0.8  # c
# What a scene itself may be given: below the wave speed. bench/stability.py
# builds scenes up to 0.5 c to find where runs fail; the command line takes VN.
SUBSONIC = Range(0.0, 1.0, low_open=True, high_open=True, unit="units of c")
GAMMA = Range(0.0, 90.0, high_open=True, unit="degrees")  # in code, 0 (head-on) too
KB_OVER_KA = Range(0.0, 1.0)
WALL_HEIGHT = Range(0.5, 100.0, unit="R")


# What a disk may hit (builder/binary.py builds the second disk), and the
# wall's options, which a binary scene refuses rather than ignores.
TARGETS = ("wall", "disk")
# The second disk: independent (its own draw) or the disk's own image through
# the midpoint of the contact (the disk turned by 180 degrees), which makes the
# collision symmetric: each disk meets what the other meets (builder/binary.py).
# "image-held": that image with every point held, an immovable rigid copy (no
# recoil, no compliance), to be met at half the pair's relative speed;
# "surface": a held, nearly flat wall built like a disk's surface (builder/binary.py).
PARTNERS = ("independent", "image", "image-held", "surface")
WALL_OPTIONS = ("n_wall", "wall_ka", "wall_fixed", "wall_width", "wall_height")


def speed_warning(vn: float, gamma_deg: float) -> str | None:
    """Why a run at (vn, gamma) may not resolve the contact, or None."""
    tangential = vn * math.tan(math.radians(gamma_deg))
    if tangential <= MAX_TANGENTIAL_SPEED * (1.0 + 1e-9):
        return None
    return (
        f"the disk's speed along the wall, vn tan(gamma) = {tangential:.2f} c, exceeds "
        f"{MAX_TANGENTIAL_SPEED:g} c, the most at which the default run was seen to resolve "
        "the contact (docs/benchmarks/stability_speeds.md): expect disk points inside the wall, "
        "or a contact longer than the wall"
    )


# How the body is carried to finer disks, four options (docs/model.md, "The
# model as the resolution grows"). By default a disk of any N hitting the wall
# is one body refined, a reading whose limit exists: one continuous surface
# per seed of correlation length 0.2 R, the contact's lengths fixed in R, and
# the barrier against triangles turning inside out (builder.study_names'
# "profile-floor"). The paper's scene, a draw per surface point and the
# contact following the spacing, is the named reading "paper"; a binary scene
# (target disk) refuses the continuous profile, the barrier and the physical
# contact, and keeps the paper's.
BODY = {
    "roughness_length": 0.2,
    "roughness_profile": "continuous",
    "contact_scaling": "physical",
    "area_floor": 0.5,
}
PAPER = {
    "roughness_length": 0.0,
    "roughness_profile": "sampled",
    "contact_scaling": "spacing",
    "area_floor": 0.0,
}
BODY_DEFAULTS = {"wall": BODY, "disk": PAPER}
WHY_BODY = (
    "with --roughness-profile, --contact-scaling and --area-floor it carries the body to finer "
    "disks: by default, at --target wall, one body refined, whose limit as n_disk grows exists "
    "(0.2, continuous, physical, 0.5: the reading profile-floor); the paper's scene, a draw per "
    "surface point, is 0, sampled, spacing, 0 (the reading paper: a study file's [scene] "
    'limit = "paper"), --target disk\'s default'
)
SEE_BODY = "the default is the body's (see --roughness-length)"


def body_defaults(name: str) -> tuple:
    """An option's default by target, ``Option.by_target``."""
    return tuple((target, values[name]) for target, values in BODY_DEFAULTS.items())


# Molecule IDs tell the bodies apart and which wall points are held fixed.
DISK, WALL_FREE, WALL_HELD = 1, 2, 3


# The contact is cut off at the spacing; exp(-a l) must have died out by then,
# or every point that crosses the cutoff jumps in energy by V0 exp(-a cutoff).
# The study has 20 decay lengths in it (a R = 300, 800 points); a 20,000-point
# disk at a R = 300 has 4, and its energy grew by 15 % into the contact (docs/contact.md).
MIN_CUTOFF_DECAYS = 15.0


def require_contact_resolved(decay: float, spacing: float, spec=None) -> None:
    """Refuse a contact whose exponential is still large at the cutoff.

    ``decay`` is the contact's a R as the scene has it (``SceneSpec.contact_decay``
    times R), ``spacing`` the cutoff in R."""
    if decay * spacing < MIN_CUTOFF_DECAYS:
        scaled = spec is not None and spec.contact_scaling == "fixed"
        hint = "; contact_scaling spacing follows the resolution" if scaled else ""
        raise InputError(
            f"contact_a must make a R >= {math.ceil(MIN_CUTOFF_DECAYS / spacing)} at this "
            f"resolution (wall spacing {spacing:.4f} R, the cutoff: at least "
            f"{MIN_CUTOFF_DECAYS:g} decay lengths within it), got a R = {decay:g}{hint} "
            "(docs/contact.md)"
        )


# Every option of a scene, declared once (builder/declared.py): SceneSpec's
# fields and checks, the command line's options (builder/cli.py, runner
# study), a study file's [scene] keys and the "made by" command line follow
# from this table. The order is the "made by" command line's.
LATTICE_NAMES = tuple(bodies.LATTICES)
SCENE_OPTIONS = (
    Option("lattice", "random", "disk lattice; the wall is always random", words=LATTICE_NAMES,
           study=False),
    Option("seed", 1, "sample seed", SEED, study=False),
    Option("gamma_deg", 45.0, "incidence angle", ANGLE, scene_numbers=GAMMA, flag="--gamma",
           study=False),  # the code's 0 (head-on) too
    Option("vn", 0.1, "normal approach speed: where the default run resolves the contact "
           "(docs/benchmarks/stability_speeds.md)", VN, scene_numbers=SUBSONIC, study=False),
    Option("roughness", 0.03, "std of the surface roughness", ROUGHNESS, made_by="always"),
    Option("n_disk", 800, "points in the disk", N_DISK, made_by="always"),
    Option("radius", 1.0, "disk radius; every length and time scales with it", RADIUS,
           made_by="always"),
    Option("wall_width", 8.0, "the wall's width (docs/model.md section 1; on grazing angles, "
           "its choices as built)", WALL_WIDTH, applies="wall", made_by="always"),
    Option("contact_a", 300.0, "decay rate of the contact, a R at 800 disk points with "
           "--contact-scaling spacing", CONTACT_A, made_by="always"),
    Option("target", "wall", "what the disk hits: the wall, or a second free disk, both moving "
           "so that the centre of mass is at rest (docs/model.md, 'Two disks')", words=TARGETS,
           made_by="changed"),
    Option("partner_lattice", None, "--target disk: the second disk's lattice (default: the "
           "disk's)", words=LATTICE_NAMES, applies="disk", made_by="changed", kind=str | None),
    Option("partner", "independent", "--target disk: independent, image (the disk itself "
           "turned by 180 degrees, a symmetric collision), image-held (that image held, "
           "immovable) or surface (a held, nearly flat wall built like a disk's surface)",
           words=PARTNERS, applies="disk", made_by="changed"),
    # points in the wall, or "density": the disk's number density; None: twice
    # the disk's (the paper's 1,600 for 800), so that the wall follows the
    # disk's resolution. A record from before the wall's readings had "density".
    Option("n_wall", None, "points in the wall, or 'density': the disk's number density "
           "(default: twice --n-disk, the paper's 1600 for 800)", N_WALL, (WALL_DENSITY,),
           applies="wall", made_by="changed", before=WALL_DENSITY, kind=int | str | None),
    Option("wall_ka", 10.0, "the wall's spring constant in units of the random disk's ka (that "
           "of a random lattice at the disk's number density with wave speed c), the same for "
           "every disk lattice, or 'same-c': the wall's springs give it the wave speed c",
           WALL_KA, (WALL_SAME_C,), applies="wall", made_by="always", before=WALL_SAME_C,
           kind=float | str),
    Option("wall_fixed", "sides", "which wall points are held fixed", words=WALL_FIXED_CHOICES,
           applies="wall", made_by="always"),
    Option("wall_roughness", None, "std of the wall's surface roughness (default: the disk's, "
           "--roughness)", ROUGHNESS, applies="wall", made_by="changed", kind=float | None),
    *(Option(name, default, meaning, words=MODEL_READINGS[name], made_by="always",
             before=MODEL_READINGS[name][0])
      for name, default, meaning in MODEL_OPTIONS),
    Option("roughness_length", None, "the roughness's correlation length along the surface, 0 "
           "(each point drawn on its own, the paper) or a length (docs/model.md, 'The model as "
           "the resolution grows'); " + WHY_BODY, ROUGHNESS_LENGTH, (0.0, 0), hide_words=True,
           made_by="changed", before=PAPER["roughness_length"], kind=float | None,
           by_target=body_defaults("roughness_length")),
    Option("roughness_profile", None, "sampled: the roughness drawn at the surface's "
           "points, anew at every n_disk; continuous: one profile of correlation length "
           "roughness_length per seed, the same surface at every n_disk (docs/model.md, 'The "
           "model as the resolution grows'); " + SEE_BODY + ", sampled where --roughness-length "
           "is 0", words=ROUGHNESS_PROFILES,
           applies="wall", made_by="changed", before=PAPER["roughness_profile"], kind=str | None,
           by_target=body_defaults("roughness_profile")),
    Option("contact_scaling", None, "spacing: a R = contact_a sqrt(n_disk / 800) and V0 "
           "times sqrt(800 / n_disk), the contact's energy per length of surface held; fixed: a "
           "and V0 as at 800 points, the paper's; physical: a and the cutoff as at 800 points, "
           "the pressure over the modulus held (docs/model.md, 'The model as the resolution "
           "grows'); " + SEE_BODY, words=CONTACT_SCALINGS, made_by="changed",
           before=PAPER["contact_scaling"], kind=str | None,
           by_target=body_defaults("contact_scaling")),
    Option("area_floor", None, "J_c of a barrier against the bodies' triangles turning inside "
           "out: an energy on each triangle whose area falls below J_c times its area at rest, "
           "diverging as the area vanishes (docs/rough_contact.md); 0: no barrier, the springs "
           "alone; " + SEE_BODY, AREA_FLOOR, applies="wall", made_by="changed",
           before=PAPER["area_floor"], kind=float | None, by_target=body_defaults("area_floor")),
    Option("k2_over_k1", 3.0 / 7.0, "square lattice only: diagonal over nearest spring "
           "constant", K2_OVER_K1, study=False),
    Option("kb_over_ka", 1e-3, "bond over spring constant", KB_OVER_KA, study=False, cli=False),
    Option("wall_height", 2.0, "the wall's height", WALL_HEIGHT, study=False, cli=False),
    Option("contact_time_guess", 9.0, "centres the sliding contact on the wall",
           Range(0.0, 1000.0, unit="R/c"), study=False, cli=False),
    Option("start_gap", 0.1, "extra gap beyond the cutoff at start, in spacings",
           Range(0.0, 100.0, low_open=True), study=False, cli=False),
    Option("partner_seed", None, "--target disk: take sample N's disk as the second disk "
           "(default: a stream of the sample's own seed, so that each sample pairs two "
           "independent disks)", SEED, study=False, applies="disk", kind=int | None),
)  # fmt: skip
SCENE = by_name(SCENE_OPTIONS)
# A scene's numbers as one type: 60 and 60.0 must not write different metadata.
INTEGERS = tuple(o.name for o in SCENE_OPTIONS if o.numbers is not None and o.numbers.integer)
FLOATS = tuple(o.name for o in SCENE_OPTIONS if o.numbers is not None and not o.numbers.integer)


@with_options(SCENE_OPTIONS)
class SceneSpec:
    """Everything that defines a scene; the seed fixes all its random draws.
    Its fields are SCENE_OPTIONS's."""

    def __post_init__(self) -> None:
        if self.n_wall is None and isinstance(self.n_disk, (int, np.integer)):
            self.n_wall = 2 * int(self.n_disk)
        for name in BODY:  # None: the body's, by target (BODY_DEFAULTS)
            if getattr(self, name) is None:
                value = SCENE[name].default_for(self.target)
                if name == "roughness_profile" and self.roughness_length == 0.0:
                    value = PAPER[name]  # a draw per point has no profile to keep
                setattr(self, name, value)
        for name in INTEGERS:
            value = getattr(self, name)
            if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
                setattr(self, name, int(value))
        for name in FLOATS:
            value = getattr(self, name)
            if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
                value, bool
            ):
                setattr(self, name, float(value))

    def validate(self) -> None:
        for option in SCENE_OPTIONS:  # each alone, then what they must be together
            option.check(getattr(self, option.name))
        if self.roughness_length != 0.0 and (
            self.surface_row != "even"
            or (self.regular_surface == "lattice" and self.lattice != "random")
        ):
            raise InputError(
                "roughness_length applies to evenly spaced surface rows (surface_row even, "
                "regular_surface band), got surface_row "
                f"{self.surface_row}, regular_surface {self.regular_surface}, roughness_length "
                f"{self.roughness_length:g} (the default body's is {BODY['roughness_length']:g}; "
                "0: the paper's draw per point)"
            )
        if not N_WALL.contains(self.wall_points):
            raise InputError(
                f"n_wall: the wall would have {self.wall_points} points (n_disk {self.n_disk} "
                f"at the disk's density over a {self.wall_width:g} R wide wall); it must have "
                f"{N_WALL.describe()}"
            )
        if self.roughness_profile == "continuous" and self.roughness_length == 0.0:
            raise InputError(
                "roughness_profile continuous needs a correlation length: give roughness_length "
                f"in {ROUGHNESS_LENGTH.describe()}"
            )
        if self.target == "disk" and self.contact_scaling == "physical":
            raise InputError("contact_scaling physical applies to target wall")
        require_contact_resolved(self.contact_decay * self.radius, self.contact_cutoff, self)
        if self.regular_surface == "lattice":
            if self.lattice == "random":
                raise InputError(
                    "regular_surface lattice applies to the triangular and square disks, "
                    "got lattice random"
                )
            if self.surface_row != "even":
                raise InputError(
                    "surface_row random places a surface row, which regular_surface lattice "
                    "does not have (its surface is the lattice's own points)"
                )
        applies = {o.name: o.applies for o in SCENE_OPTIONS if o.applies}
        for name, target in applies.items():  # another target's option is refused, not ignored
            default = 2 * self.n_disk if name == "n_wall" else SCENE[name].default_for(self.target)
            if target != self.target and getattr(self, name) != default:
                raise InputError(
                    f"{name} applies to target disk (a second disk), got target wall"
                    if target == "disk"
                    else f"{name} applies to target wall; a binary scene (target disk) has no wall"
                )
        if self.target == "disk" and self.partner != "independent":
            for name in ("partner_lattice", "partner_seed"):
                if getattr(self, name) is not None:
                    raise InputError(
                        f"{name} applies to partner independent; partner image is the "
                        "disk's own image"
                    )
        if self.target == "disk" and self.wall_height != SCENE["wall_height"].default:
            raise InputError(
                "wall_height applies to target wall; a binary scene (target disk) has no wall"
            )

    @property
    def resolution_scale(self) -> float:
        """The disk's spacing over the 800-point disk's, sqrt(800 / n_disk):
        exactly 1 at 800 points."""
        return math.sqrt(REFERENCE_N_DISK / self.n_disk)

    @property
    def contact_decay(self) -> float:
        """The contact's a, per unit length: contact_a / R, over the resolution
        scale with contact_scaling "spacing" (a times the spacing fixed)."""
        a = self.contact_a / self.radius
        return a / self.resolution_scale if self.contact_scaling == "spacing" else a

    @property
    def step_scale(self) -> float:
        """What the time step is scaled by (dt "auto", runner.options): the
        finer body's spacing over its spacing in the paper's scene, the
        800-point disk on a 1,600-point 8 R x 2 R wall; exactly 1 there."""
        reference = REFERENCE_N_DISK * 2 / (8.0 * 2.0)  # the paper's wall's points per R^2
        wall = math.sqrt(reference * self.wall_width * self.wall_height / self.wall_points)
        return min(self.resolution_scale, wall)

    @property
    def contact_cutoff(self) -> float:
        """The contact's cutoff in R: the wall's spacing, or the paper's at
        every resolution with contact_scaling "physical"."""
        return PAPER_CUTOFF if self.contact_scaling == "physical" else self.wall_spacing

    @property
    def wall_spacing(self) -> float:
        """The wall's spacing in R, which is the contact's cutoff."""
        return bodies.triangular_spacing(self.wall_points / (self.wall_width * self.wall_height))

    @property
    def wall_points(self) -> int:
        """Points in the wall: n_wall, or the disk's number density times its area."""
        if self.n_wall != WALL_DENSITY:
            return int(self.n_wall)
        density = self.n_disk / np.pi
        return int(round(density * self.wall_width * self.wall_height))


@dataclass
class Scene:
    """Atoms and springs of a scene, in LAMMPS order, with its metadata."""

    spec: SceneSpec
    positions: np.ndarray  # (n, 2)
    velocities: np.ndarray  # (n, 2)
    types: np.ndarray  # (n,) LAMMPS atom types
    molecule: np.ndarray  # (n,) DISK, WALL_FREE or WALL_HELD
    springs: np.ndarray  # (m, 2) 0-based atom indices
    ka: np.ndarray  # (m,) quadratic spring constants
    info: dict = field(default_factory=dict)
    # the barrier's angles (builder.triangles.Triangles) with area_floor > 0, else None
    angles: object = None
    # where the disk's own frame was placed: positions = frame + disk_centre
    disk_centre: np.ndarray = field(default_factory=lambda: np.zeros(2))

    @property
    def frame_positions(self) -> np.ndarray:
        """The bodies in their own frames: the disk unplaced (exact, as both the
        disk's points and its centre lie on ``placement_quantum``'s grid).
        Only the angle and the speed make one sample's scenes differ in these."""
        frame = self.positions.copy()
        frame[self.molecule == DISK] -= self.disk_centre
        return frame

    @property
    def natural_lengths(self) -> np.ndarray:
        d = self.positions[self.springs[:, 0]] - self.positions[self.springs[:, 1]]
        return np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])


def wall_spring_constant(spec: SceneSpec) -> tuple[float, float, dict]:
    """The wall's ka, which depends on the wall's reading and not on the disk's lattice.

    The unit of ``wall_ka`` is the random disk's ka: the ka that gives a random
    lattice at the disk's number density (n_disk points in pi R^2) the wave speed
    c. For the random disk it is the disk's own ka, so ``wall_ka`` = 1 is docs/model.md's
    "one ka for every spring of both bodies"; the triangular and square disks meet
    the random disk's wall. "same-c": the ka that gives the wall, a random lattice
    at its own spacing, the wave speed c.

    Parameters
    ----------
    spec : SceneSpec
        The scene; only n_disk, radius and the wall's reading matter.

    Returns
    -------
    ka_wall : float
        The wall's quadratic spring constant.
    ka_reference : float
        The unit of ``wall_ka``: the random disk's ka.
    wall_material : dict
        The random lattice's entry of the materials table.
    """
    R = spec.radius
    # The same expression as the random disk's spacing (bodies.make_disk), so that
    # the random disk's ka and this reference are the same double.
    reference_spacing = bodies.lattice_spacing("random", spec.n_disk / np.pi) * R
    ka_reference, wall_material = spring_constant("random", reference_spacing)
    if spec.wall_ka == WALL_SAME_C:
        return spring_constant("random", spec.wall_spacing * R)[0], ka_reference, wall_material
    return spec.wall_ka * ka_reference, ka_reference, wall_material


def speed_unit(spec: SceneSpec, spacing: float, ka_disk: float) -> float:
    """The unit of ``spec.vn`` in units of c: c itself, or with ``speed_unit``
    "spring" the one-dimensional sound speed of the disk's springs, d sqrt(ka / m),
    d the disk's nominal spacing (docs/model.md section 8; m = 1)."""
    if spec.speed_unit == "spring":
        return float(spacing * np.sqrt(ka_disk))
    return 1.0


def contact_energy(spec: SceneSpec, disk_points: int) -> float:
    """The contact's V0 = a m c^2 R / 2 (docs/model.md section 2), m one point's mass
    or, with ``contact_mass`` "disk", the disk's (m = c = 1; a R = contact_a).

    With ``contact_scaling`` "spacing" V0 is that times the resolution scale,
    sqrt(800 / n_disk): the contact's energy per length of surface, V0 over
    the spacing, stays the 800-point disk's. With "physical" V0 is the
    800-point disk's over the resolution scale: the contact's pressure, V0 a
    over the spacing, then grows as n_disk, as the elastic modulus does in
    units of m c^2 (a body of n_disk points of mass m), and keeps its ratio
    to it."""
    if spec.contact_scaling == "physical":
        mass = float(disk_points) * spec.resolution_scale**2 if spec.contact_mass == "disk" else 1.0
        return spec.contact_a / 2.0 * mass / spec.resolution_scale
    mass = float(disk_points) if spec.contact_mass == "disk" else 1.0
    energy = spec.contact_a / 2.0 * mass
    return energy * spec.resolution_scale if spec.contact_scaling == "spacing" else energy


def units_info(spec: SceneSpec, disk_material: dict, disk_spacing: float, ka_disk: float) -> dict:
    """scene.json's units: R, c, m, where c comes from, and the unit of vn."""
    return {
        "length": "R",
        "velocity": "c",
        "time": "R/c",
        "mass": "m (one point)",
        "R": spec.radius,
        "c": 1.0,
        "m": 1.0,
        "c_source": f"calibrated: c^2 = {disk_material['c2']:.5f} ka d^2/m "
        f"+- {disk_material['c2_se']:.1g} ({disk_material['samples']} strips)",
        # what vn is in units of: c, or the springs' d sqrt(ka / m) (spec.speed_unit)
        "vn_unit": speed_unit(spec, disk_spacing, ka_disk),
    }
