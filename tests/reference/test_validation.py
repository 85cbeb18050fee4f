"""LAMMPS at its default settings against the reference (make validate, small).

Ten scenes: random, triangular and square lattices at a near-normal (5.7), a
middle (45) and a grazing (80.4 degree) angle on the wall, and two random
disks colliding at 45 degrees, with 200-point disks for speed.
Smooth surfaces, where e and beta of one impact converge: LAMMPS's defaults
against the reference's converged fourth-order run, within 1e-3. Rough
surfaces, where they do not (chaos, docs/validation.md): LAMMPS against the
reference's velocity Verlet at the same step, the same algorithm on
independently written forces. rRESPA's split (the contact alone on the
inner level, runner.options.RESPA_DT and RESPA_NRESPA) against the same
converged reference, to the same 1e-3.
"""

from __future__ import annotations

import pytest

from bench.validation import compare
from reference.run import ReferenceOptions
from reference.validate import reference_runs, scenes
from runner.options import DEFAULT_DT, RESPA_DT, RESPA_NRESPA, RunOptions

pytestmark = [pytest.mark.lammps, pytest.mark.slow]

DEFAULTS = RunOptions(dt=DEFAULT_DT)  # the validation scenes have 800 points
RESPA = RunOptions(integrator="respa", dt=RESPA_DT, nrespa=RESPA_NRESPA)


@pytest.fixture(scope="module")
def smooth_references(tmp_path_factory):
    out = tmp_path_factory.mktemp("smooth")
    specs = scenes(n_disk=200, roughness=0.0)
    return out, specs, reference_runs(specs, out)


def compare_smooth(smooth_references, options: RunOptions, label: str) -> dict[str, dict]:
    out, specs, references = smooth_references
    return {
        name: compare(spec, out / name / label, options, references[name], out / name / "reference")
        for name, spec in specs.items()
    }


@pytest.fixture(scope="module")
def smooth(smooth_references):
    return compare_smooth(smooth_references, DEFAULTS, "lammps")


@pytest.fixture(scope="module")
def smooth_respa(smooth_references):
    return compare_smooth(smooth_references, RESPA, "lammps_respa")


@pytest.fixture(scope="module")
def rough(tmp_path_factory):
    out = tmp_path_factory.mktemp("rough")
    specs = scenes(n_disk=200)
    same_step = ReferenceOptions(integrator="verlet", dt=DEFAULTS.dt)
    twins = reference_runs(specs, out, options=same_step, label="reference_verlet")
    return {
        name: compare(
            spec, out / name / "lammps", DEFAULTS, twins[name], out / name / "reference_verlet"
        )
        for name, spec in specs.items()
    }


@pytest.mark.parametrize("name", list(scenes(n_disk=200)))
def test_default_settings_agree_with_the_converged_reference(smooth, name):
    assert abs(smooth[name]["de"]) < 1e-3
    assert abs(smooth[name]["dbeta"]) < 1e-3


@pytest.mark.parametrize("name", list(scenes(n_disk=200)))
def test_respa_agrees_with_the_converged_reference(smooth_respa, name):
    assert abs(smooth_respa[name]["de"]) < 1e-3
    assert abs(smooth_respa[name]["dbeta"]) < 1e-3


@pytest.mark.parametrize("name", list(scenes(n_disk=200)))
def test_lammps_and_reference_verlet_agree_on_rough_scenes(rough, name):
    assert abs(rough[name]["de"]) < 1e-6
    assert abs(rough[name]["dbeta"]) < 1e-6
    assert rough[name]["velocity"] < 1e-6
