"""The theories of beta(psi) (docs/model.md section 6); their fits are in test_fits.py."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.theory.tangential import (
    Compliant,
    compliant_beta,
    compliant_beta_integrated,
    eta_squared,
    nu_for_eta,
    walton_beta,
)

PSI = np.array([0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0])
MODELS = [
    Compliant(e=0.9, mu=0.3, nu=0.3),
    Compliant(e=0.3, mu=0.5, nu=0.29, alpha=2.9),
    Compliant(e=1.0, mu=0.2, nu=0.1),
    Compliant(e=0.6, mu=0.1, nu=0.45, alpha=3.1),
]


@pytest.mark.parametrize("model", MODELS)
def test_closed_form_agrees_with_direct_integration(model):
    closed = np.array([compliant_beta(p, model) for p in PSI])
    integrated = compliant_beta_integrated(PSI, model, steps=100000)
    assert np.abs(closed - integrated).max() < 1e-6


@pytest.mark.parametrize("model", MODELS)
def test_gross_slip_is_walton_sliding_line(model):
    """Small psi (large tan gamma): slip all through the contact."""
    line = -1.0 + model.mu * (1.0 + model.e) * model.alpha * PSI
    gross = line < -0.5  # well inside the sliding branch
    closed = np.array([compliant_beta(p, model) for p in PSI[gross]])
    assert gross.any()
    assert np.allclose(closed, line[gross], rtol=0, atol=1e-12)


def test_limits():
    psi = np.array([0.3, 1.0, 4.0])
    frictionless = Compliant(e=0.8, mu=0.0, nu=0.3)
    assert np.allclose([compliant_beta(p, frictionless) for p in psi], -1.0, atol=1e-12)
    sticking = Compliant(e=0.8, mu=1e6, nu=0.3)  # never slips
    expected = -np.cos(sticking.omega * sticking.end)
    assert np.allclose([compliant_beta(p, sticking) for p in psi], expected, atol=1e-9)
    assert eta_squared(0.0) == pytest.approx(1.0)
    # the paper's eta = 1.015 as a Poisson ratio, and back
    assert np.sqrt(eta_squared(nu_for_eta(1.015))) == pytest.approx(1.015, rel=1e-14)
    assert nu_for_eta(np.sqrt(eta_squared(0.29))) == pytest.approx(0.29, rel=1e-12)
    assert walton_beta(0.1, 0.5, 0.2, 0.4) == pytest.approx(-1 + 0.2 * 1.5 * 3 * 0.1)
    assert walton_beta(10.0, 0.5, 0.2, 0.4) == pytest.approx(0.4)
