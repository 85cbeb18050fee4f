"""Is e robust to the choice of normal? Each angle's mean e and beta at every
normal a target has, and whether they agree within the seed error.

Two disks have three normals (analysis.impact.binary: the line of centres at the
apse, at the first touch, and the impulse's normal). The wall has its fixed
normal, +y, and the impulse's normal, which its tables give: the disk comes
in at (v_n / cot gamma, -v_n) without spin, leaves at v_n' = e v_n and
v_t' = -beta v_t - R w' (the contact point's tangential velocity is
v_t + R w), so its impulse is M (v' - v) and its spin's change I0 w', and the
normal is the impulse's direction turned by asin(I0 w' / (R |J|)), as for two
disks. On the wall the normal is fixed by construction; the check is whether
the wall's numbers would survive the normal that the impulse itself shows.

An angle's e (or beta) is reported only where the means at the normals agree
within its seed error: the spread of the means (the largest less the
smallest) is at most the seed-bootstrap error of the headline's mean (the
apse's for two disks, the fixed normal's for the wall). Elsewhere the page
withholds it and says by how much the normals disagree.
"""

from __future__ import annotations

import numpy as np

from .statistics.seeds import SeedTable, seed_bootstrap, seed_tables

DISK_NORMALS = ("apse", "first_touch", "impulse")
WALL_NORMALS = ("fixed", "impulse")
NAMES = {
    "apse": "apse",
    "first_touch": "first touch",
    "impulse": "impulse",
    "fixed": "fixed (+y)",
}
# Columns of impacts.csv that hold each normal's numbers (the headline's are e, beta, cot_gamma).
HEADLINE = {"apse", "fixed"}


def column(quantity: str, normal: str) -> str:
    """The row's key of a quantity at a normal."""
    return quantity if normal in HEADLINE else f"{quantity}_{normal}"


def wall_impulse(row: dict, radius: float = 1.0) -> dict:
    """e, beta, cot gamma, the normal's angle from +y and the impulse's tilt
    from it, at the impulse's normal of a wall impact (module docstring).

    Parameters
    ----------
    row : dict
        A wall study's impacts.csv row (vn_in_c, cot_gamma, e, beta, omega,
        disk_inertia_ratio; numbers may be strings).
    radius : float
        R in the tables' units (1 in every study: lengths in R, times in R/c).

    Returns
    -------
    dict
        ``e_impulse``, ``beta_impulse``, ``cot_gamma_impulse``,
        ``normal_angle_deg_impulse`` and ``impulse_tilt_deg``.
    """
    v_n = float(row["vn_in_c"])
    v_t = v_n / float(row["cot_gamma"])
    e, beta, omega = float(row["e"]), float(row["beta"]), float(row["omega"])
    ratio = float(row["disk_inertia_ratio"])  # I0 / (M R^2)
    v_in = np.array([v_t, -v_n])
    v_out = np.array([-beta * v_t - radius * omega, e * v_n])
    per_mass = v_out - v_in  # J / M
    spin_change = ratio * radius * radius * omega  # dL / M
    turn = float(np.arcsin(np.clip(spin_change / (radius * np.linalg.norm(per_mass)), -1, 1)))
    angle = float(np.arctan2(per_mass[1], per_mass[0])) + turn
    normal = np.array([np.cos(angle), np.sin(angle)])
    tangent = np.array([normal[1], -normal[0]])
    c_in, c_out = v_in, v_out + radius * omega * tangent
    normal_in, tangential_in = float(c_in @ normal), float(c_in @ tangent)
    return {
        "e_impulse": float(-(c_out @ normal) / normal_in),
        "beta_impulse": float(-(c_out @ tangent) / tangential_in),
        "cot_gamma_impulse": float(abs(normal_in) / tangential_in),
        "normal_angle_deg_impulse": float(np.degrees(np.arctan2(normal[0], normal[1]))),
        "impulse_tilt_deg": float(np.degrees(turn)),
    }


def normals_of(rows: list[dict]) -> tuple[str, ...] | None:
    """The normals these rows can be measured at: two disks' three (if their
    tables have them), the wall's two; None for tables before the check."""
    if all(r.get("target") == "disk" for r in rows):
        return DISK_NORMALS if all(r.get("e_impulse") not in (None, "") for r in rows) else None
    return WALL_NORMALS


def with_normals(rows: list[dict], radius: float = 1.0) -> list[dict]:
    """The rows with every normal's e, beta and cot gamma as numbers."""
    if normals_of(rows) == WALL_NORMALS:
        return [{**r, **wall_impulse(r, radius)} for r in rows]
    return rows


def robustness(rows: list[dict], resamples: int = 200, radius: float = 1.0) -> dict | None:
    """Per lattice and angle: the means of e, beta and cot gamma at each
    normal with their seed-bootstrap errors, the spread of e and beta over
    the normals, and whether each agrees within the headline's error.

    Parameters
    ----------
    rows : list of dict
        A study's impacts.csv rows (one target).
    resamples : int
        Seed-bootstrap resamples.
    radius : float
        R (``wall_impulse``).

    Returns
    -------
    dict or None
        ``normals`` and per lattice ``gamma_deg``, ``<quantity>_<normal>``
        and ``..._error``, ``e_spread``, ``beta_spread``, ``e_robust``,
        ``beta_robust``, ``tilt_deg`` (the impulse's mean tilt from its
        normal); None where the tables lack the normals.
    """
    normals = normals_of(rows)
    if normals is None:
        return None
    rows = with_normals(rows, radius)
    quantities = [column(q, n) for n in normals for q in ("e", "beta", "cot_gamma")]
    quantities += ["impulse_tilt_deg"]
    tables = seed_tables(rows, quantities)

    def statistic(ts: dict[str, SeedTable]) -> dict:
        return {(name, q): t.mean(q) for name, t in ts.items() for q in quantities}

    error = seed_bootstrap(tables, statistic, resamples)
    out: dict = {"normals": list(normals), "lattices": {}}
    for name, table in tables.items():
        entry: dict = {"gamma_deg": table.gamma_deg.tolist()}
        for n in normals:
            for q in ("e", "beta", "cot_gamma"):
                entry[f"{q}_{n}"] = table.mean(column(q, n)).tolist()
                entry[f"{q}_{n}_error"] = np.asarray(error[(name, column(q, n))]).tolist()
        for q in ("e", "beta"):
            stack = np.array([entry[f"{q}_{n}"] for n in normals])
            spread = stack.max(axis=0) - stack.min(axis=0)
            allowed = np.array(entry[f"{q}_{normals[0]}_error"])
            entry[f"{q}_spread"] = spread.tolist()
            entry[f"{q}_robust"] = (spread <= allowed).tolist()
            # the headline and the impulse's normal alone (both the contact's,
            # where the first touch is the approach's): do they agree?
            two = np.abs(np.array(entry[f"{q}_{normals[0]}"]) - np.array(entry[f"{q}_impulse"]))
            entry[f"{q}_contact_robust"] = (two <= allowed).tolist()
        entry["tilt_deg"] = table.mean("impulse_tilt_deg").tolist()
        out["lattices"][name] = entry
    return out
