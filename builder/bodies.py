"""The two bodies of the model: a disk of radius 1 and a wall, as point networks.

Every body has a row of surface points on its outline, roughened along the
surface normal, and interior points that keep a clearance from that row.
Springs are the edges of the Delaunay triangulation of the body (see
``network``), except inside square lattices, whose springs come from the
lattice itself.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import Delaunay
from scipy.stats import qmc

from ground.errors import BuildError, InputError

from .geometry import Polyline, inside_polygon
from .network import triangulate_body, unique_edges
from .profile import Profile, correlated
from .sample_cache import cached_draw

# Roles of the points of a body. A FIXED point is held in place and is not part
# of the contact surface; a wall held fixed everywhere keeps its SURFACE row.
SURFACE, INTERIOR, FIXED = 0, 1, 2

# Bulk number density of scipy's Poisson-disk sampler (fill_space) is
# POISSON_FILL / radius**2; measured over seeds with scipy 1.17.
POISSON_FILL = 0.61
# Interior points keep this distance, in spacings, from the surface row: it
# keeps every surface segment a Delaunay edge, and keeps the circumcircles of
# the cells of a regular interior free of surface points.
CLEARANCE = 0.75
# Longest spring kept, in spacings. docs/model.md section 2 prunes at "about twice"
# the spacing to remove the hull triangles across dips; here the outline test
# in ``network`` removes those exactly, and this is only a safety net. Real
# springs exceed 2 spacings at the surface, because the roughness (std 0.45
# spacings) pushes neighbours apart: over 180 disks the longest surface spring
# was 2.55 spacings, and a prune at 2.25 would have cut genuine triangles out
# of 12 to 23 percent of them.
MAX_SPRING = 3.0

LATTICES = ("random", "triangular", "square")


@dataclass
class Body:
    """Points, their roles, and springs with relative stiffness."""

    points: np.ndarray  # (n, 2) positions
    role: np.ndarray  # (n,) SURFACE, INTERIOR or FIXED
    springs: np.ndarray  # (m, 2) point indices
    stiffness: np.ndarray  # (m,) spring constant in units of the body's ka
    surface: np.ndarray  # indices of the contact surface row, in order
    spacing: float  # nominal distance between neighbouring points
    held: np.ndarray | None = None  # (n,) True for points held fixed; None: none are
    # Outline segments that the pruned Delaunay triangulation left out (the
    # builder used to refuse such a body); a body with any was triangulated
    # exactly, as the constrained Delaunay triangulation of its outline
    # (``network.triangulate_body``). Empty for almost every body.
    steep: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), int))


def triangular_spacing(density: float) -> float:
    """Spacing of the triangular lattice with this number density."""
    return float(np.sqrt(2.0 / (np.sqrt(3.0) * density)))


def lattice_spacing(lattice: str, density: float) -> float:
    """Nominal spacing of a lattice of the given number density.

    For the random lattice it is the spacing of the triangular lattice with the
    same density, which is close to its mean spring length.
    """
    if lattice == "square":
        return float(1.0 / np.sqrt(density))
    return triangular_spacing(density)


def poisson_points(rng: np.random.Generator, spacing: float, lower, upper) -> np.ndarray:
    """Points with a minimum distance, filling a box at the density of ``spacing``
    (scipy's Poisson-disk sampler; kept in ``sample_cache``)."""
    density = 2.0 / (np.sqrt(3.0) * spacing**2)
    radius = np.sqrt(POISSON_FILL / density)
    arguments = {"radius": float(radius), "lower": list(map(float, lower))}
    arguments["upper"] = list(map(float, upper))

    def draw() -> np.ndarray:
        sampler = qmc.PoissonDisk(d=2, radius=radius, seed=rng, l_bounds=lower, u_bounds=upper)
        return sampler.fill_space()

    return cached_draw(rng, arguments, draw)


def regular_points(lattice: str, spacing: float, half_width: float) -> np.ndarray:
    """A triangular or square lattice through the origin, covering a square."""
    if lattice == "square":
        basis = np.array([[1.0, 0.0], [0.0, 1.0]]) * spacing
    else:
        basis = np.array([[1.0, 0.0], [0.5, np.sqrt(3.0) / 2.0]]) * spacing
    n = int(np.ceil(2.0 * half_width / (spacing * np.sqrt(3.0) / 2.0))) + 1
    i, j = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1), indexing="ij")
    points = np.stack([i.ravel(), j.ravel()], axis=1) @ basis
    return points[np.all(np.abs(points) <= half_width, axis=1)]


def keep_clear(candidates: np.ndarray, outline: np.ndarray, clearance: float) -> np.ndarray:
    """Candidates inside the closed outline and at least ``clearance`` from it."""
    far = ~Polyline(outline, closed=True).closer_than(candidates, clearance)
    # only the far ones can be kept: the polygon test is the costlier
    far[far] = inside_polygon(candidates[far], outline)
    return candidates[far]


def square_springs(points: np.ndarray, lattice: np.ndarray, spacing: float, k2_over_k1: float):
    """Nearest and next-nearest springs of the square lattice points ``lattice``.

    Both diagonals of every complete cell get k2; nearest neighbours get k1 = 1.
    """
    key = {tuple(np.rint(points[i] / spacing).astype(int)): i for i in lattice}
    pairs, stiffness = [], []
    for (ix, iy), i in key.items():
        for dx, dy in ((1, 0), (0, 1)):
            j = key.get((ix + dx, iy + dy))
            if j is not None:
                pairs.append((i, j))
                stiffness.append(1.0)
        corners = [key.get((ix + dx, iy + dy)) for dx, dy in ((1, 0), (0, 1), (1, 1))]
        if None not in corners:
            right, up, diagonal = corners
            pairs += [(i, diagonal), (right, up)]
            stiffness += [k2_over_k1, k2_over_k1]
    return np.sort(np.array(pairs), axis=1), np.array(stiffness)


def assemble(
    points, role, surface, outline, spacing, lattice="random", n_regular=0, k2_over_k1=None
) -> Body:
    """Triangulate a body; for a square interior swap in the lattice's own springs.

    ``n_regular`` is the number of trailing points that form a regular lattice.
    """
    springs, steep = triangulate_body(points, outline, MAX_SPRING * spacing)
    stiffness = np.ones(len(springs))
    if lattice == "square":
        regular = np.arange(len(points) - n_regular, len(points))
        is_regular = np.zeros(len(points), bool)
        is_regular[regular] = True
        # The Delaunay triangulation of a square grid picks one diagonal per
        # cell arbitrarily: drop all lattice-lattice edges and use the lattice's.
        joining = ~(is_regular[springs[:, 0]] & is_regular[springs[:, 1]])
        grid_pairs, grid_k = square_springs(points, regular, spacing, k2_over_k1)
        band_pairs = springs[joining]
        # Edges between two lattice points that the band needs (across notches of
        # the lattice's outline) are kept as joining springs.
        grid_set = {tuple(p) for p in grid_pairs.tolist()}
        lattice_edges = springs[~joining]
        extra = np.array([p for p in lattice_edges.tolist() if tuple(p) not in grid_set], int)
        extra_k = (
            np.array(
                [
                    k2_over_k1
                    if np.isclose(np.linalg.norm(points[a] - points[b]), np.sqrt(2) * spacing)
                    else 1.0
                    for a, b in extra
                ]
            )
            if len(extra)
            else np.zeros(0)
        )
        springs = np.concatenate([band_pairs, grid_pairs, extra.reshape(-1, 2)])
        stiffness = np.concatenate([np.ones(len(band_pairs)), grid_k, extra_k])
        order = np.lexsort((springs[:, 1], springs[:, 0]))
        springs, stiffness = springs[order], stiffness[order]
    return Body(points, role, springs, stiffness, surface, spacing, steep=steep)


# The readings of the model's surfaces (docs/model.md section 8): the roughness
# along the surface normal or in both directions; the disk's surface row
# evenly spaced or at random on the circle; a regular disk's surface a random
# row joined to the lattice by a band of springs, or the lattice's own outermost
# points.
ROUGHNESS_DIRECTIONS = ("normal", "both")
SURFACE_ROWS = ("even", "random")
REGULAR_SURFACES = ("band", "lattice")
# A random surface row keeps this distance, in spacings, between neighbours
# (a Poisson-disk sample on the circle, docs/model.md section 1). It gives the even
# row's number of points on average: 93 for an 800-point disk, measured over
# 60 seeds with scipy 1.17 (0.66 gave 94.4, 0.68 gave 91.4).
ROW_MIN_DISTANCE = 0.67


def make_disk(
    rng: np.random.Generator,
    lattice: str = "random",
    n_points: int = 800,
    roughness: float = 0.03,
    k2_over_k1: float = 3.0 / 7.0,
    roughness_direction: str = "normal",
    surface_row: str = "even",
    regular_surface: str = "band",
    roughness_length: float = 0.0,
    profiles: tuple[Profile, Profile] | None = None,
) -> Body:
    """A disk of radius 1 centred at the origin.

    The surface row is evenly spaced on the circle (or, with ``surface_row``
    "random", a Poisson-disk sample of it) and pushed along the radius by
    Gaussian roughness of standard deviation ``roughness`` (and, with
    ``roughness_direction`` "both", along the circle by another), independent
    from point to point or, with ``roughness_length`` > 0, a random profile of
    that correlation length along the circle (``correlated``), or, with
    ``profiles`` (the radial and the tangential), the seed's own continuous
    profiles of the angle (``profile``: the same surface at every
    ``n_points``). A regular
    disk with ``regular_surface`` "lattice" has no separate row: its surface
    is the lattice's own outermost points (``lattice_surface_disk``).

    The readings' draws come after the default's, so a seed keeps its
    interior and its radial roughness across the readings.
    """
    if lattice not in LATTICES:
        raise InputError(f"lattice must be one of {', '.join(LATTICES)}; got {lattice!r}")
    density = n_points / np.pi
    spacing = lattice_spacing(lattice, density)
    if regular_surface == "lattice" and lattice != "random":
        return lattice_surface_disk(
            rng, lattice, spacing, roughness, k2_over_k1, roughness_direction
        )
    n_surface = int(round(2.0 * np.pi / spacing))
    arc = 2.0 * np.pi / n_surface
    radial = roughness * correlated(rng.standard_normal(n_surface), arc, roughness_length)

    if lattice == "random":
        candidates = poisson_points(rng, spacing, [-1.0, -1.0], [1.0, 1.0])
    else:
        candidates = regular_points(lattice, spacing, 1.0)
    if surface_row == "random":
        angle = random_row_angles(rng, spacing)
        radial = roughness * rng.standard_normal(len(angle))
    else:
        angle = 2.0 * np.pi * np.arange(n_surface) / n_surface
    if profiles is not None:  # the noise above is still drawn: the interior stays the seed's
        radial = roughness * profiles[0](angle)
    surface_points = (1.0 + radial)[:, None] * np.stack([np.cos(angle), np.sin(angle)], axis=1)
    if roughness_direction == "both":
        shift = correlated(rng.standard_normal(len(angle)), arc, roughness_length)
        if profiles is not None:
            shift = profiles[1](angle)
        surface_points = around_the_circle(surface_points, roughness * shift)
    n_surface = len(surface_points)
    interior = keep_clear(candidates, surface_points, CLEARANCE * spacing)

    points = np.concatenate([surface_points, interior])
    role = np.concatenate([np.full(n_surface, SURFACE), np.full(len(interior), INTERIOR)])
    outline = np.arange(n_surface)
    return assemble(
        points,
        role,
        outline,
        outline,
        spacing,
        lattice,
        n_regular=len(interior) if lattice != "random" else 0,
        k2_over_k1=k2_over_k1,
    )


def random_row_angles(rng: np.random.Generator, spacing: float) -> np.ndarray:
    """Angles of a Poisson-disk sample of the unit circle at the even row's mean spacing.

    Sampled on the arc [0, 2 pi - r), r the minimum distance, so that the
    last and the first point keep it too; then turned by a random angle.
    """
    radius = ROW_MIN_DISTANCE * spacing
    sampler = qmc.PoissonDisk(
        d=1, radius=radius, seed=rng, l_bounds=[0.0], u_bounds=[2.0 * np.pi - radius]
    )
    angles = sampler.fill_space()[:, 0] + 2.0 * np.pi * rng.random()
    return np.sort(angles % (2.0 * np.pi))


def along_the_circle(points: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """Points of a disk's surface moved by ``shift`` along the circle's tangent."""
    angle = np.arctan2(points[:, 1], points[:, 0])
    return points + shift[:, None] * np.stack([-np.sin(angle), np.cos(angle)], axis=1)


def around_the_circle(points: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """``along_the_circle``, then in order of angle: a shift larger than the gap
    to a neighbour would make the row cross itself."""
    moved = along_the_circle(points, shift)
    order = np.argsort(np.arctan2(moved[:, 1], moved[:, 0]) % (2.0 * np.pi), kind="stable")
    return moved[order]


def lattice_surface_disk(
    rng: np.random.Generator,
    lattice: str,
    spacing: float,
    roughness: float,
    k2_over_k1: float,
    roughness_direction: str = "normal",
) -> Body:
    """A regular disk whose surface is the lattice's own outermost points.

    The lattice points within the unit circle that belong to a whole cell (a
    triangle of the triangular lattice, a square of the square one); the
    surface is the boundary of those cells, a closed row of points a spacing
    apart. The springs are the lattice's, taken before that row is roughened
    along the radius (and, with ``roughness_direction`` "both", along the
    circle), so every spring joins lattice neighbours.
    """
    grid = regular_points(lattice, spacing, 1.0)
    grid = grid[np.hypot(grid[:, 0], grid[:, 1]) <= 1.0 + 1e-9]
    points, outline, triangles = whole_cells(grid, lattice, spacing)
    role = np.full(len(points), INTERIOR)
    role[outline] = SURFACE
    if lattice == "square":
        springs, stiffness = square_springs(points, np.arange(len(points)), spacing, k2_over_k1)
    else:
        springs = unique_edges(triangles)
        stiffness = np.ones(len(springs))
    order = np.lexsort((springs[:, 1], springs[:, 0]))
    body = Body(points, role, springs[order], stiffness[order], outline, spacing)
    row = body.points[outline]
    radial = roughness * rng.standard_normal(len(outline))
    row = row * (1.0 + radial / np.hypot(row[:, 0], row[:, 1]))[:, None]
    if roughness_direction == "both":  # the springs fix the row's order: no re-sorting
        row = along_the_circle(row, roughness * rng.standard_normal(len(outline)))
    body.points[outline] = row
    return body


def whole_cells(
    grid: np.ndarray, lattice: str, spacing: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points of ``grid`` in whole cells of the lattice; the boundary of
    those cells as a counter-clockwise loop of indices into those points; and
    the cells' triangles (a square cell is two), as indices into them."""
    longest = (np.sqrt(2.0) if lattice == "square" else 1.0) * spacing * (1.0 + 1e-6)
    triangles = Delaunay(grid).simplices
    corners = grid[triangles]
    sides = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2)
    keep = sides.max(axis=1) <= longest
    if lattice == "square":  # half a cell whose fourth corner is outside: not a whole cell
        key = {tuple(k) for k in np.rint(grid / spacing).astype(int).tolist()}
        for t, corner in enumerate(corners):
            if keep[t]:
                legs = [np.linalg.norm(corner[i] - corner[(i + 1) % 3]) for i in range(3)]
                b = (int(np.argmax(legs)) + 2) % 3  # the vertex opposite the hypotenuse
                fourth = corner[(b + 1) % 3] + corner[(b + 2) % 3] - corner[b]
                keep[t] = tuple(np.rint(fourth / spacing).astype(int).tolist()) in key
    triangles = triangles[keep]
    used = np.unique(triangles)
    points = grid[used]
    triangles = np.searchsorted(used, triangles)
    edges = np.sort(
        np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1
    )
    unique, count = np.unique(edges, axis=0, return_counts=True)
    boundary = unique[count == 1]
    neighbours: dict[int, list[int]] = {}
    for a, b in boundary.tolist():
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    if any(len(n) != 2 for n in neighbours.values()):
        raise BuildError("the lattice's outermost cells touch at a corner: no single surface row")
    loop = [boundary[0, 0], boundary[0, 1]]
    while len(loop) < len(neighbours):
        a, b = neighbours[loop[-1]]
        loop.append(a if a != loop[-2] else b)
    loop = np.array(loop)
    x, y = points[loop, 0], points[loop, 1]
    if np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) < 0:  # clockwise: turn it round
        loop = loop[::-1]
    return points, loop, triangles


def random_rectangle(
    rng: np.random.Generator,
    spacing: float,
    width: float,
    height: float,
    roughness: float = 0.0,
    roughness_direction: str = "normal",
    roughness_length: float = 0.0,
    profiles: tuple[Profile, Profile] | None = None,
):
    """A random-lattice rectangle, x in [-width/2, width/2], y in [-height, 0].

    Rows of points on its four sides; the top row (but its corners) pushed
    along y by Gaussian roughness, and with ``roughness_direction`` "both"
    along x by another (then put in order of x, within a tenth of a spacing
    of the sides). With ``roughness_length`` > 0 both are random profiles of
    that correlation length along the row (``correlated``: the row's inner
    points taken as periodic, which correlates its two ends, held 8 R apart
    at the wall's sides), or with ``profiles`` (heights, then shifts) the
    seed's continuous profiles of x (``profile``). Returns the points, the
    outline in counter-clockwise order, and the indices of the top, right,
    left and bottom rows (sides without the top corners, bottom without its
    corners).
    """
    half = width / 2.0
    n_top = int(round(width / spacing))
    n_side = int(round(height / spacing))
    top_x = np.linspace(-half, half, n_top + 1)
    top_y = np.zeros(n_top + 1)
    step = top_x[1] - top_x[0]
    # corners stay on the sides
    top_y[1:-1] = roughness * correlated(rng.standard_normal(n_top - 1), step, roughness_length)
    if profiles is not None:  # the noise above is still drawn: the interior stays the seed's
        top_y[1:-1] = roughness * profiles[0](top_x[1:-1])
    top = np.stack([top_x, top_y], axis=1)
    side_y = np.linspace(0.0, -height, n_side + 1)[1:]  # below the top corners
    right = np.stack([np.full(n_side, half), side_y], axis=1)
    left = np.stack([np.full(n_side, -half), side_y], axis=1)
    bottom = np.stack([top_x[1:-1], np.full(n_top - 1, -height)], axis=1)

    rim = np.concatenate([top, right, left, bottom])
    rows = {"top": np.arange(n_top + 1)}
    rows["right"] = n_top + 1 + np.arange(n_side)
    rows["left"] = rows["right"][-1] + 1 + np.arange(n_side)
    rows["bottom"] = rows["left"][-1] + 1 + np.arange(n_top - 1)

    # Counter-clockwise: bottom-left corner, bottom row, right side up, top row
    # leftwards, left side down.
    outline = np.concatenate(
        [
            rows["left"][-1:],
            rows["bottom"],
            rows["right"][::-1],
            rows["top"][::-1],
            rows["left"][:-1],
        ]
    )
    candidates = poisson_points(rng, spacing, [-half, -height], [half, top_y.max()])
    if roughness_direction == "both":  # drawn after the interior, which a seed keeps
        shift = correlated(rng.standard_normal(n_top - 1), step, roughness_length)
        if profiles is not None:
            shift = profiles[1](top_x[1:-1])
        inner = top_x[1:-1] + roughness * shift
        edge = half - 0.1 * spacing
        order = np.argsort(inner, kind="stable")
        rim[1:n_top, 0] = np.clip(inner[order], -edge, edge)
        rim[1:n_top, 1] = top_y[1:-1][order]
    interior = keep_clear(candidates, rim[outline], CLEARANCE * spacing)
    return np.concatenate([rim, interior]), outline, rows


def make_wall(
    rng: np.random.Generator,
    n_points: int,
    width: float = 8.0,
    height: float = 2.0,
    roughness: float = 0.03,
    fixed: str = "sides",
    roughness_direction: str = "normal",
    roughness_length: float = 0.0,
    profiles: tuple[Profile, Profile] | None = None,
) -> Body:
    """A random-lattice wall, ``width`` by ``height``, whose top face is at y = 0.

    The top face is the contact surface, roughened along y (and along x with
    ``roughness_direction`` "both"). The points on the vertical sides are
    fixed; ``fixed`` = "sides+bottom" also fixes the bottom row and "all" every
    point (a rigid wall).
    """
    spacing = triangular_spacing(n_points / (width * height))
    points, outline, rows = random_rectangle(
        rng, spacing, width, height, roughness, roughness_direction, roughness_length, profiles
    )
    top = rows["top"]
    role = np.full(len(points), INTERIOR)
    role[top] = SURFACE
    role[[top[0], top[-1]]] = FIXED
    role[rows["right"]] = FIXED
    role[rows["left"]] = FIXED
    if fixed in ("sides+bottom", "all"):
        role[rows["bottom"]] = FIXED
    body = assemble(points, role, top, outline, spacing)
    body.held = role == FIXED
    if fixed == "all":
        body.held[:] = True
    return body
