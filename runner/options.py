"""How a scene is run: integrator, time step, contact, outputs."""

from __future__ import annotations

import math
from dataclasses import asdict, replace

from builder.declared import with_options
from builder.run_options import (  # noqa: F401 (the run's ranges and words, for the command line)
    AUTO,
    CONTACTS,
    DEFAULT_DT,
    DRIFT,
    DT,
    DUMP_EVERY,
    HALVINGS,
    INTEGRATORS,
    NPROCS,
    NRESPA,
    RESPA_DT,
    RESPA_NRESPA,
    ROUTES,
    RULES,
    RUN_OPTIONS,
    SPRINGS,
    STEPS,
    STOP_RULES,
    TMAX,
)
from ground.errors import InputError

MAX_CHUNK_TIME = 2.0  # R/c between checks at most; the shortest contacts last about 9
# Rows of series.dat and checks for the end are spaced in time, so that a
# change of dt keeps what they resolve and what they cost per R/c.
SERIES_INTERVAL = 0.08  # R/c between rows of series.dat
CHECK_INTERVAL = 0.8  # R/c between checks whether the impact is over
RANKS = NPROCS  # a study's MPI ranks per impact ([run] ranks, --ranks)


@with_options(RUN_OPTIONS)
class RunOptions:
    """How a scene is run; its fields are builder.run_options.RUN_OPTIONS's."""

    def for_scene(self, spec) -> RunOptions:
        """These options with dt "auto" made the scene's step: DEFAULT_DT times
        ``spec.step_scale`` (a builder.scene.SceneSpec), exactly DEFAULT_DT at
        the 800-point disk on its 1,600-point wall."""
        if self.dt != AUTO:
            return self
        # times are c's over the disk's lengths: a disk of radius R takes R
        # times as long (at R = 1, exactly DEFAULT_DT times the step scale)
        return replace(self, dt=DEFAULT_DT * spec.step_scale * spec.radius)

    def scene_problem(self, spec) -> str | None:
        """Why these options cannot run ``spec`` (a builder.scene.SceneSpec)
        at all, or None: dt auto outside dt's range (a radius far from 1), a
        tmax shorter than one step or than the disk's approach to the wall
        (c-speeds only: speed_unit spring has its own unit), a start beyond
        the wall's end. A disk still on the wall at tmax is an outcome, not
        refused here."""
        step = self.for_scene(spec).step
        if self.dt == AUTO and not DT.contains(step):
            return (
                f"radius {spec.radius:g}: its step (dt auto, {DEFAULT_DT:g} x the scene's step "
                f"scale x radius) would be {step:.3g}, outside dt's {DT.describe()}: give a "
                "radius nearer 1, more disk points, or --dt"
            )
        if self.tmax < step:
            return (
                f"tmax {self.tmax:g} R/c is shorter than one step (dt {step:g}): give a larger tmax"
            )
        if spec.target != "wall":
            return None
        gap = (1.0 + spec.start_gap) * spec.wall_spacing * spec.radius
        # placed back along its velocity, the disk starts gap tan(gamma) to the
        # side of where it touches: beyond the wall's end, it never meets it
        # (near 90 degrees LAMMPS says only "box size << cutoff")
        side = gap * math.tan(math.radians(spec.gamma_deg))
        if side > spec.wall_width * spec.radius / 2.0:
            return (
                f"gamma {spec.gamma_deg:g}: the disk would start {side:.3g} to the side of where "
                f"it touches the wall, beyond the wall's half-width "
                f"{spec.wall_width * spec.radius / 2.0:g}; give a smaller gamma or a wider wall "
                "(--wall-width)"
            )
        if spec.speed_unit != "c":
            return None
        # the disk starts start_gap wall spacings beyond the contact's range
        approach = spec.start_gap * spec.wall_spacing * spec.radius / spec.vn
        if self.tmax < approach:
            return (
                f"tmax {self.tmax:g} R/c is too short for the disk to reach the wall: at vn "
                f"{spec.vn:g} it takes {approach:.3g} to cross the gap it starts with; give a "
                "larger tmax or vn"
            )
        return None

    @property
    def step(self) -> float:
        """dt as a number: an "auto" step is DEFAULT_DT's (the 800-point disk's)."""
        return DEFAULT_DT if self.dt == AUTO else self.dt

    def validate(self) -> None:
        for option in RUN_OPTIONS:  # each alone, then what they must be together
            option.check(getattr(self, option.name))
        if self.tmax / self.step > STEPS.high:
            raise InputError(
                f"tmax / dt must be at most {STEPS.high:.0e} steps, got {self.tmax:g} / "
                f"{self.step:g}; give a larger dt or a smaller tmax"
            )
        every, check = self.every_steps, self.check_steps
        # the deck learns that the disk has touched from the contact energy at its
        # checks: checks farther apart than a contact lasts (9 R/c and more)
        # could miss it whole, and the run would never stop
        if check * self.step > MAX_CHUNK_TIME:
            raise InputError(
                f"check * dt must be at most {MAX_CHUNK_TIME:g} R/c (checks closer "
                f"than any contact lasts), got {check} * {self.step:g} = "
                f"{check * self.step:g}; give a smaller check"
            )
        if check % every:
            raise InputError(f"check must be a multiple of every ({every}), got {check}")
        if self.dump_every and check % self.dump_every:
            raise InputError(
                f"dump_every must divide check ({check}) so that the last "
                f"state is dumped, got {self.dump_every}"
            )
        if self.route == "python" and self.nprocs != 1:
            raise InputError("nprocs must be 1 with route python (run MPI jobs through lmp)")

    @property
    def every_steps(self) -> int:
        """Steps between rows of series.dat: every, or SERIES_INTERVAL's."""
        return self.every or max(1, round(SERIES_INTERVAL / self.step))

    @property
    def check_steps(self) -> int:
        """Steps between checks for the end: check, or the multiple of every
        nearest CHECK_INTERVAL."""
        every = self.every_steps
        return self.check or every * max(1, round(CHECK_INTERVAL / (every * self.step)))

    def as_dict(self) -> dict:
        return asdict(self)

    def deck_variables(self) -> dict[str, str]:
        """The deck's index variables for these options (dt a number: ``for_scene``)."""
        if self.dt == AUTO:
            raise ValueError("dt 'auto' is a scene's step: RunOptions.for_scene first")
        names = (
            "dt",
            "integrator",
            "nrespa",
            "contact",
            "rule",
            "springs",
            "tmax",
            "every",
            "check",
            "dump_every",
            "stop_rule",
        )
        values = {**self.as_dict(), "every": self.every_steps, "check": self.check_steps}
        return {
            name: repr(values[name]) if isinstance(values[name], float) else str(values[name])
            for name in names
        }


def on_ranks(options: RunOptions, ranks: int) -> RunOptions:
    """``options`` with each impact on ``ranks`` MPI ranks.

    More than one rank runs the deck with lmp under mpirun (or IMPACT_MPIRUN),
    as ``runner impact --np`` does: Debian's lammps module runs one rank in
    the calling process, which is a study's route on one rank.

    Parameters
    ----------
    options : RunOptions
        A study's run options.
    ranks : int
        MPI ranks per impact, ``RANKS``.

    Returns
    -------
    RunOptions
        A copy with ``nprocs`` and ``route`` set.
    """
    return replace(options, nprocs=ranks, route="lmp" if ranks > 1 else "python")


def halved_step(options: RunOptions, times: int = 1) -> RunOptions:
    """``options`` (dt a number) at the step halved ``times`` times, with its
    series' rows and checks at the same times (given in steps, they double)."""
    scale = 2**times
    return replace(
        options, dt=options.dt / scale, every=scale * options.every, check=scale * options.check
    )
