"""How a scene is run: integrator, time step, contact, outputs."""

from __future__ import annotations

from dataclasses import asdict, dataclass

from analysis.result import MAX_DRIFT
from builder.errors import InputError, require_choice, require_positive
from builder.lammps_data import DEFAULT_SPRINGS, SPRING_STYLES

INTEGRATORS = ("verlet", "respa")
CONTACTS = ("segment", "pair")
RULES = ("lever", "gradient")
SPRINGS = SPRING_STYLES
ROUTES = ("lmp", "python")
MAX_CHUNK_TIME = 2.0  # R/c; the shortest contacts last about 9


@dataclass
class RunOptions:
    dt: float = 0.008  # time step, R / c (docs/benchmarks/time_vs_error.md, drift_tail.md)
    integrator: str = "verlet"
    nrespa: int = 2  # respa: spring steps per step
    contact: str = "segment"  # segment: the paper's contact; pair: the design card
    rule: str = "lever"  # segment contact: lever rule or explicit gradient
    springs: str = DEFAULT_SPRINGS  # harmonic/quartic or class2: the model's quartic springs;
    # harmonic: no quartic
    tmax: float = 100.0  # give up after this time, R / c
    every: int = 10  # steps between rows of series.dat
    check: int = 100  # steps between checks whether the impact is over (0.8 R/c)
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
        require_positive("dt", self.dt)
        require_choice("integrator", self.integrator, INTEGRATORS)
        if not (isinstance(self.nrespa, int) and self.nrespa >= 1):
            raise InputError(f"nrespa must be an integer >= 1, got {self.nrespa}")
        require_choice("contact", self.contact, CONTACTS)
        require_choice("rule", self.rule, RULES)
        require_choice("springs", self.springs, SPRINGS)
        require_positive("tmax", self.tmax)
        require_positive("max_drift", self.max_drift)
        for name in ("every", "check", "nprocs"):
            value = getattr(self, name)
            if not (isinstance(value, int) and value >= 1):
                raise InputError(f"{name} must be an integer >= 1, got {value}")
        # the deck learns that the disk has touched from the contact energy at the
        # ends of its chunks: a chunk longer than a contact (9 R/c and more) could
        # hold it whole, and the run would never stop
        if self.check * self.dt > MAX_CHUNK_TIME:
            raise InputError(
                f"check * dt must be at most {MAX_CHUNK_TIME:g} R/c (a chunk shorter "
                f"than any contact), got {self.check} * {self.dt:g} = "
                f"{self.check * self.dt:g}"
            )
        if self.check % self.every:
            raise InputError(f"check must be a multiple of every ({self.every}), got {self.check}")
        if not (isinstance(self.dump_every, int) and self.dump_every >= 0):
            raise InputError(f"dump_every must be an integer >= 0, got {self.dump_every}")
        if self.dump_every and self.check % self.dump_every:
            raise InputError(
                f"dump_every must divide check ({self.check}) so that the last "
                f"state is dumped, got {self.dump_every}"
            )
        require_choice("stop_rule", self.stop_rule, ("predict", "clearance"))
        require_choice("route", self.route, ROUTES)
        if self.route == "python" and self.nprocs != 1:
            raise InputError("nprocs must be 1 with route python (run MPI jobs through lmp)")

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
        return {
            name: repr(getattr(self, name))
            if isinstance(getattr(self, name), float)
            else str(getattr(self, name))
            for name in names
        }
