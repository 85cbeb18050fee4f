"""A scene built: both bodies drawn, scaled and placed, in LAMMPS's atom order,
with what scene.json records (``build_scene``). A binary scene, of two disks,
is builder/binary.py's; ``build_scene`` builds either."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from ground.errors import InputError

from .binary import build_binary_scene
from .bodies import SURFACE, Body
from .materials import spring_constant
from .placement import on_grid, place_disk, placement_quantum, renumbered
from .sample import build_bodies
from .scene import (
    DISK,
    DISK_INTERIOR,
    DISK_SURFACE,
    TYPE_NAMES,
    WALL_FIXED,
    WALL_FREE,
    WALL_HELD,
    WALL_INTERIOR,
    WALL_SURFACE,
    Scene,
    SceneSpec,
    contact_energy,
    speed_unit,
    units_info,
    wall_spring_constant,
)
from .triangles import barrier_triangles

# Beyond this many disk points the interiors are stored in spatial bins, so
# that a spring's two atoms lie close in memory: the sampler's order scatters
# them, and once the atoms outgrow the cache the bond loop waits on memory
# (docs/benchmarks/loop_rate.md: LAMMPS's own binned sort gained 27 % per
# atom-step at 51,200 points, 7 % at 25,600 and nothing at 12,800). Up to
# here the sampler's order stays, and with it every committed result to its
# last bit; LAMMPS's sort itself stays off (decks/read_bodies.lmp).
SAMPLE_ORDER_UP_TO = 25_600
ORDER_BIN = 4.0  # the bins' side, in spacings


def binned_order(points: np.ndarray, indices: np.ndarray, size: float) -> np.ndarray:
    """``indices`` by the square bin of side ``size`` their points fall in,
    rows of bins bottom to top, each left to right (LAMMPS's atom sort); within
    a bin, in their given order."""
    cell = np.floor(points[indices] / size).astype(np.int64)
    return indices[np.lexsort((cell[:, 0], cell[:, 1]))]


def build_scene(spec: SceneSpec) -> Scene:
    """Build, scale and place both bodies of a scene.

    Parameters
    ----------
    spec : SceneSpec
        The scene: lattice, seed, angle, speed, sizes, contact; validated first.

    Returns
    -------
    Scene
        Atoms (positions, velocities, types, molecules) and springs in LAMMPS
        order, and ``info``, the derived quantities scene.json holds.

    Raises
    ------
    ground.errors.InputError
        If ``spec`` is invalid or its lattice is not calibrated.
    """
    spec.validate()
    if spec.target == "disk":
        return build_binary_scene(spec)
    R = spec.radius
    disk, wall = build_bodies(spec)

    ka_disk, disk_material = spring_constant(spec.lattice, disk.spacing * R, spec.k2_over_k1)
    ka_wall, ka_reference, wall_material = wall_spring_constant(spec)
    cutoff = spec.contact_cutoff * R
    gamma = np.radians(spec.gamma_deg)
    speed = spec.vn * speed_unit(spec, disk.spacing * R, ka_disk)
    if speed >= 1.0:
        raise InputError(
            f"vn must make the normal speed below c; vn {spec.vn:g} in units of the springs' "
            f"sound speed is {speed:.3f} c"
        )
    velocity = np.array([speed * np.tan(gamma), -speed])

    # Centre the sliding contact on the wall, but keep the disk clear of its sides.
    reach = spec.wall_width / 2.0 - 1.5
    contact_x = -np.clip(0.5 * velocity[0] * spec.contact_time_guess, 0.0, reach) * R
    wall_row = wall.points[wall.surface] * R
    quantum = placement_quantum(R)
    disk_points = on_grid(disk.points * R, quantum)
    centre = on_grid(
        place_disk(
            disk_points[disk.surface],
            wall_row,
            velocity,
            cutoff + spec.start_gap * cutoff,
            contact_x,
        ),
        quantum,
    )

    # Atom order: the wall's surface row first, left to right, so that
    # consecutive tags are neighbours on the contact polyline; then the rest of
    # the wall, the disk's surface row and the disk's interior.
    row = wall.surface[wall.role[wall.surface] == SURFACE]
    wall_rest = np.setdiff1d(np.arange(len(wall.points)), row)
    disk_rest = np.setdiff1d(np.arange(len(disk.points)), disk.surface)
    if spec.n_disk > SAMPLE_ORDER_UP_TO:
        wall_rest = binned_order(wall.points, wall_rest, ORDER_BIN * wall.spacing)
        disk_rest = binned_order(disk.points, disk_rest, ORDER_BIN * disk.spacing)
    wall_order = np.concatenate([row, wall_rest])
    disk_order = np.concatenate([disk.surface, disk_rest])
    n_wall = len(wall_order)

    wall_types = np.choose(wall.role, [WALL_SURFACE, WALL_INTERIOR, WALL_FIXED])[wall_order]
    disk_types = np.where(disk.role == SURFACE, DISK_SURFACE, DISK_INTERIOR)[disk_order]
    positions = np.concatenate([wall.points[wall_order] * R, disk_points[disk_order] + centre])
    velocities = np.zeros_like(positions)
    velocities[n_wall:] = velocity

    springs = np.concatenate(
        [renumbered(wall.springs, wall_order, 0), renumbered(disk.springs, disk_order, n_wall)]
    )
    ka = np.concatenate([ka_wall * wall.stiffness, ka_disk * disk.stiffness])
    types = np.concatenate([wall_types, disk_types])
    held = wall.held if wall.held is not None else np.zeros(len(wall.points), bool)
    molecule = np.concatenate(
        [np.where(held[wall_order], WALL_HELD, WALL_FREE), np.full(len(disk_order), DISK)]
    )

    scene = Scene(spec, positions, velocities, types, molecule, springs, ka, disk_centre=centre)
    scene.info = scene_info(
        scene,
        disk,
        wall,
        ka_disk,
        ka_wall,
        ka_reference,
        cutoff,
        disk_material,
        wall_material,
        velocity,
        len(row),
    )
    if spec.area_floor > 0.0:
        add_barrier(scene, disk_material["B"] * ka_disk, wall_material["B"] * ka_wall)
    return scene


def add_barrier(scene: Scene, k_disk: float, k_wall: float) -> None:
    """The barrier's angles on both bodies' triangles (builder/triangles.py),
    each body's k its 2-D bulk modulus, and what scene.json records of them."""
    in_disk = scene.molecule == DISK
    bodies = [(np.nonzero(in_disk)[0], k_disk), (np.nonzero(~in_disk)[0], k_wall)]
    floor = scene.spec.area_floor
    scene.angles = barrier_triangles(scene.frame_positions, scene.springs, bodies, floor)
    scene.info["area_barrier"] = {
        "area_floor": floor,
        "angles": int(len(scene.angles.atoms)),
        "angle_types": int(len(scene.angles.coefficients)),
        "disk_angles": int(in_disk[scene.angles.atoms[:, 0]].sum()),
        "k_disk": float(k_disk),
        "k_wall": float(k_wall),
    }


def scene_info(
    scene: Scene,
    disk: Body,
    wall: Body,
    ka_disk: float,
    ka_wall: float,
    ka_reference: float,
    cutoff: float,
    disk_material: dict,
    wall_material: dict,
    velocity: np.ndarray,
    n_row: int,
) -> dict:
    """Derived quantities that a run and its analysis need."""
    spec = scene.spec
    R = spec.radius
    in_disk = scene.molecule == DISK
    disk_xy = scene.positions[in_disk]
    com = disk_xy.mean(axis=0)  # all points have mass 1
    inertia = float(((disk_xy - com) ** 2).sum())
    lengths = scene.natural_lengths
    row = scene.positions[:n_row]
    longest_segment = float(np.linalg.norm(np.diff(row, axis=0), axis=1).max())
    a = spec.contact_decay
    return {
        "spec": asdict(spec),
        "units": units_info(spec, disk_material, disk.spacing * R, ka_disk),
        "disk_material": disk_material,
        "wall_material": wall_material,
        "n_atoms": int(len(scene.positions)),
        "n_disk_points": int(in_disk.sum()),
        "n_wall_points": int((~in_disk).sum()),
        "n_springs": int(len(scene.springs)),
        "atom_types": {str(k): v for k, v in TYPE_NAMES.items()},
        "wall_row_tags": [1, n_row],
        "wall_longest_segment": longest_segment,
        "disk_spacing": float(disk.spacing * R),
        "wall_spacing": float(wall.spacing * R),
        "max_natural_length": float(lengths.max()),
        "ka_disk": float(ka_disk),
        "ka_wall": float(ka_wall),
        # the unit of spec.wall_ka: the same for every disk lattice (wall_spring_constant)
        "ka_wall_reference": float(ka_reference),
        "kb_over_ka": spec.kb_over_ka,
        "contact": {
            "a": float(a),
            "V0": float(contact_energy(spec, in_disk.sum())),
            "cutoff": float(cutoff),
        },
        "disk_mass": float(in_disk.sum()),
        "disk_inertia": inertia,
        "disk_inertia_ratio": float(inertia / (in_disk.sum() * R * R)),
        "initial_com": com.tolist(),
        "initial_velocity": velocity.tolist(),
        "cot_gamma": float(abs(velocity[1]) / velocity[0]) if velocity[0] > 0 else None,
    }
