"""The roughness as a profile of fixed correlation length (builder.profile.correlated)."""

import numpy as np
import pytest

from builder import profile
from builder.sample import build_bodies
from builder.scene import SceneSpec
from builder.study_names import LIMITS

PAPER = LIMITS["paper"]  # the paper's draw per point, the default before issue 46


def covariance(n: int, spacing: float, length: float) -> np.ndarray:
    """The wrapped Gaussian covariance of a periodic row, written out directly."""
    index = np.arange(n)
    lag = np.abs(index[:, None] - index[None, :])
    lag = np.minimum(lag, n - lag) * spacing
    period = n * spacing
    images = lag[..., None] + period * np.arange(-4, 5)
    return np.exp(-0.5 * (images / length) ** 2).sum(axis=-1)


@pytest.mark.parametrize("n, spacing, length", [(93, 2 * np.pi / 93, 0.048), (64, 0.1, 0.3)])
def test_the_filter_has_the_profiles_covariance(n, spacing, length):
    # the filter applied to each unit vector is a matrix M with M M^T = C,
    # the covariance written out pair by pair: two computations agreeing
    filter_matrix = np.stack([profile.correlated(e, spacing, length) for e in np.eye(n)], axis=1)
    assert np.allclose(filter_matrix @ filter_matrix.T, covariance(n, spacing, length), atol=1e-10)


def test_zero_length_is_the_draw_per_point():
    noise = np.random.default_rng(3).standard_normal(50)
    assert profile.correlated(noise, 0.1, 0.0) is noise


def test_slopes_follow_the_length_not_the_spacing():
    # rms slope of a Gaussian profile is 1 / length at any fine enough spacing;
    # independent draws have sqrt(2) / spacing, which grows as the row is refined
    rng = np.random.default_rng(1)
    for n in (400, 1600):
        spacing = 2 * np.pi / n
        rows = np.stack(
            [profile.correlated(rng.standard_normal(n), spacing, 0.048) for _ in range(200)]
        )
        slope = np.diff(rows, axis=1) / spacing
        assert np.sqrt((slope**2).mean()) == pytest.approx(1 / 0.048, rel=0.05)


def test_a_correlated_disk_filters_the_seeds_own_draw():
    # the profile is the seed's draw per point, filtered: the same white noise
    disk = build_bodies(SceneSpec(seed=4, **PAPER))[0]  # the paper's draw per point
    smooth = build_bodies(SceneSpec(seed=4, **{**PAPER, "roughness_length": 0.048}))[0]
    radial = np.hypot(*disk.points[disk.surface].T) - 1.0
    heights = np.hypot(*smooth.points[smooth.surface].T) - 1.0
    arc = 2 * np.pi / len(radial)
    expected = 0.03 * profile.correlated(radial / 0.03, arc, 0.048)
    assert np.allclose(heights, expected, atol=1e-12)
    # neighbours are correlated: their differences are smaller than independent ones'
    assert np.std(np.diff(heights)) < 0.8 * np.std(np.diff(radial))


def test_uneven_rows_are_refused():
    from ground.errors import InputError

    with pytest.raises(InputError, match="roughness_length applies to evenly spaced"):
        SceneSpec(surface_row="random", roughness_length=0.05).validate()
