"""The rough surfaces' Gaussian random profiles: sampled at a row's points
(``correlated``), or one surface per seed at every resolution, a continuous
function of arc length (``Profile``).

``correlated`` filters white noise drawn at a row's points, so a finer
row is a new draw: the disk at 800 and at 3,200 points of one seed have
unrelated surfaces. Here the profile is a Fourier series whose coefficients
come from the seed's own stream and whose number of modes depends on the
correlation length and the period alone, never on the points: every
resolution samples the same function, and the differences between
resolutions are coupled (multilevel Monte Carlo, docs/model.md, "The model
as the resolution grows").

The covariance is that of ``correlated``: exp(-s^2 / (2 L^2)) between
points a distance s apart, wrapped around the period P. Its Fourier series
has the coefficients c_m = S(k_m) / P at k_m = 2 pi m / P, S(k) = L sqrt(2 pi)
exp(-k^2 L^2 / 2) the Gaussian's transform, so the sum of cos and sin modes
with independent normal amplitudes of variance c_0 and 2 c_m has exactly that
covariance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Modes up to k L = MODE_REACH: the spectrum there is exp(-MODE_REACH^2 / 2),
# 2e-16 of its peak, below a double's resolution of the profile.
MODE_REACH = 8.5
# The seed's streams for the profiles, after the sample's three
# (builder.sample.sample_seeds: the disk, the wall, the second disk).
DISK_PROFILE_STREAM = 3
WALL_PROFILE_STREAM = 4


@dataclass(frozen=True)
class Profile:
    """A periodic Gaussian random profile of unit variance (up to the period's
    images) and correlation length ``length``, as a Fourier series."""

    period: float
    length: float
    cosines: np.ndarray  # amplitude of cos(k_m s), m = 0 .. modes
    sines: np.ndarray  # amplitude of sin(k_m s); sines[0] is 0

    def __call__(self, s: np.ndarray) -> np.ndarray:
        """The profile at arc lengths ``s`` (any shape)."""
        s = np.asarray(s, float)
        phase = np.multiply.outer(s, self.wavenumbers)
        return np.cos(phase) @ self.cosines + np.sin(phase) @ self.sines

    @property
    def wavenumbers(self) -> np.ndarray:
        return 2.0 * np.pi * np.arange(len(self.cosines)) / self.period


def mode_variances(period: float, length: float) -> np.ndarray:
    """The variance of each mode's amplitudes, c_0 then 2 c_m (module doc)."""
    modes = int(np.ceil(MODE_REACH * period / (2.0 * np.pi * length)))
    k = 2.0 * np.pi * np.arange(modes + 1) / period
    c = length * np.sqrt(2.0 * np.pi) * np.exp(-0.5 * (k * length) ** 2) / period
    c[1:] *= 2.0
    return c


def draw_profile(stream: np.random.SeedSequence, period: float, length: float) -> Profile:
    """The profile of one stream: its amplitudes drawn mode by mode, from the
    longest wave up, so that the draw depends on (period, length) only."""
    variance = mode_variances(period, length)
    noise = np.random.default_rng(stream).standard_normal((len(variance), 2))
    scale = np.sqrt(variance)
    sines = noise[:, 1] * scale
    sines[0] = 0.0
    return Profile(period, length, noise[:, 0] * scale, sines)


def profile_stream(seed: int, stream: int) -> np.random.SeedSequence:
    """The sample's child stream ``stream``: the same child SeedSequence.spawn
    gives (a child depends on its index alone)."""
    return np.random.SeedSequence(seed, spawn_key=(stream,))


def disk_profiles(seed: int, length: float) -> tuple[Profile, Profile]:
    """The disk's radial and tangential profiles of a seed, of arc length on
    the unit circle (period 2 pi)."""
    children = profile_stream(seed, DISK_PROFILE_STREAM).spawn(2)
    return tuple(draw_profile(child, 2.0 * np.pi, length) for child in children)


def wall_profiles(seed: int, length: float, width: float) -> tuple[Profile, Profile]:
    """The wall's profiles along its top face (x in [-width / 2, width / 2],
    period the width): heights, then shifts along x."""
    children = profile_stream(seed, WALL_PROFILE_STREAM).spawn(2)
    return tuple(draw_profile(child, width, length) for child in children)


def correlated(noise: np.ndarray, spacing: float, length: float) -> np.ndarray:
    """White noise along an evenly spaced periodic row made a Gaussian random
    profile with correlation length ``length`` (both in the row's units).

    The profile's covariance between points a distance s apart along the row
    is exp(-s^2 / (2 length^2)) (unit variance), wrapped around the row's
    period, which is the same profile at any spacing: its slopes do not grow
    as the row is refined, unlike independent draws per point (docs/model.md,
    "The model as the resolution grows"). The covariance of an evenly spaced
    periodic row is circulant, so its eigenvalues are the FFT of its first row
    and ``noise`` filtered by their square roots has exactly that covariance
    (circulant embedding). ``length`` 0 gives ``noise`` itself.
    """
    if length == 0.0:
        return noise
    n = len(noise)
    period = n * spacing
    lag = np.minimum(np.arange(n), n - np.arange(n)) * spacing
    # the Gaussian wrapped around the period: images up to 4 periods away
    images = lag[:, None] + period * np.arange(-4, 5)[None, :]
    covariance = np.exp(-0.5 * (images / length) ** 2).sum(axis=1)
    eigenvalues = np.clip(np.fft.rfft(covariance).real, 0.0, None)
    return np.fft.irfft(np.sqrt(eigenvalues) * np.fft.rfft(noise), n)
