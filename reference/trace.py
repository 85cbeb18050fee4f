"""The total energy at every step of a reference run, and the contact's events.

Where does a rough impact's energy error come from? Each disk surface point
within the cutoff has a closest feature of the wall's polyline: the interior
of segment k (code 2k + 1) or vertex k (code 2k). When it changes between a
segment's interior and one of its ends (codes one apart) the distance l is
smooth to first order (its gradient is continuous); any other change crosses
the medial axis of the polyline, where two features are equally close: over
a valley (concave) vertex, the interiors of the two segments that meet there
(codes two apart). There l has a kink, so the force turns abruptly, and an
integrator that samples it at fixed times makes an error of first order in
dt (the share of the step spent on the wrong side). ``trace`` integrates like
``reference.run.simulate`` and books each step's energy change to the events
of that step, so the drift can be split by cause.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from analysis.impact.restitution import rebound

from .contact import InsideWall, closest_features
from .run import WALL_HELD, Observer, ReferenceOptions, Stepper, Unstable, load_model

OUT_OF_RANGE = -1


def feature_codes(points: np.ndarray, vertices: np.ndarray, cutoff: float) -> np.ndarray:
    """Each point's closest feature: 2k + 1 the interior of segment k, 2k
    vertex k, -1 farther than ``cutoff`` from the polyline.

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points.
    vertices : numpy.ndarray
        (m, 2) vertices of the polyline, in order.
    cutoff : float
        Range of the contact.

    Returns
    -------
    numpy.ndarray
        (n,) integer codes.
    """
    codes = np.full(len(points), OUT_OF_RANGE)
    near = points[:, 1] < vertices[:, 1].max() + cutoff  # the others cannot be in range
    if near.any():
        k, t, away = closest_features(points[near], vertices)
        code = np.where(t <= 0.0, 2 * k, np.where(t >= 1.0, 2 * k + 2, 2 * k + 1))
        codes[near] = np.where(np.linalg.norm(away, axis=1) < cutoff, code, OUT_OF_RANGE)
    return codes


def event_kind(old: int, new: int) -> str:
    """``cutoff`` (entering or leaving the range), ``smooth`` (a segment's
    interior and one of its ends: l is continuously differentiable there) or
    ``kink`` (two features equally close: the medial axis, where l has a kink)."""
    if old == OUT_OF_RANGE or new == OUT_OF_RANGE:
        return "cutoff"
    return "smooth" if abs(old - new) == 1 else "kink"


def feature_point(code: int, p: np.ndarray, row: np.ndarray):
    """The closest point of feature ``code`` to ``p`` and the lever weights of
    its vertices, as {vertex index: weight}."""
    k = code // 2
    if code % 2 == 0:
        return row[k], {k: 1.0}
    w1, w2 = row[k], row[k + 1]
    s = w2 - w1
    t = float(np.clip((p - w1) @ s / (s @ s), 0.0, 1.0))
    return w1 + t * s, {k: 1.0 - t, k + 1: t}


@dataclass
class Trace:
    """What ``trace`` records."""

    time: np.ndarray  # (steps + 1,)
    energy: np.ndarray  # (steps + 1,) total energy
    ke0: float  # initial kinetic energy
    events: list  # (step, point, old code, new code)
    kink_predicted: list  # Verlet only: (step, energy error, impulse on the disk (3,))
    disk_mass: float
    disk_inertia: float
    velocity_in: np.ndarray  # the disk's initial centre-of-mass velocity
    e: float  # of the run, as analysis.impact.restitution computes them
    beta: float

    def split(self) -> dict[str, float]:
        """The drift (energy change over the initial kinetic energy), split by
        the events of each step: a step counts as ``kink`` if any point crossed
        a kink in it, else ``smooth`` or ``cutoff``, else ``none``."""
        change = np.diff(self.energy) / self.ke0
        rank = {"kink": 3, "smooth": 2, "cutoff": 1}
        worst: dict[int, str] = {}
        for step, _, old, new in self.events:
            kind = event_kind(old, new)
            if rank[kind] > rank.get(worst.get(step, ""), 0):
                worst[step] = kind
        out = {"drift": float((self.energy[-1] - self.energy[0]) / self.ke0)}
        for kind in ("kink", "smooth", "cutoff"):
            steps = np.array([s for s, k in worst.items() if k == kind], dtype=int)
            out[kind] = float(change[steps - 1].sum()) if steps.size else 0.0
            out[f"{kind}_steps"] = int(steps.size)
            if kind == "kink":
                # the scale of a random walk of these steps: sqrt of the sum of squares
                out["kink_walk"] = float(np.sqrt((change[steps - 1] ** 2).sum()))
        out["none"] = out["drift"] - out["kink"] - out["smooth"] - out["cutoff"]
        return out


def trace(folder: Path | str, options: ReferenceOptions) -> Trace:
    """Integrate the scene in ``folder`` as ``reference.run.simulate`` does,
    recording the total energy at every step and every change of a disk
    point's closest feature.

    For velocity Verlet it also estimates each kink crossing's error from
    the crossing's place in the step: the kick of a step stands for the force
    over half a step either side, so a crossing at a fraction theta of the
    step from the last position gives the impulse error (F_before - F_after)
    dt (1/2 - theta) on the point, its reaction on the wall's vertices, and
    the energy error sum(impulse . velocity).

    Parameters
    ----------
    folder : pathlib.Path or str
        A scene folder (scene.data, scene.json).
    options : ReferenceOptions
        Integrator, time step, stop rule settings (``check``, ``tmax``).

    Returns
    -------
    Trace
        The energies, events and predicted kink errors.
    """
    options.validate()
    model = load_model(Path(folder), options)
    s = model.system
    observe = Observer(model)
    stepper = _EnergyStepper(model, options.integrator, options.dt)
    x, v = s.x.copy(), s.v.copy()
    dt = options.dt
    disk_mass = float(s.mass[observe.disk].sum())
    disk_inertia = observe.rigid(x, v)[3]
    velocity_in = observe.rigid(x, v)[1]

    def energy(x, v, e_contact):
        return 0.5 * float(np.sum(s.mass * (v * v).sum(axis=1))) + stepper.e_springs + e_contact

    force, _, e_contact = stepper.forces(x)
    energies = [energy(x, v, e_contact)]
    ke0 = 0.5 * float(np.sum(s.mass * (v * v).sum(axis=1)))
    predicted = []
    touched, step = False, 0
    while True:
        x_old, v_old = x.copy(), v.copy()
        stepper.step_number = step + 1
        seen = len(stepper.events)
        try:
            force, _, e_contact = stepper.step(x, v, force)
        except InsideWall as error:
            raise Unstable(
                f"a disk point is inside the wall at time {step * dt:.4g}: {error}"
            ) from error
        step += 1
        energies.append(energy(x, v, e_contact))
        if options.integrator == "verlet":
            for _, i, old, new in stepper.events[seen:]:
                if event_kind(old, new) == "kink":
                    predicted.append(
                        (step, *_kink_error(model, observe, i, old, new, x_old, x, v_old, v, dt))
                    )
        touched = touched or e_contact > 0.0
        if step % options.check == 0:
            if not np.isfinite(v).all():
                raise Unstable(f"the run went unstable at time {step * dt:.4g}")
            if touched and observe.finished(x, v, e_contact):
                break
            if step * dt >= options.tmax:
                raise Unstable(f"the disk has not left the wall by tmax = {options.tmax}")
    _, v_out, l_out, _ = observe.rigid(x, v)
    radius = json.loads((Path(folder) / "scene.json").read_text())["spec"]["radius"]
    out = rebound(velocity_in, v_out, 0.0, l_out / disk_inertia, radius)
    return Trace(
        time=dt * np.arange(step + 1),
        energy=np.array(energies),
        ke0=ke0,
        events=stepper.events,
        kink_predicted=predicted,
        disk_mass=disk_mass,
        disk_inertia=disk_inertia,
        velocity_in=velocity_in,
        e=out.e,
        beta=out.beta,
    )


class _EnergyStepper(Stepper):
    """The reference's stepper, keeping the spring energy (with the area
    barrier's, if any) of the last evaluation and the changes of closest
    feature between evaluations: at every substep's positions, since a
    fourth-order composition's substeps reach beyond the step (Forest-Ruth's
    by 1.35 dt), where a point can cross a kink and come back within one step."""

    def __init__(self, model, scheme, dt):
        super().__init__(model, scheme, dt)
        self.e_springs = 0.0
        self.events: list[tuple[int, int, int, int]] = []  # (step, point, old, new)
        self.step_number = 0
        self.codes = None

    def forces(self, x):
        springs, self.e_springs = self.model.internal_forces(x)
        contact, e_contact = self.model.contact_forces(x)
        model = self.model
        codes = feature_codes(x[model.disk_surface], x[model.wall_row], model.cutoff)
        if self.codes is not None:
            for i in np.flatnonzero(codes != self.codes):
                self.events.append((self.step_number, int(i), int(self.codes[i]), int(codes[i])))
        self.codes = codes
        return springs + contact, contact, e_contact


def _kink_error(model, observe, i, old, new, x0, x1, v0, v1, dt):
    """Velocity Verlet's energy error and the impulse error on the disk
    (fx, fy, torque about its centre) of point ``i`` crossing from feature
    ``old`` to ``new`` between positions x0 and x1."""
    point, row = model.disk_surface[i], model.wall_row

    def gap(x):
        p = x[point]
        q_old, _ = feature_point(old, p, x[row])
        q_new, _ = feature_point(new, p, x[row])
        return np.linalg.norm(p - q_old) - np.linalg.norm(p - q_new)

    g0, g1 = gap(x0), gap(x1)
    theta = float(np.clip(g0 / (g0 - g1), 0.0, 1.0)) if g0 != g1 else 0.5
    x = x0 + theta * (x1 - x0)
    vel = v0 + theta * (v1 - v0)
    p = x[point]
    impulse = np.zeros_like(x)
    for code, sign in ((old, 1.0), (new, -1.0)):
        q, weights = feature_point(code, p, x[row])
        d = p - q
        length = np.linalg.norm(d)
        f = model.a * model.v0 * np.exp(-model.a * length) * d / length
        impulse[point] += sign * f
        for k, w in weights.items():
            impulse[row[k]] -= sign * w * f
    impulse *= dt * (0.5 - theta)
    impulse[model.system.molecule == WALL_HELD] = 0.0
    com = observe.rigid(x, vel)[0]
    r = p - com
    on_disk = np.array(
        [impulse[point, 0], impulse[point, 1], r[0] * impulse[point, 1] - r[1] * impulse[point, 0]]
    )
    return float(np.sum(impulse * vel)), on_disk
