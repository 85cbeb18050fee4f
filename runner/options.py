"""How a scene is run: integrator, time step, contact, outputs."""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

from analysis.result import MAX_DRIFT
from builder.lammps_data import DEFAULT_SPRINGS, SPRING_STYLES
from ground.checks import Range
from ground.errors import InputError, require_choice

INTEGRATORS = ("verlet", "respa")
CONTACTS = ("segment", "pair")
RULES = ("lever", "gradient")
SPRINGS = SPRING_STYLES
ROUTES = ("lmp", "python")
STOP_RULES = ("predict", "clearance")  # runner/stop_rule.py
MAX_CHUNK_TIME = 2.0  # R/c between checks at most; the shortest contacts last about 9
# Rows of series.dat and checks for the end are spaced in time, so that a
# change of dt keeps what they resolve and what they cost per R/c.
SERIES_INTERVAL = 0.08  # R/c between rows of series.dat
CHECK_INTERVAL = 0.8  # R/c between checks whether the impact is over
# rRESPA's split (the outer step, the contact's steps per step) that make bench
# picks by the default's criteria (docs/benchmarks/time_vs_error.md); not the
# default integrator: on today's scene it is slower than Verlet at its default
# step (docs/benchmarks.md).
RESPA_DT, RESPA_NRESPA = 0.016, 8
# The ranges of the run's numbers, for RunOptions.validate and the command
# line alike. No scene runs above dt 0.032 (docs/benchmarks/stability.md).
DT = Range(1e-5, 0.05, unit="R/c")
# The step at the 800-point disk (docs/benchmarks/time_vs_error.md); dt "auto"
# takes it times the scene's step scale, which follows the finer body's
# spacing (builder.scene.SceneSpec.step_scale): 0.002 at 12,800 points.
DEFAULT_DT = 0.008
AUTO = "auto"
TMAX = Range(0.0, 10_000.0, low_open=True, unit="R/c")
NRESPA = Range(1, 100, integer=True)
STEPS = Range(1, 10_000_000, integer=True)  # every, check
DUMP_EVERY = Range(0, 10_000_000, integer=True)
NPROCS = Range(1, 4096, integer=True)
RANKS = NPROCS  # a study's MPI ranks per impact ([run] ranks, --ranks)
DRIFT = Range(0.0, 1.0, low_open=True, unit="of the initial kinetic energy")


@dataclass
class RunOptions:
    # time step, R / c, or "auto": DEFAULT_DT at 800 points, following the
    # spacing (``for_scene``); respa: the outer one
    dt: float | str = AUTO
    # verlet: velocity Verlet, everything at dt; respa: rRESPA, the springs at dt
    # and the contact alone on the inner level at dt / nrespa (decks/setup.lmp)
    integrator: str = "verlet"
    nrespa: int = RESPA_NRESPA  # respa: contact steps per step of dt
    contact: str = "segment"  # segment: the paper's contact; pair: the design card
    rule: str = "lever"  # segment contact: lever rule or explicit gradient
    springs: str = DEFAULT_SPRINGS  # harmonic/quartic or class2: the model's quartic springs;
    # harmonic: no quartic
    tmax: float = 100.0  # give up after this time, R / c
    every: int = 0  # steps between rows of series.dat; 0: SERIES_INTERVAL's
    check: int = 0  # steps between checks whether the impact is over; 0: CHECK_INTERVAL's
    dump_every: int = 0  # steps between dump frames; 0: no dump
    stop_rule: str = (
        "predict"  # predict (rigid-body extrapolation) or clearance (runner/stop_rule.py)
    )
    nprocs: int = 1  # MPI ranks (route lmp)
    route: str = "lmp"  # lmp: the lmp program; python: the lammps module
    max_drift: float = (
        MAX_DRIFT  # energy drift above which a result is flagged (analysis/result.py)
    )

    def for_scene(self, spec) -> RunOptions:
        """These options with dt "auto" made the scene's step: DEFAULT_DT times
        ``spec.step_scale`` (a builder.scene.SceneSpec), exactly DEFAULT_DT at
        the 800-point disk on its 1,600-point wall."""
        if self.dt != AUTO:
            return self
        return replace(self, dt=DEFAULT_DT * spec.step_scale)

    @property
    def step(self) -> float:
        """dt as a number: an "auto" step is DEFAULT_DT's (the 800-point disk's)."""
        return DEFAULT_DT if self.dt == AUTO else self.dt

    def validate(self) -> None:
        if self.dt != AUTO:
            DT.check("dt", self.dt)
        require_choice("integrator", self.integrator, INTEGRATORS)
        NRESPA.check("nrespa", self.nrespa)
        require_choice("contact", self.contact, CONTACTS)
        require_choice("rule", self.rule, RULES)
        require_choice("springs", self.springs, SPRINGS)
        TMAX.check("tmax", self.tmax)
        DRIFT.check("max_drift", self.max_drift)
        for name in ("every", "check"):
            value = getattr(self, name)
            if value != 0:
                STEPS.check(f"{name} (0 for the default)", value)
        NPROCS.check("nprocs", self.nprocs)
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
        DUMP_EVERY.check("dump_every", self.dump_every)
        if self.dump_every and check % self.dump_every:
            raise InputError(
                f"dump_every must divide check ({check}) so that the last "
                f"state is dumped, got {self.dump_every}"
            )
        require_choice("stop_rule", self.stop_rule, STOP_RULES)
        require_choice("route", self.route, ROUTES)
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
