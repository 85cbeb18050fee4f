"""One rough surface per seed at every resolution (builder/profile.py)."""

from __future__ import annotations

import numpy as np
import pytest

from builder import bodies, profile
from builder.sample import build_bodies
from builder.scene import PAPER_CUTOFF, SceneSpec, contact_energy
from builder.study_names import LIMITS
from ground.errors import InputError

LENGTH = 0.2
ROUGHNESS = 0.03


def spec(n_disk: int, seed: int = 3, **options) -> SceneSpec:
    options = {
        "roughness_length": LENGTH,
        "roughness_profile": "continuous",
        "contact_scaling": "physical",
        "area_floor": 0.0,
        **options,
    }
    return SceneSpec(n_disk=n_disk, seed=seed, **options)


def surface_heights(disk: bodies.Body) -> tuple[np.ndarray, np.ndarray]:
    """The disk's surface points as (angle, radius - 1), in order of angle."""
    row = disk.points[disk.surface]
    angle = np.arctan2(row[:, 1], row[:, 0]) % (2.0 * np.pi)
    order = np.argsort(angle)
    return angle[order], np.hypot(row[order, 0], row[order, 1]) - 1.0


def test_one_seed_is_one_surface_at_800_and_12800_points():
    """The 800-point disk's surface is the 12,800-point disk's, read at its own
    points: the fine row interpolated to the coarse angles agrees to within
    linear interpolation's error, h^2 / 8 times the profile's largest
    curvature, where two seeds' surfaces differ by the roughness itself."""
    coarse, coarse_wall = build_bodies(spec(800))
    fine, fine_wall = build_bodies(spec(12800))
    angle_c, height_c = surface_heights(coarse)
    angle_f, height_f = surface_heights(fine)
    radial = profile.disk_profiles(3, LENGTH)[0]
    s = np.linspace(0.0, 2.0 * np.pi, 20001)
    curvature = ROUGHNESS * np.abs(np.gradient(np.gradient(radial(s), s), s)).max()
    h = np.diff(angle_f).max()
    bound = curvature * h**2 / 8.0
    read = np.interp(angle_c, angle_f, height_f, period=2.0 * np.pi)
    assert np.abs(read - height_c).max() < 1.5 * bound
    assert bound < 0.01 * ROUGHNESS
    other, _ = build_bodies(spec(800, seed=4))
    assert np.abs(surface_heights(other)[1] - height_c).max() > 1.5 * ROUGHNESS
    # the wall's top face likewise, as a function of x
    top_c = coarse_wall.points[coarse_wall.surface[1:-1]]
    top_f = fine_wall.points[fine_wall.surface[1:-1]]
    order = np.argsort(top_f[:, 0])
    wall_read = np.interp(top_c[:, 0], top_f[order, 0], top_f[order, 1])
    assert np.abs(wall_read - top_c[:, 1]).max() < 0.01 * ROUGHNESS


def test_the_profile_has_the_sampled_reading_s_statistics():
    """Over seeds, the profile's variance and its covariance at a lag follow
    exp(-s^2 / (2 L^2)) (within 4 standard errors of 400 seeds), and its rms
    slope is 1 / L: the continuous reading is the sampled one's surface,
    made one function."""
    seeds = range(400)
    lags = np.array([0.0, 0.1, 0.2, 0.4])
    values = np.array([profile.disk_profiles(seed, LENGTH)[0](1.0 + lags) for seed in seeds])
    expected = np.exp(-0.5 * (lags / LENGTH) ** 2)
    product = values * values[:, :1]
    mean = product.mean(axis=0)
    error = product.std(axis=0, ddof=1) / np.sqrt(len(seeds))
    assert np.all(np.abs(mean - expected) < 4.0 * error)
    step = 1e-5
    slopes = np.array(
        [
            np.diff(profile.disk_profiles(seed, LENGTH)[0](np.array([2.0, 2.0 + step]))) / step
            for seed in seeds
        ]
    ).ravel()
    slope_error = 4.0 * np.sqrt(2.0 / len(seeds))  # of a variance estimate, relative
    assert abs(np.mean(slopes**2) * LENGTH**2 - 1.0) < slope_error


def test_mode_variances_sum_to_the_wrapped_covariance():
    """The modes' variances add up to the covariance at lag 0 with the
    period's images, an identity of the Fourier series."""
    for period, length in ((2.0 * np.pi, 0.2), (2.0 * np.pi, 0.048), (8.0, 0.2)):
        images = period * np.arange(-4, 5)
        wrapped = np.exp(-0.5 * (images / length) ** 2).sum()
        assert profile.mode_variances(period, length).sum() == pytest.approx(wrapped, rel=1e-12)


def test_the_draw_depends_on_the_seed_and_the_length_only():
    first = profile.disk_profiles(7, LENGTH)[0]
    again = profile.disk_profiles(7, LENGTH)[0]
    assert np.array_equal(first.cosines, again.cosines)
    assert not np.array_equal(first.cosines, profile.disk_profiles(8, LENGTH)[0].cosines)
    # the sample's own streams are not reused
    assert profile.DISK_PROFILE_STREAM >= 3 and profile.WALL_PROFILE_STREAM >= 3


def test_the_continuous_reading_keeps_the_sampled_reading_s_interior():
    """Only the surface row changes: the interior points of a seed are those
    of the sampled reading (the noise is still drawn)."""
    sampled, _ = build_bodies(spec(800, roughness_profile="sampled"))
    continuous, _ = build_bodies(spec(800))
    inner_s = sampled.points[sampled.role == bodies.INTERIOR]
    inner_c = continuous.points[continuous.role == bodies.INTERIOR]
    # the clearance from the surface may keep or drop a few candidates
    common = {tuple(p) for p in np.round(inner_s, 12)} & {tuple(p) for p in np.round(inner_c, 12)}
    assert len(common) > 0.95 * len(inner_s)


def test_the_physical_contact_keeps_its_lengths_and_its_pressure_over_the_modulus():
    """contact_scaling physical: a and the cutoff fixed in R; V0 a over the
    spacing grows as n_disk, as the modulus does in units of m c^2; at 800
    points, the paper's contact."""
    base, fine = spec(800), spec(12800)
    assert base.contact_decay == fine.contact_decay == 300.0
    assert base.contact_cutoff == fine.contact_cutoff == PAPER_CUTOFF
    assert PAPER_CUTOFF == pytest.approx(SceneSpec().wall_spacing, rel=1e-12)
    pressure = lambda s: contact_energy(s, s.n_disk) / s.resolution_scale  # noqa: E731
    assert pressure(fine) / pressure(base) == pytest.approx(12800 / 800)
    assert contact_energy(base, 800) == contact_energy(SceneSpec(**LIMITS["paper"]), 800)


def test_a_continuous_profile_needs_a_length():
    with pytest.raises(InputError, match="roughness_length"):
        spec(800, roughness_length=0.0).validate()
    with pytest.raises(InputError, match="physical"):
        SceneSpec(target="disk", contact_scaling="physical").validate()
