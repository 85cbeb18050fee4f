"""How a scene is run, declared once: every run option's type, range,
default and help (builder/declared.py), from which runner.options.RunOptions,
its checks, runner impact/run's and runner study's options, a study file's
[run] keys and the "made by" command line follow. Plain data, below the
runner and the analysis, which both read it.
"""

from __future__ import annotations

from ground.checks import Range

from .declared import Option, by_name
from .lammps_data import DEFAULT_SPRINGS, SPRING_STYLES

INTEGRATORS = ("verlet", "respa")
CONTACTS = ("segment", "pair")
RULES = ("lever", "gradient")
SPRINGS = SPRING_STYLES
ROUTES = ("lmp", "python")
STOP_RULES = ("predict", "clearance")  # runner/stop_rule.py
# The ranges of the run's numbers. No scene runs above dt 0.032 (docs/benchmarks/stability.md).
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
DRIFT = Range(0.0, 1.0, low_open=True, unit="of the initial kinetic energy")
HALVINGS = Range(0, 6, integer=True)
# The energy drift above which a result is flagged (analysis/impact/result.py).
MAX_DRIFT = 0.05
# rRESPA's split (the outer step, the contact's steps per step) that make bench
# picks by the default's criteria (docs/benchmarks/time_vs_error.md); not the
# default integrator: on today's scene it is slower than Verlet at its default
# step (docs/benchmarks.md).
RESPA_DT, RESPA_NRESPA = 0.016, 8

# study_cli: runner study's own option (the others: its file's [run]).
RUN_OPTIONS = (
    Option("dt", AUTO, f"time step, or auto: {DEFAULT_DT:g} at 800 disk points, scaled with "
           "the finer body's spacing; respa: the outer one", DT, (AUTO,), section="run",
           made_by="always", kind=float | str),
    Option("integrator", "verlet", "verlet: velocity Verlet, everything at dt; respa: rRESPA, "
           "the springs at dt and the contact alone on the inner level at dt / nrespa",
           words=INTEGRATORS, section="run", study_cli=False),
    Option("nrespa", RESPA_NRESPA, "respa: contact steps per step of --dt (the contact alone "
           "on the inner level)", NRESPA, section="run", study_cli=False),
    Option("contact", "segment", "segment: the paper's point-to-polyline contact; pair: the "
           "same exponential between points", words=CONTACTS, section="run", study_cli=False),
    Option("rule", "lever", "segment contact: lever rule or explicit gradient", words=RULES,
           section="run", study_cli=False),
    Option("springs", DEFAULT_SPRINGS, "bond style: harmonic/quartic (the project's own) or "
           "class2, the same quartic springs; harmonic: no quartic", words=SPRINGS,
           section="run", study_cli=False),
    Option("tmax", 100.0, "stop with an error if the disk has not left by then", TMAX,
           section="run", study_cli=False),
    Option("every", 0, "steps between rows of series.dat (0: the steps nearest 0.08 R/c)",
           STEPS, (0,), hide_words=True, section="run", study_cli=False, cli=False),
    Option("check", 0, "steps between checks whether the impact is over, a multiple of the "
           "series' rows; check * dt at most 2 R/c (0: the steps nearest 0.8 R/c)", STEPS, (0,),
           hide_words=True, section="run", study_cli=False),
    Option("dump_every", 0, "steps between dump frames (0: no dump)", DUMP_EVERY,
           section="run", study_cli=False),
    Option("stop_rule", "predict", "when the impact is over: predict (rigid-body "
           "extrapolation) or clearance (wait until the disk clears every asperity)",
           words=STOP_RULES, section="run", study_cli=False),
    Option("nprocs", 1, "MPI ranks (route lmp)", NPROCS, section="run", study_cli=False,
           flag="--np"),
    Option("route", "lmp", "lmp: the lmp program; python: the lammps module", words=ROUTES,
           section="run", study_cli=False),
    Option("max_drift", MAX_DRIFT, "flag a run whose energy drift (change of the total energy "
           "over the initial kinetic energy) exceeds this: its time step is too large (99 % of "
           "the paper study below 4.7e-3 at the default dt; docs/benchmarks/time_vs_error.md)",
           DRIFT, section="run", made_by="always"),
    Option("barrier_halvings", 2, "times the impact may run again at half the step when a "
           "triangle crosses the area barrier (--area-floor) within one step, a step too long "
           "for the barrier's stiffness, or, with --dt auto, when the contact finds the step "
           "too long (a point in the wall, a segment torn: grazing angles) (0: stop there); "
           "the step run is recorded",
           HALVINGS, section="run", study_cli=False),
)  # fmt: skip
RUN = by_name(RUN_OPTIONS)
