"""argparse types that reject bad values with a message naming the allowed range."""

from __future__ import annotations

import argparse


class OneLineParser(argparse.ArgumentParser):
    """Errors as a single line and exit status 2 (argparse prints the usage too)."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


def angle(text: str) -> float:
    value = float(text)
    if not 0.0 < value < 90.0:
        raise argparse.ArgumentTypeError(f"must be in (0, 90) degrees, got {text}")
    return value


def positive_float(text: str) -> float:
    value = float(text)
    if not value > 0.0:
        raise argparse.ArgumentTypeError(f"must be > 0, got {text}")
    return value


def count(minimum: int):
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"must be an integer >= {minimum}, got {text}"
            ) from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be an integer >= {minimum}, got {text}")
        return value

    return parse


def speed(text: str) -> float:
    value = float(text)
    if not 0.0 < value < 1.0:
        raise argparse.ArgumentTypeError(f"must be in (0, 1) (units of c), got {text}")
    return value


def wall_points(text: str) -> int | str:
    """--n-wall: a number of points >= 50, or "density" (the disk's number density)."""
    if text == "density":
        return text
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 50:
        raise argparse.ArgumentTypeError(f"must be an integer >= 50 or 'density', got {text}")
    return value


def wall_spring(text: str) -> float | str:
    """--wall-ka: the wall's ka over the disk's, in [0.01, 1000], or "same-c"."""
    if text == "same-c":
        return text
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0.01 <= value <= 1000.0:
        raise argparse.ArgumentTypeError(
            f"must be a number in [0.01, 1000] (the wall's ka over the disk's) or 'same-c', "
            f"got {text}"
        )
    return value


def add_wall_arguments(group, defaults: bool = True) -> None:
    """The readings of the wall (MODEL.md section 8); the study's take None as 'preset'."""
    from .scene import WALL_FIXED_CHOICES, SceneSpec

    spec = SceneSpec()
    group.add_argument(
        "--n-wall",
        type=wall_points,
        default=spec.n_wall if defaults else None,
        help=f"points in the wall, >= 50, or 'density': the disk's number "
        f"density (default: {spec.n_wall})",
    )
    group.add_argument(
        "--wall-ka",
        type=wall_spring,
        default=spec.wall_ka if defaults else None,
        help=f"the wall's spring constant over the disk's, in [0.01, 1000], or "
        f"'same-c': the wall's springs give it the disk's wave speed "
        f"(default: {spec.wall_ka:g})",
    )
    group.add_argument(
        "--wall-fixed",
        choices=WALL_FIXED_CHOICES,
        default=spec.wall_fixed if defaults else None,
        help=f"which wall points are held fixed (default: {spec.wall_fixed})",
    )


def add_scene_arguments(parser: argparse.ArgumentParser) -> None:
    """The options that define a scene (MODEL.md sections 1, 2 and 4)."""
    from .bodies import LATTICES

    group = parser.add_argument_group("scene")
    group.add_argument(
        "--lattice",
        choices=LATTICES,
        default="random",
        help="disk lattice (default: random); the wall is always random",
    )
    group.add_argument("--seed", type=count(0), default=1, help="sample seed (default: 1)")
    group.add_argument(
        "--gamma",
        type=angle,
        default=45.0,
        help="incidence angle from the wall normal, degrees, in (0, 90) (default: 45)",
    )
    group.add_argument(
        "--vn",
        type=speed,
        default=0.1,
        help="normal approach speed in units of c, in (0, 1) (default: 0.1)",
    )
    group.add_argument(
        "--radius",
        type=positive_float,
        default=1.0,
        help="disk radius R, the unit of length (default: 1)",
    )
    group.add_argument(
        "--n-disk", type=count(50), default=800, help="points in the disk, >= 50 (default: 800)"
    )
    group.add_argument(
        "--roughness",
        type=float,
        default=0.03,
        help="std of the surface roughness in R, in [0, 0.1] (default: 0.03)",
    )
    square = group.add_mutually_exclusive_group()
    square.add_argument(
        "--k2-over-k1",
        type=positive_float,
        default=3.0 / 7.0,
        help="square lattice: diagonal over nearest spring constant (default: 3/7)",
    )
    square.add_argument(
        "--nu",
        type=float,
        default=None,
        help="square lattice: k2/k1 that gives this Poisson ratio along the axes",
    )
    add_wall_arguments(group)
    group.add_argument(
        "--contact-a",
        type=positive_float,
        default=300.0,
        help="decay rate of the contact, a R (default: 300); finer disks need "
        "a larger one, 300 * sqrt(n_disk / 800)",
    )


def spec_from_args(args: argparse.Namespace):
    from .materials import square_ratio_for_poisson
    from .scene import SceneSpec

    if args.nu is not None:
        args.k2_over_k1 = square_ratio_for_poisson(args.nu)
    return SceneSpec(
        lattice=args.lattice,
        seed=args.seed,
        gamma_deg=args.gamma,
        vn=args.vn,
        radius=args.radius,
        n_disk=args.n_disk,
        n_wall=args.n_wall,
        roughness=args.roughness,
        k2_over_k1=args.k2_over_k1,
        wall_ka=args.wall_ka,
        wall_fixed=args.wall_fixed,
        contact_a=args.contact_a,
    )
