"""An impact whose step is too long for the area barrier runs again at half
the step (runner.impact.run_scene, --barrier-halvings), with LAMMPS itself."""

from __future__ import annotations

import filecmp
import json

import pytest

from builder.scene import SceneSpec
from ground.launch import LammpsError
from runner.impact import BARRIER_CROSSED, run_impact
from runner.options import RunOptions

pytestmark = pytest.mark.lammps

# The paper's slope as one surface (L = 0.06 R) with the barrier, sliding at
# 80.5 degrees: at 1.5 times the 800-point disk's step a surface triangle
# turns over between two steps (at step 526); at the default step it does not.
CROSSING = SceneSpec(
    n_disk=800,
    gamma_deg=80.5,
    seed=1,
    roughness_length=0.06,
    roughness_profile="continuous",
    contact_scaling="physical",
    area_floor=0.5,
)
LONG_STEP = 0.012


def test_a_step_too_long_for_the_barrier_stops_with_halvings_0(tmp_path):
    with pytest.raises(LammpsError, match=BARRIER_CROSSED):
        run_impact(CROSSING, tmp_path / "run", RunOptions(dt=LONG_STEP, barrier_halvings=0))
    assert not (tmp_path / "run" / "result.json").exists()


def test_the_impact_runs_again_at_half_the_step(tmp_path):
    """The retry is the impact at dt / 2, every output the same to the last
    bit as a run given dt / 2 from the start, and run.json says so."""
    halved = run_impact(CROSSING, tmp_path / "halved", RunOptions(dt=LONG_STEP))
    direct = run_impact(
        CROSSING, tmp_path / "direct", RunOptions(dt=LONG_STEP / 2, barrier_halvings=0)
    )
    record = json.loads((tmp_path / "halved" / "run.json").read_text())
    assert record["dt_halvings"] == 1 and record["options"]["dt"] == LONG_STEP / 2
    assert json.loads((tmp_path / "direct" / "run.json").read_text())["dt_halvings"] == 0
    for name in ("series.dat", "energy.dat"):
        assert filecmp.cmp(tmp_path / "halved" / name, tmp_path / "direct" / name, shallow=False)
    assert halved["e"] == direct["e"] and halved["beta"] == direct["beta"]
    assert 0.5 < halved["e"] < 1.0
