"""LAMMPS data files (atom_style bond, 2-D), written and read, and the scene's
settings for the deck.

Every spring gets its own bond type, so that each keeps its own natural
length. Numbers are written in Python's shortest round-trip form, so LAMMPS
reads back exactly the doubles the builder computed: every spring starts at
exactly its natural length.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ground.gate import make_folder, write_text
from ground.paths import BUILD

from .contact_table import ensure_table, table_name
from .scene import DISK, Scene
from .triangles import ANGLE_STYLE

# Decks run from the project's root and find the contact tables here: derived
# files, made when first needed, so under build/ and not in the source tree.
TABLES = BUILD / "tables"

SPRING_STYLES = ("harmonic/quartic", "class2", "harmonic")
# The project's own bond style (potentials/bond_harmonic_quartic.cpp): the same
# springs as class2 at a third of the cost (docs/benchmarks/spring_cost.md).
DEFAULT_SPRINGS = "harmonic/quartic"


def _rows(*columns: np.ndarray) -> str:
    """Lines of space-separated values; floats in shortest round-trip form."""
    lists = [c.tolist() for c in columns]
    return "".join(" ".join(map(repr, row)) + "\n" for row in zip(*lists))


def bond_coeff_columns(
    r0: np.ndarray, ka: np.ndarray, kb_over_ka: float, springs: str
) -> list[np.ndarray]:
    """Bond coefficients per spring, for the bond style ``springs``.

    harmonic/quartic (potentials/bond_harmonic_quartic.cpp): r0 ka kb, the
    model's V(x) = ka x^2 / 2 + kb x^4 / 4 itself. class2: E = K2 x^2 + K3 x^3
    + K4 x^4, so K2 = ka/2, K3 = 0, K4 = kb/4 gives the same V (the halving and
    quartering are exact in binary). harmonic: E = K x^2, K = ka/2 (no quartic).
    """
    if springs == "harmonic/quartic":
        return [r0, ka, kb_over_ka * ka]
    if springs == "class2":
        return [r0, ka / 2.0, np.zeros_like(r0), kb_over_ka * ka / 4.0]
    if springs == "harmonic":
        return [ka / 2.0, r0]
    raise ValueError(f"springs must be one of {', '.join(SPRING_STYLES)}; got {springs!r}")


def network_data_text(
    title: str,
    positions: np.ndarray,
    velocities: np.ndarray,
    types: np.ndarray,
    type_names: dict[int, str],
    molecule: np.ndarray,
    pairs: np.ndarray,
    ka: np.ndarray,
    kb_over_ka: float,
    springs: str,
    pad: float,
    angles=None,
) -> str:
    """A 2-D data file of point masses 1 and springs, one bond type per spring;
    with ``angles`` (builder.triangles.Triangles) the barrier's triangles too."""
    n, m = len(positions), len(pairs)
    lo = (positions.min(axis=0) - pad).tolist()
    hi = (positions.max(axis=0) + pad).tolist()
    d = positions[pairs[:, 0]] - positions[pairs[:, 1]]
    r0 = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
    ids = np.arange(1, n + 1)
    zeros = np.zeros(n)
    bond_ids = np.arange(1, m + 1)
    parts = [
        f"LAMMPS data file, {title}\n\n",
        f"{n} atoms\n{m} bonds\n{len(type_names)} atom types\n{m} bond types\n\n",
        f"{lo[0]!r} {hi[0]!r} xlo xhi\n{lo[1]!r} {hi[1]!r} ylo yhi\n-0.5 0.5 zlo zhi\n\n",
        "Masses\n\n",
        "".join(f"{t} 1.0  # {name}\n" for t, name in type_names.items()),
        f"\nBond Coeffs # {springs}\n\n",
        _rows(bond_ids, *bond_coeff_columns(r0, ka, kb_over_ka, springs)),
        "\nAtoms # bond\n\n",
        _rows(ids, molecule, types, positions[:, 0], positions[:, 1], zeros),
        "\nVelocities\n\n",
        _rows(ids, velocities[:, 0], velocities[:, 1], zeros),
        "\nBonds\n\n",
        _rows(bond_ids, bond_ids, pairs[:, 0] + 1, pairs[:, 1] + 1),
    ]
    if angles is not None:
        counts = f"{len(angles.atoms)} angles\n{len(angles.coefficients)} angle types\n"
        parts[1] = parts[1][:-1] + counts + "\n"
        ids = np.arange(1, len(angles.atoms) + 1)
        types = np.arange(1, len(angles.coefficients) + 1)
        parts += [
            f"\nAngle Coeffs # {ANGLE_STYLE}\n\n",
            _rows(types, *angles.coefficients.T),
            "\nAngles\n\n",
            _rows(ids, angles.types, *(angles.atoms + 1).T),
        ]
    return "".join(parts)


def data_file_text(scene: Scene, springs: str = DEFAULT_SPRINGS, placed: bool = True) -> str:
    """The scene's data file: the disk placed and moving (``placed``), or the
    bodies in their own frames and at rest, which every angle and speed of
    one sample shares (the deck places the disk: ``settings_text``)."""
    spec = scene.spec
    if placed:
        title = (
            f"impact scene: lattice={spec.lattice} seed={spec.seed} "
            f"gamma_deg={spec.gamma_deg!r} vn={spec.vn!r} springs={springs}"
        )
        positions, velocities = scene.positions, scene.velocities
    else:
        title = f"impact bodies: lattice={spec.lattice} seed={spec.seed} springs={springs}"
        positions, velocities = scene.frame_positions, np.zeros_like(scene.velocities)
    return network_data_text(
        title,
        positions,
        velocities,
        scene.types,
        {int(k): v for k, v in scene.info["atom_types"].items()},
        scene.molecule,
        scene.springs,
        scene.ka,
        spec.kb_over_ka,
        springs,
        pad=2.0 * scene.info["disk_spacing"],
        angles=scene.angles,
    )


def settings_text(
    scene: Scene, springs: str = DEFAULT_SPRINGS, bodies: Path | None = None, restart: bool = False
) -> str:
    """A LAMMPS include file with the scene's settings, as index variables.

    With ``bodies`` (a data file of the sample's bodies in their own frames,
    ``data_file_text(placed=False)``) the deck reads that file and moves the
    disk by the placement; without, it reads the folder's placed scene.data.
    Either way the disk ends up at the same doubles (``placement_quantum``).
    ``restart``: ``bodies`` is a binary restart of that data file (the deck's
    data_format, decks/read_bodies.lmp)."""
    info = scene.info
    shift = scene.disk_centre if bodies is not None else np.zeros(2)
    velocity = scene.velocities[scene.molecule == DISK][0]
    table = f"build/tables/{table_name(info['contact']['a'], info['contact']['V0'])}"
    # The contact's neighbour list is rebuilt whenever a point has moved half
    # the skin, and the disk moves at 0.1 to 0.8 c: with two spacings the
    # lists are rebuilt about a fifth as often as with half of one, for a
    # longer list the contact loops over (docs/benchmarks/loop_floor.md).
    skin = 2.0 * float(info["wall_spacing"])
    cutoff = info["contact"]["cutoff"]
    # Longest segment of the wall's surface, with room for stretching (segments
    # under the disk were seen stretched by 25 percent).
    reach = 2.0 * info["wall_longest_segment"]
    # Ghost atoms must reach across the longest spring, for bonds split between
    # ranks (1.5 times the longest natural length is LAMMPS's own estimate),
    # and from a disk point to both ends of every wall segment it may touch;
    # two disks' rings, to the vertices RING_CHORD away along the other ring
    # (the pair style's outward direction: potentials/pair_polyline_exp.cpp).
    segments = RING_CHORD if info.get("target") == "disk" else 2.0
    bonds = float(info["max_natural_length"] * 1.5 + skin)
    comm = float(max(info["max_natural_length"] * 1.5, cutoff + segments * reach) + skin)
    return (
        "# Scene settings written by the builder; -var on the command line overrides them.\n"
        f"variable cutoff      index {cutoff!r}\n"
        f"variable wall_reach  index {reach!r}\n"
        f"variable contact_a   index {info['contact']['a']!r}\n"
        f"variable contact_V0  index {info['contact']['V0']!r}\n"
        f"variable skin        index {skin!r}\n"
        f"variable comm_cutoff index {comm!r}\n"
        # the ghosts of the bodies' interiors, which only springs reach (decks/setup.lmp)
        f"variable bond_cutoff index {bonds!r}\n"
        f"variable wall_first  index {info['wall_row_tags'][0]}\n"
        f"variable wall_last   index {info['wall_row_tags'][1]}\n"
        f"variable table       index {table}\n"
        f"variable springs     index {springs}\n"
        + (f"variable angles      index {ANGLE_STYLE}\n" if scene.angles is not None else "")
        + (f"variable data        index {bodies}\n" if bodies is not None else "")
        + ("variable data_format index restart\n" if restart else "")
        + f"variable disk_dx     index {float(shift[0])!r}\n"
        f"variable disk_dy     index {float(shift[1])!r}\n"
        f"variable disk_vx     index {float(velocity[0])!r}\n"
        f"variable disk_vy     index {float(velocity[1])!r}\n"
        + (binary_settings(scene) if info.get("target") == "disk" else "")
    )


# pair_style polyline/exp's CHORD: a ring's outward direction at a vertex is
# the chord between the vertices this many before and after it.
RING_CHORD = 4


def binary_settings(scene: Scene) -> str:
    """What a binary scene adds to scene.lmp: the decks' branch, the
    target's velocity, and the contact's two rings (pair_style polyline/exp's
    partner: the target's ring is wall_first..wall_last)."""
    velocity = scene.velocities[scene.molecule != DISK][0]
    first, last = scene.info["partner_row_tags"]
    return (
        "variable target      index disk\n"
        f"variable target_vx   index {float(velocity[0])!r}\n"
        f"variable target_vy   index {float(velocity[1])!r}\n"
        f'variable contact_keywords index "closed yes partner {first} {last}"\n'
    )


def write_bodies(scene: Scene, path: Path | str, springs: str = DEFAULT_SPRINGS) -> Path:
    """Write the data file of a sample's bodies in their own frames, which all
    its angles and speeds share (``write_scene(bodies=path)``), atomically:
    two workers may write the same sample's at once.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    make_folder(path.parent)
    partial = path.with_name(f".{path.name}.{os.getpid()}")
    write_text(partial, data_file_text(scene, springs, placed=False))
    partial.replace(path)
    return path


def write_scene(
    scene: Scene,
    folder: Path | str,
    springs: str = DEFAULT_SPRINGS,
    bodies: Path | None = None,
    restart: bool = False,
) -> Path:
    """Write scene.data, scene.lmp and scene.json into ``folder``.

    Also writes the contact's table into build/tables/ if it is missing (the pair
    variant of the contact reads it). With ``bodies``, the sample's data file
    (``write_bodies``) or, with ``restart``, its binary restart, scene.lmp
    points the deck to it and places the disk, and no scene.data is written.

    Parameters
    ----------
    scene : Scene
        A built scene (``builder.assembly.build_scene``).
    folder : pathlib.Path or str
        The run folder; created if missing.
    springs : str
        Bond style of the data file: ``harmonic/quartic`` (the model's
        springs, the default), ``class2`` (the same springs) or ``harmonic``.

    Returns
    -------
    pathlib.Path
        ``folder``.
    """
    folder = make_folder(folder)  # ground.gate: the one gate of every write
    info = dict(scene.info, springs=springs)
    ensure_table(TABLES, info["contact"]["a"], info["contact"]["V0"], scene.spec.radius)
    if bodies is None:
        write_text(folder / "scene.data", data_file_text(scene, springs))
    write_text(folder / "scene.lmp", settings_text(scene, springs, bodies, restart))
    write_text(folder / "scene.json", json.dumps(info, indent=1, sort_keys=True) + "\n")
    return folder


# Reading: what LAMMPS would read from a data file of this project, as arrays
# (the reference implementation integrates them; calibration counts atoms).


@dataclass
class System:
    """Everything the dynamics needs, indexed by atom ID - 1."""

    x: np.ndarray  # (n, 2) positions
    v: np.ndarray  # (n, 2) velocities
    mass: np.ndarray  # (n,)
    types: np.ndarray  # (n,)
    molecule: np.ndarray  # (n,)
    bonds: np.ndarray  # (m, 2) atom indices
    r0: np.ndarray  # (m,) natural lengths
    k2: np.ndarray  # (m,) class2 coefficients: E = k2 dr^2 + k3 dr^3 + k4 dr^4
    k3: np.ndarray
    k4: np.ndarray
    # the barrier's triangles (angle style area/barrier, --area-floor), as the
    # Angles section lists their atoms, and each one's A0, k, J_c from its
    # type's Angle Coeffs; none without the barrier
    angles: np.ndarray = field(default_factory=lambda: np.zeros((0, 3), int))  # (t, 3)
    a0: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (t,)
    k_area: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (t,)
    jc: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (t,)


# a data file's sections; the barrier's angles with --area-floor
SECTIONS = ("Masses", "Bond Coeffs", "Atoms", "Velocities", "Bonds", "Angle Coeffs", "Angles")


def _sections(text: str) -> dict[str, list[str]]:
    sections, name = {"header": []}, "header"
    for line in text.splitlines():
        stripped = line.split("#")[0].strip()
        if not stripped:
            continue
        if stripped in SECTIONS:
            name = stripped
            sections[name] = []
        else:
            sections[name].append(stripped)
    return sections


def _angles(sections: dict[str, list[str]], path: Path | str) -> dict[str, np.ndarray]:
    """The barrier's triangles of a data file's Angles and Angle Coeffs
    (area/barrier: A0 k J_c per type), as System's fields; none if it has no
    Angles section."""
    if "Angles" not in sections:
        return {}
    if "Angle Coeffs" not in sections:
        raise ValueError(f"{path}: Angles but no Angle Coeffs section")
    coeffs = np.array([r.split() for r in sections["Angle Coeffs"]], float)
    if coeffs.ndim != 2 or coeffs.shape[1] != 4:
        raise ValueError(f"{path}: Angle Coeffs must be 'type A0 k Jc' ({ANGLE_STYLE})")
    rows = np.array([r.split() for r in sections["Angles"]], int).reshape(-1, 5)
    rows = rows[np.argsort(rows[:, 0])]
    by_type = np.full((max(int(coeffs[:, 0].max()), int(rows[:, 1].max())) + 1, 3), np.nan)
    by_type[coeffs[:, 0].astype(int)] = coeffs[:, 1:]
    values = by_type[rows[:, 1]]
    if np.isnan(values).any():
        raise ValueError(f"{path}: an angle's type has no Angle Coeffs line")
    return {
        "angles": rows[:, 2:5] - 1,
        "a0": values[:, 0],
        "k_area": values[:, 1],
        "jc": values[:, 2],
    }


def read_data(path: Path | str) -> System:
    """A System from a data file; raises FileNotFoundError or ValueError.

    Parameters
    ----------
    path : pathlib.Path or str
        A LAMMPS data file of this project (scene.data, strip.data): atom style
        bond, class2 or harmonic bonds.

    Returns
    -------
    System
        Positions, velocities, masses, types, molecules and springs, indexed by
        atom ID - 1.
    """
    sections = _sections(Path(path).read_text())
    for needed in ("Masses", "Atoms", "Bonds", "Bond Coeffs"):
        if needed not in sections:
            raise ValueError(f"{path}: no {needed} section")
    masses = {int(r.split()[0]): float(r.split()[1]) for r in sections["Masses"]}
    atoms = np.array([r.split() for r in sections["Atoms"]], float)
    order = np.argsort(atoms[:, 0])
    atoms = atoms[order]
    n = len(atoms)
    if not np.array_equal(atoms[:, 0], np.arange(1, n + 1)):
        raise ValueError(f"{path}: atom IDs must be 1..{n}")
    types = atoms[:, 2].astype(int)
    v = np.zeros((n, 2))
    if "Velocities" in sections:
        vel = np.array([r.split() for r in sections["Velocities"]], float)
        v[vel[:, 0].astype(int) - 1] = vel[:, 1:3]
    coeffs = np.array([r.split() for r in sections["Bond Coeffs"]], float)
    coeffs = coeffs[np.argsort(coeffs[:, 0])]
    if coeffs.shape[1] == 4:  # harmonic/quartic: r0 ka kb, class2 with ka/2, 0, kb/4
        zero = np.zeros(len(coeffs))
        coeffs = np.column_stack(
            [coeffs[:, 0], coeffs[:, 1], coeffs[:, 2] / 2.0, zero, coeffs[:, 3] / 4.0]
        )
    elif coeffs.shape[1] == 3:  # harmonic: K r0, i.e. class2 with K3 = K4 = 0
        zero = np.zeros(len(coeffs))
        coeffs = np.column_stack([coeffs[:, 0], coeffs[:, 2], coeffs[:, 1], zero, zero])
    bonds = np.array([r.split() for r in sections["Bonds"]], int)
    kind = bonds[:, 1] - 1
    return System(
        **_angles(sections, path),
        x=atoms[:, 3:5].copy(),
        v=v,
        mass=np.array([masses[t] for t in types]),
        types=types,
        molecule=atoms[:, 1].astype(int),
        bonds=bonds[:, 2:4] - 1,
        r0=coeffs[kind, 1],
        k2=coeffs[kind, 2],
        k3=coeffs[kind, 3],
        k4=coeffs[kind, 4],
    )
