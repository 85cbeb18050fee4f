"""The tilted frame of analysis/impact/tilt.py: what the letter's mechanism predicts."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.impact.restitution import rebound
from analysis.impact.tilt import tilted_e


@pytest.mark.parametrize("gamma_deg, theta_deg", [(60.0, 2.0), (75.0, 1.0), (80.0, 4.8)])
def test_an_elastic_bounce_off_a_tilted_surface_has_e_above_one(gamma_deg, theta_deg):
    """A disk reflected elastically by a surface rising ahead of it by theta:
    e against that surface's normal is 1, against the wall's it is above 1 by
    about (1 + e) tan(gamma) tan(theta), the share of the approach the tilt
    adds from the tangential motion."""
    theta = np.radians(theta_deg)
    v_in = np.array([np.tan(np.radians(gamma_deg)), -1.0]) * 0.01
    normal = np.array([-np.sin(theta), np.cos(theta)])
    v_out = v_in - 2 * (v_in @ normal) * normal
    result = dict(vx_in=v_in[0], vy_in=v_in[1], vx_out=v_out[0], vy_out=v_out[1])
    assert tilted_e(result, theta) == pytest.approx(1.0, abs=1e-12)
    e_wall = rebound(v_in, v_out, 0.0, 0.0, 1.0).e
    share = np.tan(np.radians(gamma_deg)) * np.tan(theta)
    assert e_wall > 1.0
    assert e_wall - 1.0 == pytest.approx(2 * share, rel=0.1)
    assert tilted_e(result, 0.0) == pytest.approx(e_wall, rel=1e-12)  # untilted: the wall's


def test_runner_tilt_refuses_an_angle_the_study_has_not(tmp_path):
    """python -m runner tilt --gamma G: G must be one of the tables' angles;
    one line naming the option and the angles, exit 2, nothing written."""
    import subprocess
    import sys

    from tests.helpers import ROOT

    out = tmp_path / "tilt"
    proc = subprocess.run(
        [sys.executable, "-m", "runner", "tilt", "--gamma", "33", "--out", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert "--gamma must be one of the study's angles (30 45 55" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and not out.exists()
