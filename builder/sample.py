"""One sample's bodies: the random streams its seed draws (the disk, the wall,
a binary scene's second disk), and the disk and the wall drawn from them,
cached, since a study builds the same sample at every angle and speed."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from . import bodies, profile
from .bodies import Body
from .scene import SceneSpec


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
        spec.roughness_profile,
    )


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
            spec.roughness if spec.wall_roughness is None else spec.wall_roughness,
            spec.wall_fixed,
            spec.roughness_direction,
            spec.roughness_length,
            spec.roughness_profile,
        ),
    )


def sample_seeds(seed: int) -> tuple[np.random.SeedSequence, ...]:
    """Independent streams for the disk, the wall and the second disk of one
    sample (a child's stream depends on its index only, so the disk and the
    wall are those of the two streams this drew before the second disk)."""
    return tuple(np.random.SeedSequence(seed).spawn(3))


@lru_cache(maxsize=8)
def _disk(lattice, seed, n_disk, roughness, k2_over_k1, *readings) -> Body:
    *readings, length, kind = readings
    rng = np.random.default_rng(sample_seeds(seed)[0])
    profiles = profile.disk_profiles(seed, length) if kind == "continuous" else None
    return bodies.make_disk(
        rng, lattice, n_disk, roughness, k2_over_k1, *readings, length, profiles
    )


@lru_cache(maxsize=4)
def _wall(seed, n_wall, width, height, roughness, wall_fixed, direction, length, kind) -> Body:
    rng = np.random.default_rng(sample_seeds(seed)[1])
    profiles = profile.wall_profiles(seed, length, width) if kind == "continuous" else None
    return bodies.make_wall(
        rng, n_wall, width, height, roughness, wall_fixed, direction, length, profiles
    )
