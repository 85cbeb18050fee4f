"""Does beta depend on the Poisson ratio? The numbers of the two square
disks compared (fits.json's ``pair``), with what else differs between them:
their shear stiffness, the energy they take into vibrations, the wall they
met (pages/templates/results/nu.md.j2 states them)."""

from __future__ import annotations

import math

import numpy as np

# beta0 of the two disks differs if both differences are above DIFFER
# errors, is the same if both are within SAME, and is a hint otherwise.
SAME, DIFFER = 2.0, 3.0


def shear_anisotropy(nu: float) -> float:
    """c44 / ((c11 - c12) / 2) of a square lattice's interior from its Poisson
    ratio along the axes: c11 = k1 + k2, c12 = c44 = k2 (per unit area), so
    nu = k2 / (k1 + k2) and the ratio is 2 k2 / k1 = 2 nu / (1 - nu); 1 for
    an isotropic solid, and the shear modulus over an isotropic solid's of the
    same c11 and nu."""
    return 2.0 * nu / (1.0 - nu)


def shear_ratio(nu_a: float, nu_b: float) -> float:
    """c44 of a square lattice of Poisson ratio nu_a over one of nu_b, at the
    same c11: c44 / c11 = k2 / (k1 + k2) = nu."""
    return nu_a / nu_b


def common_wall(study: dict, rows: list[dict], lattices: tuple[str, ...]) -> dict:
    """Whether the lattices met one wall (the same points, springs and spring
    constant): ``common``, from study.json's ``common_wall`` where it is
    recorded (``recorded``), else from impacts.csv: the wall's spring
    constant over each disk's (``ratios``; ``same_multiple`` if it is the
    same multiple of each disk's, a wall of each disk's own stiffness) and
    whether a seed's walls had the same points (``same_points``)."""
    if study.get("common_wall") is not None:
        return {"common": bool(study["common_wall"]), "recorded": True}
    mine = [r for r in rows if r["study_lattice"] in lattices]
    ratios = {
        lattice: sorted(
            {float(r["ka_wall_over_disk"]) for r in mine if r["study_lattice"] == lattice}
        )
        for lattice in lattices
    }
    points: dict = {}
    for r in mine:
        points.setdefault(r["seed"], set()).add(str(r["n_wall_points"]))
    same_points = all(len(v) == 1 for v in points.values())
    same_multiple = len({tuple(v) for v in ratios.values()}) == 1
    return {
        "common": False if same_multiple else same_points,
        "recorded": False,
        "ratios": ratios,
        "same_points": same_points,
        "same_multiple": same_multiple,
    }


def beta_at(means: list[dict], lattice: str, gamma: float) -> tuple | None:
    """A lattice's mean beta at an angle with its seed error, or None."""
    for m in means:
        if m["study_lattice"] == lattice and float(m["gamma_deg"]) == float(gamma):
            return m["beta"], m.get("beta_seed_sd")
    return None


def span(means: list[dict], lattice: str, quantity: str) -> tuple[float, float]:
    """The smallest and largest of a lattice's per-angle means of ``quantity``."""
    values = [m[quantity] for m in means if m["study_lattice"] == lattice]
    return min(values), max(values)


def poisson_pair(fits: dict, study: dict, rows: list[dict], means: list[dict]) -> dict | None:
    """The two square disks compared, or None if the study has not two."""
    pair = fits.get("pair")
    if not pair:
        return None
    low, high = pair["lower_nu"], pair["higher_nu"]
    a, b = fits["lattices"][low], fits["lattices"][high]
    limit = fits["chi2_limit"]
    differences = pair["beta_difference"]
    values, sds = np.array(differences["value"], float), np.array(differences["sd"], float)
    # how many angles' differences are above (below) SAME and DIFFER errors
    beyond = {
        name: (int(np.sum(values > k * sds)), int(np.sum(values < -k * sds)))
        for name, k in (("same", SAME), ("differ", DIFFER))
    }
    paper = pair["beta0_difference_paper"]
    paper_failed = max(a["walton"]["paper"]["chi2"], b["walton"]["paper"]["chi2"]) > limit
    paper_error = math.hypot(paper["sd"], paper["systematic"] if paper_failed else 0.0)
    normal = pair["beta_normal_difference"]
    z = abs(paper["value"]) / paper_error if paper_error > 0 else math.inf
    z_normal = abs(normal["value"]) / normal["sd"] if normal["sd"] else math.inf
    verdict = "hint"
    if min(z, z_normal) > DIFFER:
        verdict = "differ"
    elif max(z, z_normal) <= SAME:
        verdict = "same"
    return {
        "low": low,
        "high": high,
        "a": a,
        "b": b,
        "angles": [
            {
                "gamma": gamma,
                "low": beta_at(means, low, gamma),
                "high": beta_at(means, high, gamma),
                "difference": (d, s),
            }
            for gamma, d, s in zip(pair["gamma_deg"], values, sds)
        ],
        "beyond": beyond,
        "paper": paper,
        "paper_failed": paper_failed,
        "measured": pair["beta0_difference_measured"],
        "normal": normal,
        "z": z,
        "z_normal": z_normal,
        "verdict": verdict,
        "anisotropy": (shear_anisotropy(a["nu"]), shear_anisotropy(b["nu"])),
        "shear_ratio": shear_ratio(a["nu"], b["nu"]),
        # the disk's and the wall's share of the energy over the angles, each disk's
        "vibration": {
            target: tuple(span(means, x, f"vibration_{target}") for x in (low, high))
            for target in ("disk", "wall")
        },
        "wall": common_wall(study, rows, (low, high)),
    }
