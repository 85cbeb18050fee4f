"""A scene: a disk placed above a wall, moving towards it at an angle.

Coordinates: the wall's top face is near y = 0 and its centre at x = 0; the
wall normal is +y; the disk moves with velocity (v_n tan gamma, -v_n).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from functools import lru_cache

import numpy as np

from . import bodies
from .bodies import SURFACE, Body
from .checks import Range
from .errors import InputError, require_choice
from .geometry import Polyline
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


def placement_quantum(radius: float) -> float:
    """The grid of the disk's points in its own frame and of its placement: a
    power of two near radius * 2**-40 (about 1e-12 R). Points and offsets on
    one such grid, below 2**12 R, add exactly in binary, so the disk placed by
    LAMMPS (displace_atoms) is bit for bit the disk placed here, and every
    spring's length is the same double in either frame."""
    return 2.0 ** (math.floor(math.log2(radius)) - 40)


def on_grid(values: np.ndarray, quantum: float) -> np.ndarray:
    """``values`` rounded to multiples of ``quantum`` (exact: a power of two)."""
    return np.round(np.asarray(values) / quantum) * quantum


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


def build_bodies(spec: SceneSpec) -> tuple[Body, Body]:
    """The disk and the wall of a sample, in units of R; independent of the angle.

    Cached, because a sweep builds the same sample for every angle, and the
    wall, which depends on the seed only, for every lattice of that seed.

    Parameters
    ----------
    spec : SceneSpec
        The scene; only its lattice, seed, sizes and roughness matter here.

    Returns
    -------
    disk, wall : Body
        Points, springs and surfaces of each body, unscaled and unplaced.
    """
    return (
        sample_disk(spec),
        _wall(
            spec.seed,
            spec.wall_points,
            spec.wall_width,
            spec.wall_height,
            spec.roughness,
            spec.wall_fixed,
            spec.roughness_direction,
            spec.roughness_length,
        ),
    )


def _sample_seeds(seed: int) -> tuple[np.random.SeedSequence, ...]:
    """Independent streams for the disk, the wall and the second disk of one
    sample (a child's stream depends on its index only, so the disk and the
    wall are those of the two streams this drew before the second disk)."""
    return tuple(np.random.SeedSequence(seed).spawn(3))


@lru_cache(maxsize=8)
def _disk(lattice, seed, n_disk, roughness, k2_over_k1, *readings) -> Body:
    rng = np.random.default_rng(_sample_seeds(seed)[0])
    return bodies.make_disk(rng, lattice, n_disk, roughness, k2_over_k1, *readings)


@lru_cache(maxsize=4)
def _wall(seed, n_wall, width, height, roughness, wall_fixed, *readings) -> Body:
    rng = np.random.default_rng(_sample_seeds(seed)[1])
    return bodies.make_wall(rng, n_wall, width, height, roughness, wall_fixed, *readings)


def place_disk(
    disk_surface: np.ndarray,
    wall_row: np.ndarray,
    velocity: np.ndarray,
    target_gap: float,
    contact_x: float,
) -> np.ndarray:
    """Centre of the disk such that it is ``target_gap`` from the wall's surface.

    The disk starts high enough to clear every asperity, a little upstream so
    that it first comes into range near ``contact_x``, and then moves along its
    velocity until its closest point is ``target_gap`` from the wall's
    polyline. Each step moves the disk by its current excess distance, which no
    point can overshoot (sphere tracing).
    """
    direction = velocity / np.linalg.norm(velocity)
    touch = -disk_surface[:, 1].min() + target_gap  # centre height at contact
    wall_top = wall_row[:, 1].max()
    safe = wall_top + touch + target_gap  # no point in range up here
    centre = np.array([contact_x, touch]) - direction * (safe - touch) / -direction[1]
    lowest = np.argsort(disk_surface[:, 1])[:8]
    wall = Polyline(wall_row)  # searched near each point only
    for _ in range(10000):
        points = disk_surface + centre
        # Only points that may be nearest: a point is at least its height over
        # the wall's top from the wall, and the lowest few bound the nearest
        # distance from above. The same distances, minimum and centre, for a
        # fraction of the points.
        bound = wall.distance(points[lowest]).min()
        near = points[:, 1] - wall_top <= bound
        excess = wall.distance(points[near]).min() - target_gap
        if excess < 1e-9 * target_gap:
            return centre
        centre = centre + excess * direction
    raise RuntimeError("disk placement did not converge")


def renumbered(springs: np.ndarray, order: np.ndarray, offset: int) -> np.ndarray:
    """A body's springs in the scene's atom order: atom ``order[k]`` of the
    body becomes atom ``offset + k``; each spring's ends in increasing order."""
    new_index = np.empty(len(order), int)
    new_index[order] = np.arange(len(order)) + offset
    return np.sort(new_index[springs], axis=1)


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


def sample_disk(spec: SceneSpec) -> Body:
    """The sample's disk, unscaled and unplaced (cached: ``_disk``)."""
    return _disk(
        spec.lattice,
        spec.seed,
        spec.n_disk,
        spec.roughness,
        spec.k2_over_k1,
        spec.roughness_direction,
        spec.surface_row,
        spec.regular_surface,
        spec.roughness_length,
    )


def build_scene(spec: SceneSpec) -> Scene:
    """Build, scale and place both bodies of a scene.

    Parameters
    ----------
    spec : SceneSpec
        The scene: lattice, seed, angle, speed, sizes, contact; validated first.

    Returns
    -------
    Scene
        Atoms (positions, velocities, types, molecules) and springs in LAMMPS
        order, and ``info``, the derived quantities scene.json holds.

    Raises
    ------
    builder.errors.InputError
        If ``spec`` is invalid or its lattice is not calibrated.
    """
    spec.validate()
    if spec.target == "disk":
        from .binary import build_binary_scene  # it builds on this module

        return build_binary_scene(spec)
    R = spec.radius
    disk, wall = build_bodies(spec)

    ka_disk, disk_material = spring_constant(spec.lattice, disk.spacing * R, spec.k2_over_k1)
    ka_wall, ka_reference, wall_material = wall_spring_constant(spec)
    cutoff = wall.spacing * R
    gamma = np.radians(spec.gamma_deg)
    speed = spec.vn * speed_unit(spec, disk.spacing * R, ka_disk)
    if speed >= 1.0:
        raise InputError(
            f"vn must make the normal speed below c; vn {spec.vn:g} in units of the springs' "
            f"sound speed is {speed:.3f} c"
        )
    velocity = np.array([speed * np.tan(gamma), -speed])

    # Centre the sliding contact on the wall, but keep the disk clear of its sides.
    reach = spec.wall_width / 2.0 - 1.5
    contact_x = -np.clip(0.5 * velocity[0] * spec.contact_time_guess, 0.0, reach) * R
    wall_row = wall.points[wall.surface] * R
    quantum = placement_quantum(R)
    disk_points = on_grid(disk.points * R, quantum)
    centre = on_grid(
        place_disk(
            disk_points[disk.surface],
            wall_row,
            velocity,
            cutoff + spec.start_gap * cutoff,
            contact_x,
        ),
        quantum,
    )

    # Atom order: the wall's surface row first, left to right, so that
    # consecutive tags are neighbours on the contact polyline; then the rest of
    # the wall, the disk's surface row and the disk's interior.
    row = wall.surface[wall.role[wall.surface] == SURFACE]
    wall_rest = np.setdiff1d(np.arange(len(wall.points)), row)
    disk_rest = np.setdiff1d(np.arange(len(disk.points)), disk.surface)
    wall_order = np.concatenate([row, wall_rest])
    disk_order = np.concatenate([disk.surface, disk_rest])
    n_wall = len(wall_order)

    wall_types = np.choose(wall.role, [WALL_SURFACE, WALL_INTERIOR, WALL_FIXED])[wall_order]
    disk_types = np.where(disk.role == SURFACE, DISK_SURFACE, DISK_INTERIOR)[disk_order]
    positions = np.concatenate([wall.points[wall_order] * R, disk_points[disk_order] + centre])
    velocities = np.zeros_like(positions)
    velocities[n_wall:] = velocity

    springs = np.concatenate(
        [renumbered(wall.springs, wall_order, 0), renumbered(disk.springs, disk_order, n_wall)]
    )
    ka = np.concatenate([ka_wall * wall.stiffness, ka_disk * disk.stiffness])
    types = np.concatenate([wall_types, disk_types])
    held = wall.held if wall.held is not None else np.zeros(len(wall.points), bool)
    molecule = np.concatenate(
        [np.where(held[wall_order], WALL_HELD, WALL_FREE), np.full(len(disk_order), DISK)]
    )

    scene = Scene(spec, positions, velocities, types, molecule, springs, ka, disk_centre=centre)
    scene.info = scene_info(
        scene,
        disk,
        wall,
        ka_disk,
        ka_wall,
        ka_reference,
        cutoff,
        disk_material,
        wall_material,
        velocity,
        len(row),
    )
    return scene


def scene_info(
    scene: Scene,
    disk: Body,
    wall: Body,
    ka_disk: float,
    ka_wall: float,
    ka_reference: float,
    cutoff: float,
    disk_material: dict,
    wall_material: dict,
    velocity: np.ndarray,
    n_row: int,
) -> dict:
    """Derived quantities that a run and its analysis need."""
    spec = scene.spec
    R = spec.radius
    in_disk = scene.molecule == DISK
    disk_xy = scene.positions[in_disk]
    com = disk_xy.mean(axis=0)  # all points have mass 1
    inertia = float(((disk_xy - com) ** 2).sum())
    lengths = scene.natural_lengths
    row = scene.positions[:n_row]
    longest_segment = float(np.linalg.norm(np.diff(row, axis=0), axis=1).max())
    a = spec.contact_decay
    return {
        "spec": asdict(spec),
        "units": units_info(spec, disk_material, disk.spacing * R, ka_disk),
        "disk_material": disk_material,
        "wall_material": wall_material,
        "n_atoms": int(len(scene.positions)),
        "n_disk_points": int(in_disk.sum()),
        "n_wall_points": int((~in_disk).sum()),
        "n_springs": int(len(scene.springs)),
        "atom_types": {str(k): v for k, v in TYPE_NAMES.items()},
        "wall_row_tags": [1, n_row],
        "wall_longest_segment": longest_segment,
        "disk_spacing": float(disk.spacing * R),
        "wall_spacing": float(wall.spacing * R),
        "max_natural_length": float(lengths.max()),
        "ka_disk": float(ka_disk),
        "ka_wall": float(ka_wall),
        # the unit of spec.wall_ka: the same for every disk lattice (wall_spring_constant)
        "ka_wall_reference": float(ka_reference),
        "kb_over_ka": spec.kb_over_ka,
        "contact": {
            "a": float(a),
            "V0": float(contact_energy(spec, in_disk.sum())),
            "cutoff": float(cutoff),
        },
        "disk_mass": float(in_disk.sum()),
        "disk_inertia": inertia,
        "disk_inertia_ratio": float(inertia / (in_disk.sum() * R * R)),
        "initial_com": com.tolist(),
        "initial_velocity": velocity.tolist(),
        "cot_gamma": float(abs(velocity[1]) / velocity[0]) if velocity[0] > 0 else None,
    }
