"""A scene: a disk placed above a wall, moving towards it at an angle.

Coordinates: the wall's top face is near y = 0 and its centre at x = 0; the
wall normal is +y; the disk moves with velocity (v_n tan gamma, -v_n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ground.checks import Range
from ground.errors import InputError, require_choice

from . import bodies
from .materials import spring_constant

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
# The readings of the wall that the paper leaves open (MODEL.md section 8):
# n_wall is a number of points or "density" (the disk's number density), and
# wall_ka is the wall's spring constant over the random disk's (``wall_spring_constant``),
# or "same-c" (the ka that gives the wall the wave speed c). Neither depends on
# the disk's lattice, so that every lattice of a study meets the same wall.
WALL_DENSITY = "density"
WALL_SAME_C = "same-c"
# The readings of the model (MODEL.md section 8), each a SceneSpec field: its
# choices, the one this project first read the paper's text as first. The
# default (SceneSpec) is the rule's pick, which may be another.
MODEL_READINGS = {
    "contact_mass": ("point", "disk"),
    "speed_unit": ("c", "spring"),
    "roughness_direction": bodies.ROUGHNESS_DIRECTIONS,
    "surface_row": bodies.SURFACE_ROWS,
    "regular_surface": bodies.REGULAR_SURFACES,
}
# What a scene.json, result or impacts.csv row made before these options means.
FIRST_READING = {name: choices[0] for name, choices in MODEL_READINGS.items()}
# The ranges of the scene's numbers, for SceneSpec.validate and the command line
# (builder/cli.py) alike.
ANGLE = Range(0.0, 90.0, low_open=True, high_open=True, unit="degrees from the wall's normal")
SEED = Range(0, 2**32 - 1, integer=True)
RADIUS = Range(1e-3, 1000.0, unit="R, the unit of length")
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
CONTACT_SCALINGS = ("spacing", "fixed")
# The disk at which every setting that follows the resolution is the paper's.
REFERENCE_N_DISK = 800
# Where the default run resolves the contact (bench/stability.py,
# docs/benchmarks/stability_speeds.md, three seeds per point): every normal speed up
# to 0.4 c at speeds along the wall up to 0.8 c; at 0.5 c and 1.0 c along the
# wall segments stretch past the contact's reach. --vn stops at 0.3 c, the
# speed study's last (docs/speed.md).
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


@dataclass
class SceneSpec:
    """Everything that defines a scene; the seed fixes all its random draws."""

    lattice: str = "random"
    seed: int = 1
    gamma_deg: float = 45.0  # incidence angle from the wall normal; 0 is head-on
    vn: float = 0.1  # normal approach speed, in units of c
    radius: float = 1.0  # R, the unit of length
    n_disk: int = 800  # target number of points in the disk
    # The wall's and the model's reading (MODEL.md section 8) that the rule picks:
    # docs/model.md, docs/model_readings.md.
    # points in the wall, or "density": the disk's number density; None: twice
    # the disk's (the paper's 1,600 for 800), so that the wall follows the
    # disk's resolution
    n_wall: int | str | None = None
    roughness: float = 0.03  # std of surface displacement, in R
    # the roughness's correlation length along the surface, in R; 0: each
    # point drawn on its own (the paper), whose slopes grow as the disk is refined
    roughness_length: float = 0.0
    k2_over_k1: float = 3.0 / 7.0  # square lattice only
    kb_over_ka: float = 1e-3
    wall_fixed: str = "sides"
    wall_width: float = 8.0  # in R
    wall_height: float = 2.0  # in R
    wall_ka: float | str = 10.0  # wall's ka over the random disk's, or "same-c": wave speed c
    contact_a: float = 300.0  # decay rate of the contact, a R (at 800 points with "spacing")
    # the contact as the disk is refined: a R and V0 "fixed", or following the spacing
    contact_scaling: str = "spacing"
    # The readings of the model (MODEL.md section 8; MODEL_READINGS below).
    contact_mass: str = "disk"  # V0 = a m c^2 R / 2 with m one point's mass or the disk's
    speed_unit: str = "c"  # vn in units of c, or of the springs' sound speed d sqrt(ka / m)
    roughness_direction: str = "normal"  # along the surface normal, or in both directions
    surface_row: str = "even"  # the disk's surface row: evenly spaced, or at random
    regular_surface: str = "band"  # a regular disk's surface: a joined row, or its own points
    contact_time_guess: float = 9.0  # R / c; centres the sliding contact on the wall
    start_gap: float = 0.1  # extra gap beyond the cutoff at start, in spacings
    # What the disk hits: the wall, or a second disk (builder/binary.py).
    target: str = "wall"
    partner_lattice: str | None = None  # the second disk's lattice; None: the disk's
    partner_seed: int | None = None  # None: the sample's own third stream; N: sample N's disk
    partner: str = "independent"  # "image": the disk turned by 180 degrees; PARTNERS

    def __post_init__(self) -> None:
        if self.n_wall is None and isinstance(self.n_disk, (int, np.integer)):
            self.n_wall = 2 * int(self.n_disk)
        # Same spec, same files: 60 and 60.0 must not write different metadata.
        for name, kind in (("seed", int), ("n_disk", int), ("n_wall", int)):
            value = getattr(self, name)
            if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
                setattr(self, name, kind(value))
        for name in (
            "gamma_deg",
            "vn",
            "radius",
            "roughness",
            "roughness_length",
            "k2_over_k1",
            "kb_over_ka",
            "wall_width",
            "wall_height",
            "wall_ka",
            "contact_a",
            "contact_time_guess",
            "start_gap",
        ):
            value = getattr(self, name)
            if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
                value, bool
            ):
                setattr(self, name, float(value))

    def validate(self) -> None:
        require_choice("lattice", self.lattice, bodies.LATTICES)
        SEED.check("seed", self.seed)
        GAMMA.check("gamma_deg", self.gamma_deg)
        SUBSONIC.check("vn", self.vn)
        RADIUS.check("radius", self.radius)
        N_DISK.check("n_disk", self.n_disk)
        if self.n_wall != WALL_DENSITY and not N_WALL.contains(self.n_wall):
            raise InputError(
                f"n_wall must be {N_WALL.describe()} or {WALL_DENSITY!r}, got {self.n_wall!r}"
            )
        ROUGHNESS.check("roughness", self.roughness)
        if self.roughness_length != 0.0:
            ROUGHNESS_LENGTH.check("roughness_length", self.roughness_length)
            if self.surface_row != "even" or (
                self.regular_surface == "lattice" and self.lattice != "random"
            ):
                raise InputError(
                    "roughness_length applies to evenly spaced surface rows (surface_row even, "
                    "regular_surface band), got surface_row "
                    f"{self.surface_row}, regular_surface {self.regular_surface}"
                )
        require_choice("contact_scaling", self.contact_scaling, CONTACT_SCALINGS)
        K2_OVER_K1.check("k2_over_k1", self.k2_over_k1)
        KB_OVER_KA.check("kb_over_ka", self.kb_over_ka)
        require_choice("wall_fixed", self.wall_fixed, WALL_FIXED_CHOICES)
        WALL_WIDTH.check("wall_width", self.wall_width)
        WALL_HEIGHT.check("wall_height", self.wall_height)
        if self.wall_ka != WALL_SAME_C and not WALL_KA.contains(self.wall_ka):
            raise InputError(
                f"wall_ka must be {WALL_KA.describe()} or {WALL_SAME_C!r}, got {self.wall_ka!r}"
            )
        if not N_WALL.contains(self.wall_points):
            raise InputError(
                f"n_wall: the wall would have {self.wall_points} points (n_disk {self.n_disk} "
                f"at the disk's density over a {self.wall_width:g} R wide wall); it must have "
                f"{N_WALL.describe()}"
            )
        CONTACT_A.check("contact_a", self.contact_a)
        require_contact_resolved(self.contact_decay * self.radius, self.wall_spacing, self)
        for name, choices in MODEL_READINGS.items():
            require_choice(name, getattr(self, name), choices)
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
        Range(0.0, 1000.0).check("contact_time_guess", self.contact_time_guess)
        Range(0.0, 100.0, low_open=True).check("start_gap", self.start_gap)
        require_choice("target", self.target, TARGETS)
        if self.target == "wall":
            for name in ("partner_lattice", "partner_seed"):
                if getattr(self, name) is not None:
                    raise InputError(
                        f"{name} applies to target disk (a second disk), got target wall"
                    )
            if self.partner != SceneSpec.partner:
                raise InputError("partner applies to target disk (a second disk), got target wall")
        else:
            for name in WALL_OPTIONS:
                default = 2 * self.n_disk if name == "n_wall" else getattr(SceneSpec, name)
                if getattr(self, name) != default:
                    raise InputError(
                        f"{name} applies to target wall; a binary scene (target disk) has no wall"
                    )
            if self.partner_lattice is not None:
                require_choice("partner_lattice", self.partner_lattice, bodies.LATTICES)
            if self.partner_seed is not None:
                SEED.check("partner_seed", self.partner_seed)
            require_choice("partner", self.partner, PARTNERS)
            if self.partner != "independent":
                for name in ("partner_lattice", "partner_seed"):
                    if getattr(self, name) is not None:
                        raise InputError(
                            f"{name} applies to partner independent; partner image is the "
                            "disk's own image"
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
    c. For the random disk it is the disk's own ka, so ``wall_ka`` = 1 is MODEL.md's
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
    d the disk's nominal spacing (MODEL.md section 8; m = 1)."""
    if spec.speed_unit == "spring":
        return float(spacing * np.sqrt(ka_disk))
    return 1.0


def contact_energy(spec: SceneSpec, disk_points: int) -> float:
    """The contact's V0 = a m c^2 R / 2 (MODEL.md section 2), m one point's mass
    or, with ``contact_mass`` "disk", the disk's (m = c = 1; a R = contact_a).

    With ``contact_scaling`` "spacing" V0 is that times the resolution scale,
    sqrt(800 / n_disk): the contact's energy per length of surface, V0 over
    the spacing, stays the 800-point disk's."""
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
