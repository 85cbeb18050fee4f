"""rRESPA with the contact alone on its inner level (integrator respa).

Its levels must hold every force once: the contact on the inner one (a
sub-style of pair_style hybrid), the springs on the outer one. In a state of
an impact where the contact presses hardest, the sum of the levels, on one
rank and on two, must be Verlet's force on every atom of both bodies.

Tolerance: 1e-12 of the largest force. The same terms are summed in another
order (per level, then the levels; on two ranks, ghosts' shares in another
order), so the forces differ by rounding: measured 8e-17 on one rank and on
two. The contact's own forces reach 1.3 times that scale here, so a level
that drops or repeats them shows at once.
"""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

from analysis.impact.series import read_series
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.launch import command_line, mpi_environment, mpi_launcher
from runner.impact import run_scene
from runner.options import RESPA_NRESPA, RunOptions
from tests.helpers import PAPER, ROOT

pytestmark = [pytest.mark.lammps, pytest.mark.mpi]

DECK = ROOT / "tests" / "decks" / "impact_forces.lmp"
TOLERANCE = 1e-12


@pytest.fixture(scope="module")
def pressed(tmp_path_factory):
    """The paper's scene at 45 degrees, run with Verlet and a dump at every row
    of the series: its folder and the dumped step of the largest contact energy."""
    folder = write_scene(
        build_scene(SceneSpec(gamma_deg=45.0, **PAPER)), tmp_path_factory.mktemp("pressed")
    )
    run_scene(folder, RunOptions(dump_every=RunOptions().every_steps))
    series = read_series(folder / "series.dat")
    return folder, int(series["step"][np.argmax(series["pe_contact"])])


def forces(folder, frame: int, name: str, nprocs: int = 1, **variables: str) -> np.ndarray:
    """fx, fy of every atom, by id, after tests/decks/impact_forces.lmp."""
    out = folder / f"forces.{name}"
    settings = {"scene": str(folder), "frame": str(frame), "out": str(out), **variables}
    subprocess.run(
        mpi_launcher(nprocs) + ["lmp", *command_line(settings, folder / f"log.{name}", DECK)],
        cwd=ROOT,
        check=True,
        capture_output=True,
        env=mpi_environment(),
    )
    table = np.loadtxt(out, skiprows=9)
    return table[np.argsort(table[:, 0]), 1:]


def test_respa_levels_sum_to_verlets_forces_on_one_and_two_ranks(pressed):
    folder, frame = pressed
    verlet = forces(folder, frame, "verlet")
    springs = forces(folder, frame, "springs", contact="none")
    scale = np.abs(verlet).max()
    # the contact acts, strongly, in this state
    assert np.abs(verlet - springs).max() > 0.1 * scale
    respa = {"integrator": "respa", "nrespa": str(RESPA_NRESPA)}
    for nprocs in (1, 2):
        # against Verlet on as many ranks: on two, the balanced split decides
        # which rank sums which forces, and so their last bits (potentials/README.md)
        same = verlet if nprocs == 1 else forces(folder, frame, "verlet.2", 2)
        ours = forces(folder, frame, f"respa.{nprocs}", nprocs, **respa)
        assert ours.shape == verlet.shape
        assert np.abs(ours - same).max() <= TOLERANCE * scale, f"{nprocs} ranks"
