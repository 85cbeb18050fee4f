"""Times follow the radius (issue 44): dt "auto" is the scene's step times
R, so a disk of radius R is the unit disk's impact on R's scale of length
and time, and its e and beta are the unit disk's; before, dt and tmax stayed
the unit disk's, and every radius but 1 failed (unstable at 0.1, on the wall
at tmax at 10)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.helpers import ROOT


def impact(radius: float, tmp_path) -> dict:
    done = subprocess.run(
        [sys.executable, "-m", "runner", "impact", "--n-disk", "200", "--radius", str(radius),
         "--out", str(tmp_path / f"r{radius}")],
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    header, row = done.stdout.strip().splitlines()[-2:]
    return dict(zip(header.split(), row.split(), strict=True))


@pytest.mark.parametrize("radius", [0.2, 3.0])
def test_e_and_beta_do_not_depend_on_the_radius(radius, tmp_path):
    unit, scaled = impact(1.0, tmp_path), impact(radius, tmp_path)
    assert float(scaled["e"]) == pytest.approx(float(unit["e"]), abs=2e-4)
    assert float(scaled["beta"]) == pytest.approx(float(unit["beta"]), abs=2e-4)
    # the contact lasts R times as long (read off series.dat's rows, 0.08
    # apart whatever R: 4 % of the 0.2 disk's contact)
    assert float(scaled["contact_time"]) == pytest.approx(
        radius * float(unit["contact_time"]), rel=0.05
    )
