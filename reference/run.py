"""Runs an impact scene with the reference implementation, writing the same
files as decks/impact.lmp, so that the same analysis reads both."""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from analysis.impact.result import analyse_run, write_json_atomically
from analysis.impact.series import BINARY_COLUMNS, COLUMNS
from builder.lammps_data import read_data
from ground import gate
from ground.checks import Range
from ground.errors import InputError
from ground.provenance import git_revision

from .contact import InsideWall
from .forces import Model, TurnedOver, area_barrier
from .integrators import SCHEMES, weights

DISK, WALL_HELD = 1, 3
DISK_SURFACE, WALL_SURFACE = 1, 3
VERSION = "reference (numpy)"
# The reference's time step, R / c: the range of LAMMPS's runs (runner.options.DT).
DT = Range(1e-5, 0.05, unit="R/c")


class Unstable(RuntimeError):
    """The run blew up or a disk point went into the wall."""


@dataclass
class ReferenceOptions:
    dt: float = 0.001
    integrator: str = "forest-ruth"
    contact: str = "segment"
    rule: str = "lever"
    tmax: float = 100.0
    every: int = 10
    check: int = 100
    # the area barrier of a scene with --area-floor; False leaves it out (to
    # see what it changes: tests/reference/test_barrier.py)
    barrier: bool = True

    def validate(self) -> None:
        DT.check("dt", self.dt)
        if self.integrator not in SCHEMES:
            raise InputError(
                f"integrator must be one of {', '.join(SCHEMES)}; got {self.integrator!r}"
            )
        if self.contact not in ("segment", "pair"):
            raise InputError(f"contact must be one of segment, pair; got {self.contact!r}")
        if self.check % self.every:
            raise InputError(f"check must be a multiple of every ({self.every}), got {self.check}")


def load_model(folder: Path, options: ReferenceOptions) -> Model:
    scene = json.loads((folder / "scene.json").read_text())
    system = read_data(folder / "scene.data")
    first, last = scene["wall_row_tags"]
    contact = scene["contact"]
    partner = None
    if scene.get("target") == "disk":
        a_first, a_last = scene["partner_row_tags"]
        partner = np.arange(a_first - 1, a_last)
    return Model(
        system=system,
        a=contact["a"],
        v0=contact["V0"],
        cutoff=contact["cutoff"],
        disk_surface=np.flatnonzero(system.types == DISK_SURFACE),
        wall_row=np.arange(first - 1, last),
        contact=options.contact,
        rule=options.rule,
        partner_ring=partner,
        barrier=options.barrier,
    )


class Observer:
    """The disk's rigid-body motion, as decks/impact.lmp records it (and the
    second disk's too, as decks/binary.lmp does)."""

    def __init__(self, model: Model, reach_margin: float = 0.0):
        s = model.system
        self.model = model
        self.disk = np.flatnonzero(s.molecule == DISK)
        self.wall = np.flatnonzero(s.molecule != DISK)
        self.binary = model.partner_ring is not None

    def rigid(self, x, v, atoms=None):
        atoms = self.disk if atoms is None else atoms
        xd, vd, m = x[atoms], v[atoms], self.model.system.mass[atoms]
        total = m.sum()
        com = m @ xd / total
        vcm = m @ vd / total
        r, u = xd - com, vd - vcm
        lz = float(np.sum(m * (r[:, 0] * u[:, 1] - r[:, 1] * u[:, 0])))
        izz = float(np.sum(m * (r * r).sum(axis=1)))
        return com, vcm, lz, izz

    def header(self) -> str:
        return "# " + " ".join(BINARY_COLUMNS if self.binary else COLUMNS) + "\n"

    def row(self, step, t, x, v, contact_force, e_contact):
        values = []
        for atoms in (self.disk, self.wall) if self.binary else (self.disk,):
            com, vcm, lz, izz = self.rigid(x, v, atoms)
            values += [*com, *vcm, lz, izz, lz / izz, *contact_force[atoms].sum(axis=0)]
        values.append(e_contact)
        return f"{step} {t:.10g} " + " ".join(repr(float(value)) for value in values) + "\n"

    def energies(self, t, x, v, e_contact):
        s = self.model.system
        ke = 0.5 * s.mass * (v * v).sum(axis=1)
        i = s.bonds[:, 0]
        d = x[s.bonds[:, 1]] - x[i]
        dr = np.sqrt((d * d).sum(axis=1)) - s.r0
        e_bond = dr * dr * (s.k2 + dr * (s.k3 + dr * s.k4))
        in_disk = s.molecule[i] == DISK  # springs never cross bodies
        # the barrier's energy, per body as the deck's pe/atom bond angle has it
        # (triangles never cross bodies either)
        e_angle = np.zeros(len(s.angles))
        if self.model.has_barrier:
            e_angle = area_barrier(x, s.angles, s.a0, s.k_area, s.jc).each
        angle_in_disk = s.molecule[s.angles[:, 0]] == DISK
        values = (
            ke[self.disk].sum(),
            e_bond[in_disk].sum() + e_angle[angle_in_disk].sum(),
            ke[self.wall].sum(),
            e_bond[~in_disk].sum() + e_angle[~angle_in_disk].sum(),
            e_contact,
        )
        return f"{t:.10g} " + " ".join(repr(float(value)) for value in values) + "\n"

    def finished(self, x, v, e_contact: float) -> bool:
        """The deck's rule: the disk's lowest possible point clears the wall by
        the cutoff; two disks (decks/binary.lmp): no contact, the centres
        further apart than both reaches and the cutoff, and moving apart."""
        if self.binary:
            if e_contact > 0.0:
                return False
            (com_a, v_a, *_), (com_b, v_b, *_) = self.rigid(x, v), self.rigid(x, v, self.wall)
            reaches = sum(
                np.linalg.norm(x[ring] - com, axis=1).max()
                for ring, com in ((self.model.partner_ring, com_a), (self.model.wall_row, com_b))
            )
            r = com_a - com_b
            return np.linalg.norm(r) - reaches > self.model.cutoff and r @ (v_a - v_b) > 0
        com = self.rigid(x, np.zeros_like(x))[0]
        surface = self.model.disk_surface
        reach = np.linalg.norm(x[surface] - com, axis=1).max()
        wall_top = x[self.model.wall_row, 1].max()
        return com[1] - reach - wall_top > self.model.cutoff


class Stepper:
    """Advances positions and velocities by composition steps of velocity Verlet."""

    def __init__(self, model: Model, scheme: str, dt: float):
        s = model.system
        self.model = model
        self.moving = (s.molecule != WALL_HELD)[:, None]
        self.inverse_mass = (1.0 / s.mass)[:, None] * self.moving
        self.substeps = [w * dt for w in weights(scheme)]

    def forces(self, x):
        contact, e_contact = self.model.contact_forces(x)
        return self.model.internal_forces(x)[0] + contact, contact, e_contact

    def step(self, x, v, force):
        """One step in place; returns the new (force, contact force, contact energy)."""
        for h in self.substeps:
            v += 0.5 * h * force * self.inverse_mass
            x += h * v * self.moving
            force, contact, e_contact = self.forces(x)
            v += 0.5 * h * force * self.inverse_mass
        return force, contact, e_contact


def advance(model: Model, scheme: str, dt: float, steps: int):
    """The state after ``steps`` steps from the scene's initial state (for tests)."""
    x, v = model.system.x.copy(), model.system.v.copy()
    stepper = Stepper(model, scheme, dt)
    force = stepper.forces(x)[0]
    for _ in range(steps):
        force = stepper.step(x, v, force)[0]
    return x, v


def simulate(folder: Path | str, options: ReferenceOptions) -> float:
    """Integrate the scene in ``folder``; writes series.dat and energy.dat.

    Parameters
    ----------
    folder : pathlib.Path or str
        A scene folder (scene.data, scene.json).
    options : ReferenceOptions
        Time step, integrator, contact and outputs.

    Returns
    -------
    float
        Wall time, seconds.

    Raises
    ------
    Unstable
        If the run blows up or a disk point goes into the wall.
    """
    options.validate()
    folder = Path(folder)
    model = load_model(folder, options)
    x, v = model.system.x.copy(), model.system.v.copy()
    observe = Observer(model)
    stepper = Stepper(model, options.integrator, options.dt)
    dt = options.dt

    start = time.perf_counter()
    force, contact, e_contact = stepper.forces(x)
    series = [observe.header(), observe.row(0, 0.0, x, v, contact, e_contact)]
    body = "target" if observe.binary else "wall"
    energies = [
        f"# time ke_disk pe_disk ke_{body} pe_{body} pe_contact\n",
        observe.energies(0.0, x, v, e_contact),
    ]
    touched, step = False, 0
    while True:
        try:
            force, contact, e_contact = stepper.step(x, v, force)
        except InsideWall as error:
            raise Unstable(
                f"a disk point is inside the wall at time {step * dt:.4g}: {error}"
            ) from error
        except TurnedOver as error:
            raise Unstable(f"at time {step * dt:.4g}, {error}") from error
        step += 1
        if step % options.every == 0:
            series.append(observe.row(step, step * dt, x, v, contact, e_contact))
        if step % options.check == 0:
            if not np.isfinite(v).all():
                raise Unstable(f"the run went unstable at time {step * dt:.4g}")
            touched = touched or e_contact > 0.0
            if touched and observe.finished(x, v, e_contact):
                break
            if step * dt >= options.tmax:
                raise Unstable(f"the disk has not left the wall by tmax = {options.tmax}")
    seconds = time.perf_counter() - start
    energies.append(observe.energies(step * dt, x, v, e_contact))
    gate.write_text(folder / "series.dat", "".join(series))
    gate.write_text(folder / "energy.dat", "".join(energies))
    if model.barrier and len(model.system.angles):
        # as decks/impact.lmp writes fix area/barrier's counts (here over every
        # force evaluation: the steps, and a composition's substeps)
        gate.write_text(
            folder / "barrier.dat",
            f"# most_in_barrier min_area_ratio\n{model.in_barrier_max} {model.area_ratio_min!r}\n",
        )
    return seconds


def run_reference(folder: Path | str, options: ReferenceOptions) -> dict:
    """Simulate, then write run.json and result.json like a LAMMPS run.

    Parameters
    ----------
    folder : pathlib.Path or str
        A scene folder (scene.data, scene.json); earlier outputs are removed.
    options : ReferenceOptions
        Time step, integrator, contact and outputs.

    Returns
    -------
    dict
        The result (``analysis.impact.result.analyse_run``), as written to result.json.
    """
    folder = Path(folder)
    for name in ("series.dat", "energy.dat", "barrier.dat", "run.json", "result.json"):
        (folder / name).unlink(missing_ok=True)
    seconds = simulate(folder, options)
    run = {
        "options": {**asdict(options), "springs": "class2", "route": "reference", "nprocs": 1},
        "wall_seconds": seconds,
        "lammps_version": VERSION,
        "git_revision": git_revision(),
    }
    write_json_atomically(run, folder / "run.json")
    result = analyse_run(folder)
    if any(isinstance(v, float) and not math.isfinite(v) for v in result.values()):
        raise Unstable("non-finite results; no result written")
    write_json_atomically(result, folder / "result.json")
    return result
