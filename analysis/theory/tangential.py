"""Theories of the tangential restitution beta(psi), psi = cot gamma (docs/model.md section 6).

Walton: beta = min(beta0, -1 + mu (1 + e) K psi).

The compliant model of Maw, Barber and Fawcett in Stronge's linear-spring
form, in units where velocities are in V_n and time is w t (w the normal
frequency). The normal impulse per unit mass is p = 1 - cos t while loading
(t <= pi/2) and p = 1 - e cos phi after, phi = t/e + (pi/2)(1 - 1/e), up to
t = (1 + e) pi/2; the normal force is n = dp/dt (sin t, then sin phi). The
contact point's tangential velocity u starts at 1/psi. Slipping in direction
s, du/dt = -alpha mu s n. Sticking, a spring of stiffness Omega^2/alpha (per
unit mass, Omega = sqrt(alpha)/eta, eta^2 = (2 - nu) / (2 (1 - nu))) holds it:
du/dt = -alpha f, df/dt = (Omega^2/alpha) u. Slip turns to stick when the
slider stops (u equals the spring's rate of stretch, (alpha mu s / Omega^2) dn/dt);
stick turns to slip when |f| reaches mu n. beta = -u_end / u_0.

compliant_beta solves this phase by phase in closed form, with the transition
times found by root finding; compliant_beta_integrated integrates the spring
and slider directly (a return-mapping scheme, no phase logic). They agree
(tests/analysis/theory/test_theory.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

HALF_PI = 0.5 * math.pi  # the end of loading, in units of the normal period / 2 pi


def walton_beta(psi, e, mu: float, beta0: float, K: float = 3.0):
    """Walton's beta: gross sliding, capped by the sticking plateau beta0.

    Parameters
    ----------
    psi : float or array_like
        cot gamma, |V_y| / V_x before the impact.
    e : float or array_like
        The coefficient of normal restitution at each psi.
    mu : float
        Friction coefficient.
    beta0 : float
        The plateau of beta at small angles of incidence.
    K : float
        1 + M R^2 / I (3 for a uniform disk).

    Returns
    -------
    numpy.ndarray
        min(beta0, -1 + mu (1 + e) K psi).
    """
    return np.minimum(beta0, -1.0 + mu * (1.0 + np.asarray(e)) * K * np.asarray(psi))


def eta_squared(nu: float) -> float:
    """k_n / k_t of the compliant contact, from the Poisson ratio.

    Parameters
    ----------
    nu : float
        Poisson ratio.

    Returns
    -------
    float
        (2 - nu) / (2 (1 - nu)).
    """
    return (2.0 - nu) / (2.0 * (1.0 - nu))


def nu_for_eta(eta: float) -> float:
    """The Poisson ratio whose eta^2 = (2 - nu) / (2 (1 - nu)) is eta^2: how a
    model given by eta (the paper's 1.015) is written with ``Compliant``.

    Parameters
    ----------
    eta : float
        sqrt(k_n / k_t), at least 1/sqrt(2) (nu below 1).

    Returns
    -------
    float
        (2 - 2 eta^2) / (1 - 2 eta^2).
    """
    eta2 = eta * eta
    return (2.0 - 2.0 * eta2) / (1.0 - 2.0 * eta2)


@dataclass(frozen=True)
class Compliant:
    """Parameters of the compliant model."""

    e: float
    mu: float
    nu: float
    alpha: float = 3.0  # K = 1 + M R^2 / I

    @property
    def omega(self) -> float:
        """Tangential over normal frequency."""
        return np.sqrt(self.alpha / eta_squared(self.nu))

    @property
    def end(self) -> float:
        return (1.0 + self.e) * np.pi / 2.0

    def _phase(self, t):
        return t / self.e + 0.5 * np.pi * (1.0 - 1.0 / self.e)

    # Each takes an array (a root's scan) or a float (Brent's steps, most of
    # the calls of a fit: math on a float is about ten times numpy's speed).
    def impulse(self, t):
        """Normal impulse per unit mass, in units of V_n."""
        if isinstance(t, float):
            return 1.0 - math.cos(t) if t <= HALF_PI else 1.0 - self.e * math.cos(self._phase(t))
        t = np.asarray(t, float)
        return np.where(t <= HALF_PI, 1.0 - np.cos(t), 1.0 - self.e * np.cos(self._phase(t)))

    def force(self, t):
        """Normal force per unit mass, dp/dt."""
        if isinstance(t, float):
            return math.sin(t) if t <= HALF_PI else math.sin(self._phase(t))
        t = np.asarray(t, float)
        return np.where(t <= HALF_PI, np.sin(t), np.sin(self._phase(t)))

    def force_rate(self, t):
        """dn/dt."""
        if isinstance(t, float):
            return math.cos(t) if t <= HALF_PI else math.cos(self._phase(t)) / self.e
        t = np.asarray(t, float)
        return np.where(t <= HALF_PI, np.cos(t), np.cos(self._phase(t)) / self.e)


SCAN = np.linspace(0.0, 1.0, 401)  # a root's scan, as a share of its interval


def _first_root(function, start: float, end: float) -> float | None:
    """The first zero of ``function`` in (start, end], by a scan and Brent's method."""
    grid = start + (end - start) * SCAN
    grid[-1] = end
    values = np.asarray(function(grid), float)  # the functions take arrays
    # a zero at the very start is the transition just made, not a new one:
    # the first sample after it that is a zero or ends a change of sign
    before, after = values[:-1], values[1:]
    hits = np.flatnonzero((after == 0.0) | ((np.sign(after) != np.sign(before)) & (before != 0.0)))
    if not hits.size:
        return None
    k = hits[0] + 1
    if values[k] == 0.0:
        return float(grid[k])
    return float(brentq(function, grid[k - 1], grid[k], xtol=1e-14, rtol=1e-13))


def compliant_beta(psi: float, model: Compliant) -> float:
    """beta of the compliant model, phase by phase in closed form.

    Parameters
    ----------
    psi : float
        cot gamma before the impact.
    model : Compliant
        The model's e, mu, nu and alpha.

    Returns
    -------
    float
        The tangential coefficient of restitution.
    """
    alpha, mu, omega = model.alpha, model.mu, model.omega
    t, u, f = 0.0, 1.0 / psi, 0.0
    sticking = u <= mu * alpha / omega**2  # initial stick: tan gamma <= mu eta^2
    direction = 1.0
    while t < model.end:
        if sticking:
            t0, u0, f0 = t, u, f

            def state(time):
                theta = omega * (time - t0)
                trig = math if isinstance(theta, float) else np  # as Compliant's own
                cos, sin = trig.cos(theta), trig.sin(theta)
                return (u0 * cos - alpha * f0 / omega * sin, f0 * cos + omega * u0 / alpha * sin)

            # slip again when the spring force reaches mu n (after the normal
            # force has started to fall, or at once if it is already there)
            slip = _first_root(
                lambda time: abs(state(time)[1]) - mu * model.force(time), t0, model.end
            )
            t = slip if slip is not None else model.end
            u, f = state(t)
            if slip is not None:
                direction = np.sign(f) if f != 0.0 else direction
                sticking = False
        else:
            t0, u0, s = t, u, direction

            def velocity(time):
                return u0 - alpha * mu * s * (model.impulse(time) - model.impulse(t0))

            # stick when the slider stops: u equals the spring's rate of stretch
            stick = _first_root(
                lambda time: (
                    s * (velocity(time) - alpha * mu * s / omega**2 * model.force_rate(time))
                ),
                t0,
                model.end,
            )
            t = stick if stick is not None else model.end
            u, f = velocity(t), mu * s * model.force(t)
            if stick is not None:
                sticking = True
    return float(-u * psi)


def compliant_beta_integrated(psi, model: Compliant, steps: int = 200000) -> np.ndarray:
    """beta of the compliant model by direct integration of spring and slider.

    The spring's stretch is advanced with the contact point's velocity; if the
    spring force would exceed mu n, the slider gives way and the force is
    mu n (return mapping). Velocity-Verlet splitting, vectorised over psi.

    Parameters
    ----------
    psi : float or array_like
        cot gamma before the impact.
    model : Compliant
        The model's e, mu, nu and alpha.
    steps : int
        Time steps over the contact.

    Returns
    -------
    numpy.ndarray
        beta at each psi (a check of ``compliant_beta``).
    """
    psi = np.atleast_1d(np.asarray(psi, float))
    alpha, mu, omega = model.alpha, model.mu, model.omega
    stiffness = omega**2 / alpha
    h = model.end / steps
    u = 1.0 / psi
    stretch = np.zeros_like(u)
    force = np.zeros_like(u)
    for k in range(steps):
        t = (k + 1) * h
        u -= 0.5 * h * alpha * force
        stretch += h * u
        limit = mu * model.force(t)
        force = stiffness * stretch
        slipping = np.abs(force) > limit
        force = np.where(slipping, np.sign(force) * limit, force)
        stretch = force / stiffness
        u -= 0.5 * h * alpha * force
    return -u * psi
