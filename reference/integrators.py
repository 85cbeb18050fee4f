"""Symplectic integrators as compositions of velocity Verlet substeps.

A step of weights (w1, w2, ...) is velocity Verlet with time step w1 dt, then
w2 dt, ...; the last force of a step is the first of the next. Verlet is (1);
Forest-Ruth (Yoshida's triple jump) composes three substeps into a
fourth-order method; Suzuki's five-substep composition is fourth order with an
error constant about ten times smaller.
"""

from __future__ import annotations

THETA = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
SUZUKI = 1.0 / (4.0 - 4.0 ** (1.0 / 3.0))

SCHEMES = {
    "verlet": ((1.0,), 2),
    "forest-ruth": ((THETA, 1.0 - 2.0 * THETA, THETA), 4),
    "suzuki": ((SUZUKI, SUZUKI, 1.0 - 4.0 * SUZUKI, SUZUKI, SUZUKI), 4),
}


def weights(scheme: str) -> tuple[float, ...]:
    if scheme not in SCHEMES:
        raise ValueError(f"integrator must be one of {', '.join(SCHEMES)}; got {scheme!r}")
    return SCHEMES[scheme][0]


def order(scheme: str) -> int:
    return SCHEMES[scheme][1]
