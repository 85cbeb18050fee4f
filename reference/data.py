"""Reads the LAMMPS data files the builder writes (atom_style bond, 2-D; springs
harmonic/quartic, class2 or harmonic)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np


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


def _sections(text: str) -> dict[str, list[str]]:
    sections, name = {"header": []}, "header"
    for line in text.splitlines():
        stripped = line.split("#")[0].strip()
        if not stripped:
            continue
        if stripped in ("Masses", "Bond Coeffs", "Atoms", "Velocities", "Bonds"):
            name = stripped
            sections[name] = []
        else:
            sections[name].append(stripped)
    return sections


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
