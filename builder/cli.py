"""The scene's command-line options, shared by the builder, the runner and the study.

Every value goes through ground.checks: a number outside its range, a
non-finite one or an unknown choice is refused with one line that names the
option and what it may be, exit status 2, before anything is written.
"""

from __future__ import annotations

import argparse

from ground.errors import InputError

from .scene import (
    ANGLE,
    CONTACT_A,
    K2_OVER_K1,
    N_DISK,
    N_WALL,
    NU,
    RADIUS,
    ROUGHNESS,
    ROUGHNESS_LENGTH,
    SEED,
    VN,
    WALL_KA,
    WALL_WIDTH,
)


class OneLineParser(argparse.ArgumentParser):
    """Errors as a single line and exit status 2 (argparse prints the usage too)."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


def roughness_length(text: str) -> float:
    """--roughness-length: 0 (each point on its own), or a correlation length."""
    try:
        if float(text) == 0.0:
            return 0.0
    except ValueError:
        pass
    return ROUGHNESS_LENGTH(text)


# what tests/cli/test_bad_input.py feeds it: below, above and not numbers (0 is a value)
roughness_length.bad_values = ("-0.1", "0.001", "2", "nan", "abc")


def wall_points(text: str) -> int | str:
    """--n-wall: a number of points, or "density" (the disk's number density)."""
    if text == "density":
        return text
    try:
        return N_WALL(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"must be {N_WALL.describe()} or 'density', got {text}"
        ) from None


def wall_spring(text: str) -> float | str:
    """--wall-ka: the wall's ka over the random disk's, or "same-c"."""
    if text == "same-c":
        return text
    try:
        return WALL_KA(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"must be {WALL_KA.describe()} or 'same-c', got {text}"
        ) from None


wall_points.__name__ = wall_spring.__name__ = "reading"
# what each takes besides its word (tests/cli/test_bad_input.py feeds it bad numbers)
wall_points.numbers, wall_spring.numbers = N_WALL, WALL_KA


def add_wall_arguments(group, defaults: bool = True) -> None:
    """The readings of the wall (MODEL.md section 8); the study's take None as 'preset'."""
    from .scene import WALL_FIXED_CHOICES, SceneSpec

    spec = SceneSpec()
    group.add_argument(
        "--n-wall",
        type=wall_points,
        default=None,  # twice the disk's points (SceneSpec)
        help=f"points in the wall, {N_WALL.describe()}, or 'density': the disk's number "
        "density (default: twice --n-disk, the paper's 1600 for 800)",
    )
    group.add_argument(
        "--wall-ka",
        type=wall_spring,
        default=spec.wall_ka if defaults else None,
        help=f"the wall's spring constant in units of the random disk's ka (that of a random "
        f"lattice at the disk's number density with wave speed c), the same for every disk "
        f"lattice, {WALL_KA.describe()}, or 'same-c': the wall's springs give it the wave speed c "
        f"(default: {spec.wall_ka:g})",
    )
    group.add_argument(
        "--wall-fixed",
        choices=WALL_FIXED_CHOICES,
        default=spec.wall_fixed if defaults else None,
        help=f"which wall points are held fixed (default: {spec.wall_fixed})",
    )
    group.add_argument(
        "--wall-width",
        type=WALL_WIDTH,
        default=spec.wall_width if defaults else None,
        help=f"the wall's width, {WALL_WIDTH.describe()} (default: {spec.wall_width:g}, "
        "docs/model.md section 1; on grazing angles, its choices as built)",
    )


# The readings of the model (MODEL.md section 8), SceneSpec's fields by option,
# with what each choice means.
MODEL_OPTIONS = {
    "contact_mass": (
        "--contact-mass",
        "the m of the contact's V0 = a m c^2 R / 2: one point's mass, or the disk's",
    ),
    "speed_unit": (
        "--speed-unit",
        "the unit of --vn: c, the calibrated wave speed, or the disk springs' "
        "one-dimensional sound speed d sqrt(ka / m)",
    ),
    "roughness_direction": (
        "--roughness-direction",
        "surface points displaced along the surface normal, or in both directions",
    ),
    "surface_row": (
        "--surface-row",
        "the disk's surface row evenly spaced on the circle, or a Poisson-disk sample of it",
    ),
    "regular_surface": (
        "--regular-surface",
        "the triangular and square disks' surface: a row joined to the lattice by a band of "
        "springs, or the lattice's own outermost points",
    ),
}


def add_model_arguments(group, defaults: bool = True) -> None:
    """The readings of the model (MODEL.md section 8); the study's take None as 'preset'."""
    from .scene import MODEL_READINGS, SceneSpec

    for name, (option, meaning) in MODEL_OPTIONS.items():
        default = getattr(SceneSpec, name)
        group.add_argument(
            option,
            choices=MODEL_READINGS[name],
            default=default if defaults else None,
            help=f"{meaning} (default: {default})",
        )


def add_scene_arguments(parser: argparse.ArgumentParser) -> None:
    """The options that define a scene (MODEL.md sections 1, 2 and 4)."""
    from .bodies import LATTICES
    from .scene import CONTACT_SCALINGS, PARTNERS, TARGETS

    group = parser.add_argument_group("scene")
    group.add_argument(
        "--lattice",
        choices=LATTICES,
        default="random",
        help="disk lattice (default: random); the wall is always random",
    )
    group.add_argument(
        "--seed", type=SEED, default=1, help=f"sample seed, {SEED.describe()} (default: 1)"
    )
    group.add_argument(
        "--gamma",
        type=ANGLE,
        default=45.0,
        help=f"incidence angle, {ANGLE.describe()} (default: 45)",
    )
    group.add_argument(
        "--vn",
        type=VN,
        default=0.1,
        help=f"normal approach speed, {VN.describe()}: where the default run resolves "
        "the contact (docs/benchmarks/stability_speeds.md) (default: 0.1)",
    )
    group.add_argument(
        "--radius",
        type=RADIUS,
        default=1.0,
        help=f"disk radius, {RADIUS.describe()} (default: 1)",
    )
    group.add_argument(
        "--n-disk",
        type=N_DISK,
        default=800,
        help=f"points in the disk, {N_DISK.describe()} (default: 800)",
    )
    group.add_argument(
        "--roughness",
        type=ROUGHNESS,
        default=0.03,
        help=f"std of the surface roughness, {ROUGHNESS.describe()} (default: 0.03)",
    )
    group.add_argument(
        "--roughness-length",
        type=roughness_length,
        default=0.0,
        help="the roughness's correlation length along the surface, 0 (each point drawn on "
        f"its own, the paper; default) or {ROUGHNESS_LENGTH.describe()} (docs/model.md, "
        "'The model as the resolution grows')",
    )
    square = group.add_mutually_exclusive_group()
    square.add_argument(
        "--k2-over-k1",
        type=K2_OVER_K1,
        default=None,
        help=f"square lattice only: diagonal over nearest spring constant, "
        f"{K2_OVER_K1.describe()} (default: 3/7)",
    )
    square.add_argument(
        "--nu",
        type=NU,
        default=None,
        help=f"square lattice only: k2/k1 that gives this Poisson ratio along the axes, "
        f"{NU.describe()}; a scene needs the ratio calibrated (0.1 and 0.3 are; "
        "python -m calibration run --square K2_OVER_K1 adds one)",
    )
    # no defaults here: a binary scene refuses a wall option given (spec_from_args)
    add_wall_arguments(group, defaults=False)
    group.add_argument(
        "--target",
        choices=TARGETS,
        default="wall",
        help="what the disk hits: the wall, or a second free disk, both moving so that the "
        "centre of mass is at rest (default: wall; docs/model.md, 'Two disks')",
    )
    group.add_argument(
        "--partner-lattice",
        choices=LATTICES,
        default=None,
        help="--target disk: the second disk's lattice (default: the disk's)",
    )
    group.add_argument(
        "--partner-seed",
        type=SEED,
        default=None,
        help="--target disk: take sample N's disk as the second disk (default: a stream of "
        "the sample's own seed, so that each sample pairs two independent disks)",
    )
    group.add_argument(
        "--partner",
        choices=PARTNERS,
        default="independent",
        help="--target disk: independent (default), or image: the disk itself turned by 180 "
        "degrees, which makes the collision symmetric (docs/model.md, 'Two disks')",
    )
    group.add_argument(
        "--contact-a",
        type=CONTACT_A,
        default=300.0,
        help=f"decay rate of the contact, {CONTACT_A.describe()}, at 800 disk points with "
        "--contact-scaling spacing (default: 300)",
    )
    group.add_argument(
        "--contact-scaling",
        choices=CONTACT_SCALINGS,
        default="spacing",
        help="spacing: a R = contact_a sqrt(n_disk / 800) and V0 times sqrt(800 / n_disk), "
        "the contact's energy per length of surface held (default); fixed: a and V0 as at "
        "800 points, the paper's (docs/model.md, 'The model as the resolution grows')",
    )
    add_model_arguments(parser.add_argument_group("the readings of the model (MODEL.md section 8)"))


# The wall's options by SceneSpec field (add_wall_arguments).
WALL_ARGUMENTS = {
    "n_wall": "--n-wall",
    "wall_ka": "--wall-ka",
    "wall_fixed": "--wall-fixed",
    "wall_width": "--wall-width",
}

# SceneSpec's fields by the options that set them, for messages the user can act on.
OPTIONS = {
    "gamma_deg": "--gamma",
    "vn": "--vn",
    "n_disk": "--n-disk",
    "n_wall": "--n-wall",
    "contact_a": "--contact-a",
    "contact_scaling": "--contact-scaling",
    "roughness_length": "--roughness-length",
    "wall_ka": "--wall-ka",
    "wall_width": "--wall-width",
    "k2_over_k1": "--k2-over-k1",
    "roughness": "--roughness",
    "radius": "--radius",
    "seed": "--seed",
    "target": "--target",
    "partner_lattice": "--partner-lattice",
    "partner_seed": "--partner-seed",
    "partner": "--partner",
    **{name: option for name, (option, _) in MODEL_OPTIONS.items()},
}


def validate_spec(spec) -> None:
    """SceneSpec.validate, its message naming the option rather than the field."""
    try:
        spec.validate()
    except InputError as error:
        word, _, rest = str(error).partition(" ")
        field, colon = word.rstrip(":"), word[len(word.rstrip(":")) :]
        if field in OPTIONS:
            raise InputError(f"{OPTIONS[field]}{colon} {rest}") from None
        raise


def spec_from_args(args: argparse.Namespace):
    """The SceneSpec of parsed scene options; an option that does not apply to
    the chosen lattice is refused, not ignored."""
    from .materials import square_ratio_for_poisson
    from .scene import SceneSpec

    k2_over_k1 = SceneSpec.k2_over_k1
    if args.k2_over_k1 is not None or args.nu is not None:
        if args.lattice != "square":
            option = "--nu" if args.nu is not None else "--k2-over-k1"
            raise InputError(f"{option} applies to --lattice square only, got {args.lattice}")
        k2_over_k1 = square_ratio_for_poisson(args.nu) if args.nu is not None else args.k2_over_k1
    wall = {name: getattr(args, name) for name in WALL_ARGUMENTS}
    if args.target == "disk":
        for name, value in wall.items():
            if value is not None:
                raise InputError(
                    f"{WALL_ARGUMENTS[name]} applies to --target wall; a binary scene "
                    "(--target disk) has no wall"
                )
    else:
        for name, option in (
            ("partner_lattice", "--partner-lattice"),
            ("partner_seed", "--partner-seed"),
        ):
            if getattr(args, name) is not None:
                raise InputError(f"{option} applies to --target disk, got --target {args.target}")
        if args.partner != "independent":
            raise InputError(f"--partner applies to --target disk, got --target {args.target}")
    wall = {
        name: getattr(SceneSpec, name) if value is None else value for name, value in wall.items()
    }
    return SceneSpec(
        lattice=args.lattice,
        seed=args.seed,
        gamma_deg=args.gamma,
        vn=args.vn,
        radius=args.radius,
        n_disk=args.n_disk,
        roughness=args.roughness,
        roughness_length=args.roughness_length,
        k2_over_k1=k2_over_k1,
        **wall,
        contact_a=args.contact_a,
        contact_scaling=args.contact_scaling,
        target=args.target,
        partner_lattice=args.partner_lattice,
        partner_seed=args.partner_seed,
        partner=args.partner,
        **{name: getattr(args, name) for name in MODEL_OPTIONS},
    )
