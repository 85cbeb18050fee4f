"""Starting LAMMPS, for every package: decks/impact.lmp (or another deck) with the lmp
program, serial or under MPI, or in this process through the lammps module
with the project's styles registered; and what its log says (the error, the
version)."""

from __future__ import annotations

import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from .paths import BUILD, DECKS, ROOT

DECK = DECKS / "impact.lmp"
RESTART_DECK = DECKS / "write_restart.lmp"


class LammpsError(RuntimeError):
    """LAMMPS stopped with an error; the message is LAMMPS's own."""


def lammps_error(log: Path, fallback: str) -> str:
    """The ERROR line of a LAMMPS log, or ``fallback`` if there is none.

    Parameters
    ----------
    log : pathlib.Path
        A LAMMPS log file (it may not exist).
    fallback : str
        The message if the log holds no ERROR line.

    Returns
    -------
    str
        The first ERROR line, without LAMMPS's source-file reference.
    """
    if log.exists():
        for line in log.read_text(errors="replace").splitlines():
            if line.startswith("ERROR"):
                return re.sub(r"\s*\([^()]*\.cpp:\d+\)\s*$", "", line)
    return fallback


def lammps_version(log: Path) -> str:
    """The version LAMMPS prints first in its log, e.g. '29 Sep 2021 - Update 2'.

    Parameters
    ----------
    log : pathlib.Path
        A LAMMPS log file.

    Returns
    -------
    str
        The version, or ``unknown``.
    """
    match = re.match(r"LAMMPS \((.*)\)", log.read_text(errors="replace"))
    return match.group(1) if match else "unknown"


def command_line(variables: dict[str, str], log: Path, deck: Path = DECK) -> list[str]:
    """lmp's arguments: the deck (decks/impact.lmp unless given), its log and -var settings."""
    args = ["-in", str(deck), "-log", str(log), "-screen", "none", "-nocite"]
    for name, value in variables.items():
        args += ["-var", name, value]
    return args


def mpi_launcher(nprocs: int) -> list[str]:
    """mpirun for ``nprocs`` ranks, nothing for one. IMPACT_MPIRUN replaces
    mpirun, with ``-n nprocs`` after its words: "srun --mpi=pmix" under Slurm
    (OpenMPI's direct launch needs PMIx; plain srun fails on Debian 12)."""
    if nprocs == 1:
        return []
    if os.environ.get("IMPACT_MPIRUN"):
        words = os.environ["IMPACT_MPIRUN"].split()
        if shutil.which(words[0]) is None:
            raise LammpsError(
                f"IMPACT_MPIRUN: {words[0]} is not a program on PATH; unset IMPACT_MPIRUN "
                "(mpirun) or name one, such as srun --mpi=pmix"
            )
        return words + ["-n", str(nprocs)]
    if shutil.which("mpirun") is None:
        raise LammpsError(
            "mpirun not found: install openmpi-bin (make setup) to run on several ranks"
        )
    # By name, not by its full path: Open MPI's mpirun called as /usr/bin/mpirun
    # acts as if given --prefix /usr and puts /usr/bin first on the ranks' PATH,
    # so lmp's embedded Python would start from Debian's python3, not ours.
    # Unbound: Open MPI binds up to 2 ranks to the first cores by default, and
    # so every one of a study's workers' mpiruns would, onto the same cores.
    return ["mpirun", "--bind-to", "none", "-np", str(nprocs)]


# Linux's prctl, to end lmp (or mpirun, which ends its ranks) with the process
# that started it: a study's worker killed from outside must not leave its
# impact's LAMMPS running, writing into the folder the impact's next start uses.
PR_SET_PDEATHSIG = 1
_PRCTL = getattr(ctypes.CDLL(None), "prctl", None) if sys.platform == "linux" else None


def ends_with_parent():
    """A ``preexec_fn`` that has the child sent SIGTERM when the thread that
    started it ends (it waits for the child, so: when its process ends), or
    None where there is no prctl."""
    if _PRCTL is None:
        return None
    parent = os.getpid()

    def arm() -> None:
        _PRCTL(PR_SET_PDEATHSIG, int(signal.SIGTERM))
        if os.getppid() != parent:  # the parent ended before the signal was armed
            os._exit(1)

    return arm


def _inherited_mpi_job(name: str) -> bool:
    """A variable that Open MPI sets in a process it runs (or, through the
    lammps module, a singleton): passed on, mpirun would take itself for a
    rank of that job and fail to start."""
    if name.startswith(("PMIX_", "ORTE_", "OMPI_MCA_orte_", "OMPI_MCA_ess", "OMPI_MCA_pmix")):
        return True
    return name.startswith("OMPI_") and not name.startswith(("OMPI_MCA_", "OMPI_ALLOW_RUN_AS_ROOT"))


def mpi_environment() -> dict[str, str]:
    """The environment for lmp and mpirun.

    lmp's embedded Python (the contact style's loader, the stop rule) takes
    its prefix from the first python3 on PATH, which must be this interpreter.
    Open MPI refuses root (CI) unless told. What this process inherited or
    set up as an MPI process itself stays out.
    """
    env = {name: value for name, value in os.environ.items() if not _inherited_mpi_job(name)}
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    if os.geteuid() == 0:
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def require_lmp(env: dict[str, str] | None = None) -> None:
    """Refuse, in one line, a machine without lmp on the PATH lmp gets
    (rather than a FileNotFoundError's traceback after the build)."""
    env = env or mpi_environment()
    if shutil.which("lmp", path=env.get("PATH")) is None:
        raise LammpsError(
            "lmp not found on PATH: install Debian's lammps (make setup), or run on one rank "
            "with --route python"
        )


def run_lmp(variables: dict[str, str], log: Path, nprocs: int = 1, deck: Path = DECK) -> float:
    """Run a deck with lmp; returns the wall time in seconds.

    Parameters
    ----------
    variables : dict of str to str
        ``-var`` settings of the deck (decks/impact.lmp: at least ``scene``).
    log : pathlib.Path
        Where LAMMPS writes its log.
    nprocs : int
        MPI ranks; 1 runs lmp without mpirun.
    deck : pathlib.Path
        The input script; decks/impact.lmp unless given (decks/stretch.lmp:
        calibration/stretch.py).

    Returns
    -------
    float
        Wall time, seconds.

    Raises
    ------
    LammpsError
        If lmp fails; the message is LAMMPS's ERROR line.
    """
    env = mpi_environment()
    require_lmp(env)
    start = time.perf_counter()
    proc = subprocess.run(
        mpi_launcher(nprocs) + ["lmp"] + command_line(variables, log, deck),
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=env,
        preexec_fn=ends_with_parent(),  # it calls prctl alone: no lock a thread could hold
    )
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        tail = (proc.stderr.strip() or proc.stdout.strip()).splitlines()[-1:] or ["no output"]
        raise LammpsError(lammps_error(log, f"lmp exited with {proc.returncode}: {tail[0]}"))
    return elapsed


def open_lammps(variables: dict[str, str] | None = None, log: Path | None = None):
    """A LAMMPS instance in this process (the lammps module), with the
    project's styles registered: the one place the project makes one.

    Parameters
    ----------
    variables : dict of str to str, optional
        ``-var`` settings for the input it will read.
    log : pathlib.Path, optional
        Where LAMMPS writes its log; none if not given.

    Returns
    -------
    lammps.lammps
        The instance; its caller closes it.
    """
    from lammps import lammps

    lmp = lammps(cmdargs=command_line(variables or {}, log or Path(os.devnull))[2:])
    register_styles(lmp)
    return lmp


def run_python(variables: dict[str, str], log: Path) -> float:
    """Run the deck in this process through the lammps module.

    Debian's LAMMPS is built without C++ exceptions, so a LAMMPS error ends
    this process; drivers that must survive failed impacts run this in a child.

    Parameters
    ----------
    variables : dict of str to str
        ``-var`` settings of decks/impact.lmp (at least ``scene``).
    log : pathlib.Path
        Where LAMMPS writes its log.

    Returns
    -------
    float
        Wall time, seconds.
    """
    start = time.perf_counter()
    cwd = os.getcwd()
    os.chdir(ROOT)
    # The styles are registered here, so the deck's loaders, which would each
    # make a lammps wrapper of their own (26 ms apiece), have nothing to do.
    variables = {
        **variables,
        "polyline_load": "none",
        "springs_load": "none",
        "impact2d_load": "none",
        "area_barrier_load": "none",
    }
    try:
        lmp = open_lammps(variables, log)
        ACTIVE[lmp.lmp.value] = lmp
        try:
            lmp.file(str(DECK))
        finally:
            ACTIVE.pop(lmp.lmp.value, None)
        lmp.close()
    finally:
        os.chdir(cwd)
    return time.perf_counter() - start


def data_has_angles(data: Path) -> bool:
    """Whether a data file's header declares angles (the barrier's, --area-floor)."""
    with open(data) as handle:
        for line in handle:
            words = line.split()
            if words[-1:] == ["angles"]:
                return True
            if words[-2:] == ["xlo", "xhi"]:  # the header's counts come before the box
                return False
    return False


def data_to_restart(data: Path, restart: Path, springs: str, log: Path | None = None) -> Path:
    """Write the data file ``data`` of bodies as a binary restart, in this
    process (decks/write_restart.lmp), LAMMPS's log into ``log`` (none if
    not given): the deck reads it in a tenth of read_data's time, into the
    same atoms in the same order.

    Returns
    -------
    pathlib.Path
        ``restart``.
    """
    variables = {"data": str(data), "restart": str(restart), "springs": springs}
    variables.update({"springs_load": "none", "impact2d_load": "none", "area_barrier_load": "none"})
    if data_has_angles(data):  # the barrier's triangles (--area-floor): atom_style angle
        variables["angles"] = "area/barrier"
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        lmp = open_lammps(variables, log)
        lmp.file(str(RESTART_DECK))
        lmp.close()
    finally:
        os.chdir(cwd)
    return restart


# The lammps objects of the instances run_python is running, by their address:
# the deck's Python callbacks (decks/future_clear.py) use them instead of
# making wrappers of their own.
ACTIVE: dict[int, object] = {}
STYLE_LIBRARIES = {
    ("pair", "polyline/exp"): ("libpolyline_exp.so", "polyline_exp_register"),
    ("bond", "harmonic/quartic"): ("libharmonic_quartic.so", "harmonic_quartic_register"),
    ("compute", "motion/2d"): ("libimpact_2d.so", "impact_2d_register"),
    ("fix", "nve/2d"): ("libimpact_2d.so", "impact_2d_register"),
    ("angle", "area/barrier"): ("libarea_barrier.so", "area_barrier_register"),
    ("fix", "area/barrier"): ("libarea_barrier.so", "area_barrier_register"),
}


def register_styles(lmp) -> None:
    """Register the project's styles (potentials/) into a LAMMPS instance that
    lacks them (Debian's build; see decks/polyline_exp.lmp)."""
    import ctypes

    for (kind, style), (library, function) in STYLE_LIBRARIES.items():
        if not lmp.has_style(kind, style):
            getattr(ctypes.CDLL(str(BUILD / library)), function)(lmp.lmp)
