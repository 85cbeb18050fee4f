"""Bond style harmonic/quartic (potentials/bond_harmonic_quartic.cpp): the
model's spring, checked against class2 with the same springs, against the
formula, on one and two ranks, through write_data / read_data, and its
refusal of bad coefficients."""

from __future__ import annotations

import ctypes
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import SceneSpec
from ground.launch import mpi_environment, mpi_launcher
from tests.helpers import PAPER, ROOT, new_lammps

pytestmark = pytest.mark.lammps

DECK = ROOT / "tests" / "decks" / "spring_forces.lmp"
LIBRARY = ROOT / "build" / "libharmonic_quartic.so"


@pytest.fixture(scope="module")
def scenes(tmp_path_factory) -> dict[str, Path]:
    """The paper's scene (800-point wall), written for both bond styles."""
    scene = build_scene(SceneSpec(gamma_deg=30.0, n_wall=800, **PAPER))
    root = tmp_path_factory.mktemp("springs")
    return {
        springs: write_scene(scene, root / springs.replace("/", "_"), springs)
        for springs in ("class2", "harmonic/quartic")
    }


def spring_state(
    tmp: Path,
    scene: Path,
    springs: str,
    nprocs: int = 1,
    newton: str = "on",
    amp: float = 0.01,
    command: list[str] | None = None,
    env: dict | None = None,
    extra: tuple[str, ...] = (),
) -> tuple[np.ndarray, np.ndarray]:
    """(energy and virial xx yy xy), per atom (fx fy fz pe) by ID, at a displaced state."""
    out = tmp / f"{springs.replace('/', '_')}_{nprocs}_{newton}_{len(list(tmp.iterdir()))}.dump"
    log = out.with_suffix(".log")
    args = [
        "-in",
        str(DECK),
        "-log",
        str(log),
        "-screen",
        "none",
        "-nocite",
        "-var",
        "scene",
        str(scene),
        "-var",
        "springs",
        springs,
        "-var",
        "out",
        str(out),
        "-var",
        "newton",
        newton,
        "-var",
        "amp",
        repr(amp),
        *extra,
    ]
    proc = subprocess.run(
        mpi_launcher(nprocs) + (command or ["lmp"]) + args,
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**mpi_environment(), **(env or {})},
    )
    if proc.returncode != 0:
        errors = (
            [line for line in log.read_text().splitlines() if line.startswith("ERROR")]
            if log.exists()
            else []
        )
        raise RuntimeError(errors[0] if errors else proc.stdout[-2000:] + proc.stderr[-2000:])
    atoms = np.loadtxt(out, skiprows=9)
    return np.array(Path(f"{out}.global").read_text().split(), float), atoms[:, 1:]


def relative(ours: np.ndarray, theirs: np.ndarray) -> float:
    return float(np.abs(ours - theirs).max() / np.abs(theirs).max())


def test_forces_energies_and_virial_equal_class2(tmp_path, scenes):
    # the quartic term is 1e-7 of the force at these strains: far above 1e-12
    for newton in ("on", "off"):
        quartic = spring_state(
            tmp_path, scenes["harmonic/quartic"], "harmonic/quartic", newton=newton
        )
        class2 = spring_state(tmp_path, scenes["class2"], "class2", newton=newton)
        assert np.abs(class2[1][:, :2]).max() > 1.0  # the springs are stretched
        assert relative(quartic[1][:, :2], class2[1][:, :2]) < 1e-12
        assert np.all(quartic[1][:, 2] == 0.0)  # 2-D: no z force
        assert relative(quartic[1][:, 3], class2[1][:, 3]) < 1e-12
        assert np.allclose(quartic[0], class2[0], rtol=1e-12, atol=0.0)


@pytest.mark.mpi
def test_two_ranks_give_the_forces_of_one(tmp_path, scenes):
    """Two ranks cut the scene in two: bonds across the cut, ghost atoms, and
    with newton off bonds computed on both sides."""
    scene = scenes["harmonic/quartic"]
    one = spring_state(tmp_path, scene, "harmonic/quartic")
    for newton in ("on", "off"):
        two = spring_state(tmp_path, scene, "harmonic/quartic", nprocs=2, newton=newton)
        assert relative(two[1][:, :2], one[1][:, :2]) < 1e-12
        assert relative(two[1][:, 3], one[1][:, 3]) < 1e-12
        assert np.allclose(two[0], one[0], rtol=1e-12, atol=0.0)


@pytest.mark.mpi
@pytest.mark.parametrize("nprocs", [1, 2])
def test_packed_bond_list_gives_the_plain_loop_bit_for_bit(tmp_path, scenes, nprocs):
    """The loop over the packed copy of the bond list (the default) sums the
    same numbers in the same order as the loop over LAMMPS's list and each
    bond's type (packed no): after steps over which the lists were rebuilt,
    and atoms moved between ranks, positions, forces and energies agree to
    the last bit. The scene's springs have two distinct stiffnesses (disk and
    wall), so a bond given the wrong row would show."""
    scene = scenes["harmonic/quartic"]
    states = {}
    for packed in ("yes", "no"):
        extra = ("-var", "steps", "200", "-var", "springs_args", f"packed {packed}")
        states[packed] = spring_state(
            tmp_path, scene, "harmonic/quartic", nprocs=nprocs, extra=extra
        )
    logs = sorted(tmp_path.glob("*.log"))
    builds = [
        max(int(m) for m in re.findall(r"Neighbor list builds = (\d+)", log.read_text()))
        for log in logs
    ]
    assert len(builds) == 2 and min(builds) > 5  # the packed list was remade
    assert np.abs(states["yes"][1][:, :2]).max() > 1.0
    assert np.array_equal(states["yes"][1], states["no"][1])
    assert np.array_equal(states["yes"][0], states["no"][0])


def test_write_data_read_data_round_trip(tmp_path, scenes):
    """write_data keeps the coefficients to the last bit, and the file read
    back gives the same forces."""
    written = tmp_path / "written.data"
    first = spring_state(
        tmp_path,
        scenes["harmonic/quartic"],
        "harmonic/quartic",
        extra=("-var", "write_data", "yes", "-var", "data_out", str(written)),
    )
    text = written.read_text()
    assert "Bond Coeffs # harmonic/quartic" in text
    again = tmp_path / "again"
    again.mkdir()
    shutil.copy(scenes["harmonic/quartic"] / "scene.lmp", again)
    shutil.copy(written, again / "scene.data")
    second = spring_state(tmp_path, again, "harmonic/quartic", amp=0.0)
    assert np.array_equal(second[1], first[1])

    def coeffs(data: str) -> np.ndarray:
        block = data.split("Bond Coeffs")[1].split("\n\n")[1]
        return np.array([line.split() for line in block.splitlines()], float)

    built = coeffs((scenes["harmonic/quartic"] / "scene.data").read_text())
    assert built.shape[1] == 4 and np.array_equal(coeffs(text), built)


def two_atoms(r: float, coeff: str, dimension: int = 2):
    """Two atoms at distance r along a direction off every axis, one bond."""
    lmp = new_lammps()
    ctypes.CDLL(str(LIBRARY)).harmonic_quartic_register(lmp.lmp)
    u = np.array([0.6, 0.8, 0.0]) if dimension == 2 else np.array([0.48, 0.64, 0.6])
    for command in [
        f"dimension {dimension}",
        "units lj",
        "atom_style bond",
        f"boundary f f {'p' if dimension == 2 else 'f'}",
        f"region box block -10 10 -10 10 {'-1 1' if dimension == 2 else '-10 10'}",
        "create_box 1 box bond/types 1 extra/bond/per/atom 1",
        "mass 1 1.0",
        "create_atoms 1 single 0 0 0",
        "create_atoms 1 single {} {} {}".format(*(r * u)),
        "bond_style harmonic/quartic",
        coeff,
        "create_bonds single/bond 1 1 2",
        "pair_style zero 1.0",
        "pair_coeff * *",
        "compute e all pe bond",
        "thermo_style custom step c_e",
        "run 0",
    ]:
        lmp.command(command)
    return lmp, u


@pytest.mark.parametrize("dimension", [2, 3])
def test_energy_and_force_of_one_spring_are_the_formula(dimension):
    """Far from rest, where the quartic term dominates: E = ka x^2/2 + kb x^4/4
    and F = -(ka x + kb x^3) along the bond, in 2-D and in 3-D."""
    r0, ka, kb, r = 1.5, 2.0, 0.5, 4.0
    lmp, u = two_atoms(r, f"bond_coeff 1 {r0} {ka} {kb}", dimension)
    x = r - r0
    assert lmp.extract_compute("e", 0, 0) == pytest.approx(ka * x**2 / 2 + kb * x**4 / 4, rel=1e-14)
    f = np.ctypeslib.as_array(lmp.gather_atoms("f", 1, 3)).reshape(2, 3)
    assert np.allclose(f[1], -(ka * x + kb * x**3) * u, rtol=1e-14, atol=1e-14)
    assert np.allclose(f[0], -f[1], rtol=1e-14, atol=0.0)
    lmp.close()


@pytest.mark.parametrize(
    "coeff, message",
    [
        ("bond_coeff 1 1.0 2.0", r"expects N r0 ka kb, got 3 values"),
        ("bond_coeff 1 1.0 2.0 0.1 7", r"expects N r0 ka kb, got 5 values"),
        ("bond_coeff 1 1.0 -2.0 0.1", r"ka must be >= 0, got -2"),
        ("bond_coeff 1 1.0 2.0 -0.1", r"kb must be >= 0, got -0.1"),
        ("bond_coeff 1 -1.0 2.0 0.1", r"r0 must be >= 0, got -1"),
        ("bond_coeff 1 1.0 two 0.1", r"[Ee]xpected floating point"),
    ],
)
def test_bad_coefficients_are_refused(tmp_path, coeff, message):
    """A one-line error naming the coefficient (errors end the process: lmp, not the module)."""
    deck = tmp_path / "in.lmp"
    deck.write_text(
        "\n".join(
            [
                "variable springs_lib index " + str(LIBRARY),
                "include decks/harmonic_quartic.lmp",
                "units lj",
                "atom_style bond",
                "region box block -1 1 -1 1 -1 1",
                "create_box 1 box bond/types 1 extra/bond/per/atom 1",
                "bond_style harmonic/quartic",
                coeff,
                "",
            ]
        )
    )
    proc = subprocess.run(
        ["lmp", "-in", str(deck), "-log", "none", "-nocite"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=mpi_environment(),
    )
    errors = [line for line in proc.stdout.splitlines() if line.startswith("ERROR")]
    assert proc.returncode != 0 and len(errors) == 1
    assert re.search(message, errors[0]), errors[0]
