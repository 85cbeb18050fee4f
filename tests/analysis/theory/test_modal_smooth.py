"""The modal bookkeeping of analysis/theory/modal_smooth.py on small networks with known answers."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import trapezoid

from analysis.theory import modal_smooth as ms


def modes_of(x: np.ndarray, bonds: np.ndarray, ka: np.ndarray, free: np.ndarray) -> ms.Modes:
    omega2, shapes = np.linalg.eigh(ms.stiffness(x, bonds, ka, free))
    surface = np.zeros(free.sum(), bool)
    return ms.Modes(x[free], surface, np.sqrt(np.clip(omega2, 0.0, None)), shapes)


def grid(held_bottom: bool) -> ms.Modes:
    """A 4 x 4 square grid with diagonals, springs 1 to 2.5; its bottom row held or free."""
    x = np.array([(i, j) for j in range(4) for i in range(4)], float)
    bonds = []
    for j in range(4):
        for i in range(4):
            k = 4 * j + i
            if i < 3:
                bonds.append((k, k + 1))
            if j < 3:
                bonds.append((k, k + 4))
            if i < 3 and j < 3:
                bonds += [(k, k + 5), (k + 1, k + 4)]
    bonds = np.array(bonds)
    ka = np.linspace(1.0, 2.5, len(bonds))
    free = np.ones(16, bool)
    if held_bottom:
        free[:4] = False
    return modes_of(x, bonds, ka, free)


def test_one_spring_under_a_step():
    """Two unit masses, one spring along y: F on one for tau leaves F^2 sin^2(w tau/2) / w^2."""
    modes = modes_of(
        np.array([[0.0, 0.0], [0.0, 1.0]]), np.array([[0, 1]]), np.ones(1), np.ones(2, bool)
    )
    assert modes.omega[-1] == pytest.approx(np.sqrt(2.0))
    assert np.allclose(modes.omega[:3], 0.0, atol=1e-7)
    force, tau, omega = 0.7, 1.3, np.sqrt(2.0)
    energy = ms.residual_energy(modes, np.array([3]), np.full((1, 2), force), np.array([0.0, tau]))
    assert energy.sum() == pytest.approx(
        force**2 * np.sin(omega * tau / 2) ** 2 / omega**2, rel=1e-9
    )


def test_an_impulse_on_a_held_body_leaves_its_kinetic_energy():
    """With every mode elastic, a short kick J on a unit mass leaves J^2 / 2."""
    modes = grid(held_bottom=True)
    width = 1e-3 * 2 * np.pi / modes.omega.max()
    time = np.array([0.0, width, 2 * width])
    kick = 2.0
    loads = np.array([[0.0, kick / width, 0.0]])  # a triangle of impulse ``kick``
    energy = ms.residual_energy(modes, np.array([2 * 9 + 1]), loads, time)
    assert energy.sum() == pytest.approx(kick**2 / 2, rel=1e-4)


def test_a_free_body_keeps_the_rigid_share_out():
    modes = grid(held_bottom=False)
    width = 1e-3 * 2 * np.pi / modes.omega.max()
    time = np.array([0.0, width, 2 * width])
    loads = np.array([[0.0, 1.0 / width, 0.0]])
    energy = ms.residual_energy(modes, np.array([2 * 5 + 1]), loads, time)
    # the kick's rigid part: translation 1/(2 M) and rotation about the centre
    lever = 5.0 % 4 - 1.5
    rigid = 0.5 / 16 + 0.5 * lever**2 / np.sum((modes.x - modes.x.mean(axis=0)) ** 2)
    assert energy.sum() == pytest.approx(0.5 - rigid, rel=1e-4)


def test_a_slow_push_leaves_nothing():
    modes = grid(held_bottom=True)
    time = np.linspace(0.0, 200 * 2 * np.pi / modes.omega.min(), 20001)
    loads = (np.sin(np.pi * time / time[-1]) ** 2)[None, :]
    energy = ms.residual_energy(modes, np.array([2 * 9 + 1]), loads, time)
    assert energy.sum() < 1e-6 * trapezoid(loads[0], time) ** 2 / 2


def test_contact_loads_share_the_force():
    x = np.array([[i * 0.1 - 0.5, 0.0] for i in range(11)] + [[0.0, -1.0]])
    modes = ms.Modes(x, np.arange(12) < 11, np.zeros(24), np.eye(24))
    force = np.array([0.0, 1.0, 5.0])
    dofs, loads = ms.contact_loads(modes, force, np.array([0.0, 0.05, 0.32]), 0.0, -1.0)
    assert np.allclose(loads.sum(axis=0), -force)
    assert set(dofs // 2) == set(range(11))
    assert np.count_nonzero(loads[:, 1]) == 1  # narrower than the spacing: the nearest point
    assert np.count_nonzero(loads[:, 2]) == 7  # |x| < 0.32
