"""A binary scene: the disk hits a second disk, both free, centre of mass at rest.

The second disk (the target) sits at the origin; the disk (the projectile)
comes from above. The relative velocity of the centres, v_A - v_B, is
(v_n tan gamma, -v_n), and the disk is aimed by the contact, not by rigid
circles: its line of motion is offset from the target's centre so that, at
the first contact, the line of the centres of mass makes the angle gamma
with the relative velocity. The first contact is where a surface point of either
disk first comes within the contact's stand-off of the other's surface: the
distance l* at which one point's contact energy V0 exp(-a l*) equals the
approach's normal kinetic energy (1/2) mu v_n^2 (mu the reduced mass), the
turning distance of a head-on approach, which with the rings makes the
contact's effective diameter (``builder.aim.stand_off``). Until then both disks move
rigidly (the contact's energy is below a millionth of that until 0.05 R
before the stand-off, a R being 300), so the first contact follows from their rings
alone (``builder.aim.first_contact``: each point's ray against the other ring's segments
widened by the reach). Rigid circles of radius R would need the offset
2 R sin gamma; the rough rings and the stand-off need a larger one. Where
no line first touches at gamma (the incidence jumps past it onto another
asperity), the pair is turned, a quarter of the disk's surface spacing at a
time, until one does (``builder.aim.aim_turned``). The total momentum is zero.

Atom order and types: the target's surface ring first (tags 1..n, counter-
clockwise: pair_style polyline/exp's ring), then its interior (types 3 and 4,
molecule 2), then the disk's ring and interior (types 1 and 2, molecule 1),
so that decks/setup.lmp's groups and exclusions serve both scenes.
"""

from __future__ import annotations

from dataclasses import asdict, replace

import numpy as np

from ground.errors import InputError

from . import bodies, profile
from .aim import aim_turned, first_contact, hits, place_projectile, stand_off, turned
from .bodies import SURFACE, Body
from .materials import spring_constant
from .placement import on_grid, placement_quantum, renumbered
from .sample import sample_disk, sample_seeds
from .scene import (
    DISK,
    DISK_INTERIOR,
    DISK_SURFACE,
    WALL_FIXED,
    WALL_FREE,
    WALL_HELD,
    WALL_INTERIOR,
    WALL_SURFACE,
    Scene,
    SceneSpec,
    contact_energy,
    require_contact_resolved,
    speed_unit,
    units_info,
)

TARGET = WALL_FREE  # the target's molecule ID: decks/setup.lmp's group wall
TYPE_NAMES = {
    DISK_SURFACE: "disk surface",
    DISK_INTERIOR: "disk interior",
    WALL_SURFACE: "target disk surface",
    WALL_INTERIOR: "target disk interior",
    5: "held target disk interior (partner image-held)",
}


def partner_body(spec: SceneSpec, disk: Body) -> Body:
    """The second disk: its own stream of the sample's seed, or the disk of
    sample ``partner_seed``; the disk's lattice unless ``partner_lattice``.

    With ``partner`` "image" it is ``disk`` turned by 180 degrees about its
    centre: placed at the origin with the disk at c, it is the disk's point
    image through c / 2, and with equal and opposite velocities that point
    stays put. The collision is then symmetric (a rotation by 180 degrees
    about it maps each disk onto the other): each meets the other's surface
    exactly as the other meets its own, the symmetric two-body reference.
    (A mirror image in a line would be symmetric only without tangential
    motion: reflecting the disk in the midplane also reflects its velocity.)
    The turn keeps the ring counter-clockwise and every spring's length.
    """
    if spec.partner in ("image", "image-held"):
        return replace(disk, points=-disk.points)
    if spec.partner == "surface":
        return surface_ring(spec, disk.spacing)
    lattice = spec.partner_lattice or spec.lattice
    readings = (
        spec.roughness_direction,
        spec.surface_row,
        spec.regular_surface,
        spec.roughness_length,
    )
    if spec.partner_seed is not None:
        return sample_disk(replace(spec, lattice=lattice, seed=spec.partner_seed))
    rng = np.random.default_rng(sample_seeds(spec.seed)[2])
    return bodies.make_disk(rng, lattice, spec.n_disk, spec.roughness, spec.k2_over_k1, *readings)


# partner "surface": the held ring's radius in R. Its curvature is a
# twentieth of the disk's, so the contact's effective radius is 0.95 R, a
# flat wall's R to 5 %, while the ring stays small enough to build and aim.
SURFACE_RADIUS = 20.0


def surface_ring(spec: SceneSpec, spacing: float) -> Body:
    """A wall built like a disk's surface (``partner`` "surface"): a ring of
    radius SURFACE_RADIUS R with the disk's surface spacing, each point moved
    along the ring's normal by the disk's roughness (Gaussian, ``roughness``
    R, correlated along the ring with ``roughness_length`` as the disk's),
    from the sample's third stream. Only the ring: all its points are held,
    so it needs no interior and no springs; the contact sees both sides' points,
    as between two disks.
    """
    n = int(round(2.0 * np.pi * SURFACE_RADIUS / spacing))
    arc = 2.0 * np.pi * SURFACE_RADIUS / n
    rng = np.random.default_rng(sample_seeds(spec.seed)[2])
    radial = spec.roughness * profile.correlated(rng.standard_normal(n), arc, spec.roughness_length)
    angle = 2.0 * np.pi * np.arange(n) / n
    points = (SURFACE_RADIUS + radial)[:, None] * np.column_stack([np.cos(angle), np.sin(angle)])
    return Body(
        points=points,
        role=np.full(n, SURFACE),
        springs=np.zeros((0, 2), int),
        stiffness=np.zeros(0),
        surface=np.arange(n),
        spacing=arc,
    )


def counter_clockwise(ring: np.ndarray) -> bool:
    """Whether a closed ring runs counter-clockwise (positive shoelace area)."""
    x, y = ring[:, 0], ring[:, 1]
    return float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) > 0.0


def build_binary_scene(spec: SceneSpec) -> Scene:
    """Build, scale and place both disks of a binary scene (``target`` disk).

    Parameters
    ----------
    spec : SceneSpec
        The scene; validated by ``builder.assembly.build_scene``.

    Returns
    -------
    Scene
        As ``builder.assembly.build_scene``'s; ``info`` has ``target`` "disk" and
        both disks' masses, moments of inertia and rings.
    """
    R = spec.radius
    disk = sample_disk(spec)
    target = partner_body(spec, disk)
    partner_lattice = spec.partner_lattice or spec.lattice
    ka_disk, disk_material = spring_constant(spec.lattice, disk.spacing * R, spec.k2_over_k1)
    ka_target, target_material = spring_constant(
        partner_lattice, target.spacing * R, spec.k2_over_k1
    )
    # The contact's range is the coarser disk's spacing, as the wall's is its
    # own: the surface rows are then as fine as the range, both ways.
    cutoff = max(disk.spacing, target.spacing) * R
    require_contact_resolved(spec.contact_decay * R, cutoff / R, spec)

    quantum = placement_quantum(R)
    disk_points = on_grid(disk.points * R, quantum)
    target_points = on_grid(target.points * R, quantum)
    ring_a, ring_b = disk_points[disk.surface], target_points[target.surface]
    for name, ring in (("disk", ring_a), ("target", ring_b)):
        if not counter_clockwise(ring):  # pair_style polyline/exp's rings need it
            raise RuntimeError(f"the {name}'s surface row does not run counter-clockwise")

    speed = spec.vn * speed_unit(spec, disk.spacing * R, ka_disk)
    if speed >= 1.0:
        raise InputError(
            f"vn must make the normal speed below c; vn {spec.vn:g} in units of the springs' "
            f"sound speed is {speed:.3f} c"
        )
    gamma = np.radians(spec.gamma_deg)
    # the relative velocity before the aim's turn (below)
    unturned = np.array([speed * np.tan(gamma), -speed])
    mass_a, mass_b = len(disk.points), len(target.points)
    # a held target neither recoils nor gives: the disk brings all the relative velocity
    held = spec.partner in ("image-held", "surface")
    reduced_mass = mass_a if held else mass_a * mass_b / (mass_a + mass_b)
    reach = stand_off(
        contact_energy(spec, mass_a),
        spec.contact_a / R,
        reduced_mass,
        speed,
        cutoff,
    )
    # the aim's scale: R, or for the surface's 20 R ring the mean of both radii
    scale = 0.5 * (1.0 + SURFACE_RADIUS) * R if spec.partner == "surface" else R
    # Where no line of these rough rings first touches at gamma (the
    # incidence jumps past it onto another asperity), the pair is turned by
    # a quarter of the disk's surface spacing at a time: the same disks met
    # at other points of their surfaces, until a line does.
    # The line of centres is that of the centres of mass (as the analysis
    # measures it), not of the bodies' frames: a random disk's centre of mass
    # is up to 0.02 R from its frame's origin, which turns the line by up to
    # 0.6 degrees. So the aim sees each ring about its centre of mass.
    com_a, com_b = disk_points.mean(axis=0), target_points.mean(axis=0)
    about_a, about_b = ring_a - com_a, ring_b - com_b
    step = 0.25 * disk.spacing
    direction, offset, miss, turn = aim_turned(
        about_a, about_b, unturned / np.linalg.norm(unturned), gamma, reach, scale, step
    )
    relative = turned(unturned, turn) if turn else unturned
    gap = cutoff * (1 + spec.start_gap)
    placed = place_projectile(about_a, about_b, direction, offset, scale, gap)
    # the disk's frame goes where its centre of mass is placed less that centre
    centre = on_grid(placed + com_b - com_a, quantum)
    # the first contact the run will see, from where the disk is put, and the
    # line of the centres of mass then
    travel = first_contact(ring_a, ring_b, centre, direction, reach)
    touch = centre + travel * direction + com_a - com_b
    across = np.array([-direction[1], direction[0]])
    aimed = {
        "reach": reach,
        "offset": offset,
        # the pair's turn (degrees, counter-clockwise), and whether a line
        # first touches at gamma (else the nearest line past a jump)
        "turn_deg": float(np.degrees(turn)) + 0.0,
        "hit": bool(hits(miss)),
        "rigid_offset": 2.0 * scale * float(np.sin(gamma)),
        # R/c from the start: the run's time of the first contact
        "first_touch_time": float(travel / np.linalg.norm(relative)),
        "first_touch_incidence_deg": float(
            np.degrees(np.arctan2(touch @ across, -(touch @ direction)))
        ),
    }
    velocity_a = relative if held else relative * mass_b / (mass_a + mass_b)
    velocity_b = 0.0 * relative if held else -relative * mass_a / (mass_a + mass_b)

    disk_rest = np.setdiff1d(np.arange(len(disk.points)), disk.surface)
    target_rest = np.setdiff1d(np.arange(len(target.points)), target.surface)
    target_order = np.concatenate([target.surface, target_rest])
    disk_order = np.concatenate([disk.surface, disk_rest])
    n_target = len(target_order)

    positions = np.concatenate([target_points[target_order], disk_points[disk_order] + centre])
    velocities = np.concatenate(
        [np.tile(velocity_b, (n_target, 1)), np.tile(velocity_a, (len(disk_order), 1))]
    )
    # held: the ring keeps the surface type the contact acts on, the interior
    # is type 5; molecule 3 is not integrated (decks/setup.lmp's mobile) and
    # needs no springs
    target_interior = WALL_FIXED if held else WALL_INTERIOR
    types = np.concatenate(
        [
            np.where(target.role == SURFACE, WALL_SURFACE, target_interior)[target_order],
            np.where(disk.role == SURFACE, DISK_SURFACE, DISK_INTERIOR)[disk_order],
        ]
    )
    molecule = np.concatenate(
        [np.full(n_target, WALL_HELD if held else TARGET), np.full(len(disk_order), DISK)]
    )
    target_springs = target.springs[:0] if held else target.springs
    springs = np.concatenate(
        [
            renumbered(target_springs, target_order, 0),
            renumbered(disk.springs, disk_order, n_target),
        ]
    )
    target_stiffness = target.stiffness[:0] if held else target.stiffness
    ka = np.concatenate([ka_target * target_stiffness, ka_disk * disk.stiffness])
    scene = Scene(spec, positions, velocities, types, molecule, springs, ka, disk_centre=centre)
    n_ring_b, n_ring_a = len(target.surface), len(disk.surface)
    scene.info = binary_info(
        scene,
        disk_material,
        target_material,
        ka_disk,
        ka_target,
        cutoff,
        disk.spacing * R,
        relative,
        rings=((1, n_ring_b), (n_target + 1, n_target + n_ring_a)),
    )
    scene.info["aim"] = aimed
    # the nominal incidence, whatever the aim's turn
    scene.info["cot_gamma"] = float(-unturned[1] / unturned[0]) if unturned[0] > 0 else None
    return scene


def body_inertia(points: np.ndarray) -> tuple[float, np.ndarray]:
    """Moment of inertia about the centre of mass (unit point masses), and that centre."""
    com = points.mean(axis=0)
    return float(((points - com) ** 2).sum()), com


def longest_ring_segment(ring: np.ndarray) -> float:
    return float(np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1).max())


def binary_info(
    scene: Scene,
    disk_material: dict,
    target_material: dict,
    ka_disk: float,
    ka_target: float,
    cutoff: float,
    disk_spacing: float,
    relative: np.ndarray,
    rings: tuple[tuple[int, int], tuple[int, int]],
) -> dict:
    """Derived quantities of a binary scene that a run and its analysis need;
    the wall scene's keys where they mean the same (``scene_info``)."""
    spec = scene.spec
    R = spec.radius
    in_disk = scene.molecule == DISK
    inertia_a, com_a = body_inertia(scene.positions[in_disk])
    inertia_b, com_b = body_inertia(scene.positions[~in_disk])
    mass_a, mass_b = float(in_disk.sum()), float((~in_disk).sum())
    (b_first, b_last), (a_first, a_last) = rings
    longest = max(
        longest_ring_segment(scene.positions[b_first - 1 : b_last]),
        longest_ring_segment(scene.positions[a_first - 1 : a_last]),
    )
    lengths = scene.natural_lengths
    return {
        "spec": asdict(spec),
        "target": "disk",
        # partner image-held: the target's points are held (its mass and
        # inertia are those of its points, but nothing moves it)
        "target_held": spec.partner in ("image-held", "surface"),
        "units": units_info(spec, disk_material, disk_spacing, ka_disk),
        "disk_material": disk_material,
        "target_material": target_material,
        "n_atoms": int(len(scene.positions)),
        "n_disk_points": int(mass_a),
        "n_target_points": int(mass_b),
        "n_springs": int(len(scene.springs)),
        "atom_types": {str(k): v for k, v in TYPE_NAMES.items()},
        # the target's ring is the pair style's polyline, the disk's its partner
        "wall_row_tags": [b_first, b_last],
        "partner_row_tags": [a_first, a_last],
        "wall_longest_segment": longest,
        "disk_spacing": float(disk_spacing),
        "wall_spacing": float(cutoff),
        "max_natural_length": float(lengths.max()),
        "ka_disk": float(ka_disk),
        "ka_target": float(ka_target),
        "kb_over_ka": spec.kb_over_ka,
        "contact": {
            "a": float(spec.contact_decay),
            # both directions at the V0 of the disk's mass (docs/model.md, "Two disks")
            "V0": float(contact_energy(spec, mass_a)),
            "cutoff": float(cutoff),
        },
        "disk_mass": mass_a,
        "target_mass": mass_b,
        "disk_inertia": inertia_a,
        "target_inertia": inertia_b,
        "disk_inertia_ratio": float(inertia_a / (mass_a * R * R)),
        "target_inertia_ratio": float(inertia_b / (mass_b * R * R)),
        "initial_com": com_a.tolist(),
        "target_initial_com": com_b.tolist(),
        "initial_velocity": scene.velocities[in_disk][0].tolist(),
        "target_initial_velocity": scene.velocities[~in_disk][0].tolist(),
        "initial_relative_velocity": relative.tolist(),
    }
