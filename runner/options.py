"""How a scene is run: integrator, time step, contact, outputs."""

from __future__ import annotations

from dataclasses import asdict, dataclass

from analysis.result import MAX_DRIFT
from builder.checks import Range
from builder.errors import InputError, require_choice
from builder.lammps_data import DEFAULT_SPRINGS, SPRING_STYLES

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
TMAX = Range(0.0, 10_000.0, low_open=True, unit="R/c")
NRESPA = Range(1, 100, integer=True)
STEPS = Range(1, 10_000_000, integer=True)  # every, check
DUMP_EVERY = Range(0, 10_000_000, integer=True)
NPROCS = Range(1, 4096, integer=True)
DRIFT = Range(0.0, 1.0, low_open=True, unit="of the initial kinetic energy")


@dataclass
class RunOptions:
    dt: float = 0.008  # time step, R / c (docs/benchmarks/time_vs_error.md); respa: the outer one
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

    def validate(self) -> None:
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
        if self.tmax / self.dt > STEPS.high:
            raise InputError(
                f"tmax / dt must be at most {STEPS.high:.0e} steps, got {self.tmax:g} / "
                f"{self.dt:g}; give a larger dt or a smaller tmax"
            )
        every, check = self.every_steps, self.check_steps
        # the deck learns that the disk has touched from the contact energy at its
        # checks: checks farther apart than a contact lasts (9 R/c and more)
        # could miss it whole, and the run would never stop
        if check * self.dt > MAX_CHUNK_TIME:
            raise InputError(
                f"check * dt must be at most {MAX_CHUNK_TIME:g} R/c (checks closer "
                f"than any contact lasts), got {check} * {self.dt:g} = "
                f"{check * self.dt:g}; give a smaller check"
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
        return self.every or max(1, round(SERIES_INTERVAL / self.dt))

    @property
    def check_steps(self) -> int:
        """Steps between checks for the end: check, or the multiple of every
        nearest CHECK_INTERVAL."""
        every = self.every_steps
        return self.check or every * max(1, round(CHECK_INTERVAL / (every * self.dt)))

    def as_dict(self) -> dict:
        return asdict(self)

    def deck_variables(self) -> dict[str, str]:
        """The deck's index variables for these options."""
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
