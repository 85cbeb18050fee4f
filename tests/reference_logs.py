"""Reference logs of the paper's impact, as LAMMPS's examples ship them.

``decks/log.<date>.impact.g++.1`` and ``.2`` are LAMMPS's logs of
decks/impact.lmp on the paper's scene at 30 degrees, seed 1 (``python -m
runner impact`` with SCENE_ARGS), with one and two MPI ranks and a thermo
row every 20 steps (0.16 R/c at the default step). ``make reference-logs``
(``main``) writes them anew, replacing the old ones: run it, and commit the result,
whenever the paper's scene or the deck changes. tests/runner/test_reference_logs.py
checks a fresh run against them.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from datetime import date
from pathlib import Path

import numpy as np

from ground.launch import mpi_environment, mpi_launcher
from tests.helpers import ROOT

DECKS = ROOT / "decks"
NAME = "impact"
# the paper's scene (builder.scene.PAPER, the reading "paper"), every other
# option at its default: the logs were made on it before the default became
# the refined body (issue 46)
SCENE_ARGS = ["--gamma", "30", "--seed", "1", "--roughness-length", "0", "--roughness-profile",
              "sampled", "--contact-scaling", "spacing", "--area-floor", "0"]  # fmt: skip
THERMO_EVERY = 20
# Relative to the project's root (the deck's working directory), so that the
# logs name no machine's temporary folder.
SCENE = Path("runs") / "reference-logs" / "scene"


def build_scene(folder: Path = SCENE) -> Path:
    """Write the paper's scene (``python -m builder scene`` with SCENE_ARGS)
    into ``folder``, relative to the project's root.

    Parameters
    ----------
    folder : pathlib.Path
        Destination, relative to the project's root or absolute.

    Returns
    -------
    pathlib.Path
        ``folder``.
    """
    subprocess.run(
        [sys.executable, "-m", "builder", "scene", *SCENE_ARGS, "--out", str(folder)],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    )
    return folder


def run_impact(scene: Path, log: Path, nprocs: int = 1) -> Path:
    """Run decks/impact.lmp on ``scene`` with lmp on ``nprocs`` ranks, thermo
    every THERMO_EVERY steps, its log into ``log``.

    Parameters
    ----------
    scene : pathlib.Path
        Scene folder (scene.data, scene.lmp), relative to the root or absolute.
    log : pathlib.Path
        Where LAMMPS writes its log.
    nprocs : int
        MPI ranks; 1 runs lmp without mpirun.

    Returns
    -------
    pathlib.Path
        ``log``.
    """
    out = scene / f"out.{nprocs}"  # series.dat, energy.dat
    (ROOT / out).mkdir(parents=True, exist_ok=True)
    args = ["-in", "decks/impact.lmp", "-log", str(log), "-screen", "none", "-nocite"]
    args += ["-var", "scene", str(scene), "-var", "out", str(out)]
    args += ["-var", "thermo_every", str(THERMO_EVERY)]
    subprocess.run(
        mpi_launcher(nprocs) + ["lmp"] + args,
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
        env=mpi_environment(),
    )
    return log


def thermo_rows(log: Path) -> np.ndarray:
    """Every thermo row of a LAMMPS log, in order, as one array.

    Parameters
    ----------
    log : pathlib.Path
        A LAMMPS log file.

    Returns
    -------
    numpy.ndarray
        One row per thermo line (all runs of the log, headers left out), one
        column per thermo keyword that every table of the log has (the deck
        switches to fewer columns during its run; the first five, step,
        time, ke, pe and the contact's energy, are in all).
    """
    rows, inside = [], False
    for line in log.read_text().splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            inside = True
        elif inside and words:
            try:
                rows.append([float(w) for w in words])
            except ValueError:  # "Loop time of ...": the run's table ended
                inside = False
    width = min((len(row) for row in rows), default=0)
    return np.array([row[:width] for row in rows])


def committed_log(nprocs: int) -> Path:
    """The committed reference log for ``nprocs`` ranks (there must be one).

    Parameters
    ----------
    nprocs : int
        1 or 2.

    Returns
    -------
    pathlib.Path
        ``decks/log.<date>.impact.g++.<nprocs>``.
    """
    logs = sorted(DECKS.glob(f"log.*.{NAME}.g++.{nprocs}"))
    if len(logs) != 1:
        raise FileNotFoundError(
            f"expected one decks/log.*.{NAME}.g++.{nprocs}, found "
            f"{len(logs)}: run make reference-logs"
        )
    return logs[0]


def main(argv: list[str] | None = None) -> None:
    """Write decks/log.<today>.impact.g++.1 and .2, removing older ones."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.parse_args(argv)
    stamp = date.today().strftime("%d%b%y").lstrip("0")  # LAMMPS's style: 23Nov26
    build_scene()
    for nprocs in (1, 2):
        for old in DECKS.glob(f"log.*.{NAME}.g++.{nprocs}"):
            old.unlink()
        log = DECKS / f"log.{stamp}.{NAME}.g++.{nprocs}"
        run_impact(SCENE, log.relative_to(ROOT), nprocs)
        print(f"{log.relative_to(ROOT)}: {len(thermo_rows(log))} thermo rows")


if __name__ == "__main__":
    main()
