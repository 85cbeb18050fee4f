"""What a binary study's page finds, in sentences whose every number comes
from its fits.json (pages/templates/binary_findings.md.j2): the aim, the
normals' check, e and friction beside the wall, and e > 1 at grazing angles,
each at the significance its errors (seed and systematic, and the look-
elsewhere of a chosen peak) support."""

from __future__ import annotations

import numpy as np

from analysis.binary_comparison import THIS_STUDY
from analysis.grazing import SIGNIFICANT, significant

from .render import render


def angle_list(gammas) -> str:
    """Angles as the page names them: '30, 45 and 55 degrees', or 'none'."""
    names = [f"{g:g}" for g in gammas]
    if not names:
        return "none"
    return (", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else names[0]) + (
        " degrees"
    )


def robust_angles(check: dict | None, quantity: str = "e") -> dict:
    """Per lattice the angles whose ``quantity`` all the normals agree on, those
    where the headline and the impulse's normal alone do, and of how many."""
    if not check:
        return {}
    return {
        lattice: {
            "robust": [g for g, r in zip(entry["gamma_deg"], entry[f"{quantity}_robust"]) if r],
            "contact": [
                g for g, r in zip(entry["gamma_deg"], entry[f"{quantity}_contact_robust"]) if r
            ],
            "angles": len(entry["gamma_deg"]),
            "normals": len(check["normals"]),
        }
        for lattice, entry in check["lattices"].items()
    }


def matched(comparisons: dict) -> str | None:
    """The wall study at half the pairs' relative speed (each disk's approach
    speed in the centre of mass), if there is one."""
    for name, numbers in comparisons.items():
        if numbers["wall_vn"] and all(
            abs(w - 0.5 * d) < 1e-9 for w in numbers["wall_vn"] for d in numbers["disk_vn"]
        ):
            return name
    return None


def e_beside_the_wall(numbers: dict, checks: dict, name: str) -> dict:
    """Per lattice: at the angles both targets' e is robust, the verdicts."""
    out = {}
    disk_check = checks.get(THIS_STUDY)
    wall_check = checks.get(f"the wall, docs/studies/{name}")
    for lattice, entry in numbers["lattices"].items():
        kept = []
        for j, gamma in enumerate(entry["gamma_deg"]):
            both = all(
                check is None
                or check["lattices"][lattice]["e_robust"][
                    check["lattices"][lattice]["gamma_deg"].index(gamma)
                ]
                for check in (disk_check, wall_check)
            )
            if both:
                kept.append((gamma, entry["e_verdict"][j], entry["e_difference"][j]))
        out[lattice] = {
            verdict: [g for g, v, _ in kept if v == verdict]
            for verdict in ("same", "undecided", "differs")
        }
        out[lattice]["largest_difference"] = max((abs(d) for _, _, d in kept), default=float("nan"))
    return out


def grazing_verdicts(grazing: dict | None) -> dict:
    """Per lattice the largest mean e (and whether the normals agree there),
    the largest that they agree on with its local and global z, and the
    verdict on e > 1 (analysis.grazing.significant)."""
    out = {}
    for lattice, n in (grazing or {}).items():
        out[lattice] = {
            "largest": n["largest"],
            "kept": n["largest_robust"],
            "contact": n.get("largest_contact"),
            "established": significant(n),
        }
    return out


def findings_section(fits: dict, study: dict) -> list[str]:
    """The page's findings (template binary_findings.md.j2) from its fits."""
    comparisons = fits.get("wall_comparison", {})
    checks = fits.get("normals", {})
    if not comparisons:
        return []
    first = next(iter(comparisons.values()))
    touch = first.get("first_touch") or {}
    worst = max(
        ((abs(x), lattice, g) for lattice, t in touch.items()
         for x, g in zip(t["relative"], t["gamma_deg"])),
        default=None,
    )  # fmt: skip
    name = matched(comparisons)
    context = {
        "study": study,
        "aim": {
            "worst": worst,
            "angles": sum(len(t["gamma_deg"]) for t in touch.values()),
            "no_line": sum(sum(t.get("no_line", ())) for t in touch.values()),
            "turned": sum(sum(t.get("turned", ())) for t in touch.values()),
            "largest_deg": max(
                (x for t in touch.values() for x in t.get("largest_deg", ())), default=None
            ),
            "impacts": sum(sum(t.get("impacts", ())) for t in touch.values()),
            "within_one_percent": sum(
                abs(x) <= 0.01 for t in touch.values() for x in t["relative"]
            ),
        },
        "normals": {
            target: {"e": robust_angles(check), "beta": robust_angles(check, "beta")}
            for target, check in checks.items()
            if check
        },
        "matched": name,
        "matched_vn": comparisons[name]["wall_vn"] if name else None,
        "disk_vn": first["disk_vn"],
        "e_matched": e_beside_the_wall(comparisons[name], checks, name) if name else {},
        "mu": {wall: numbers.get("mu_difference", {}) for wall, numbers in comparisons.items()},
        "wall_vn": {wall: numbers["wall_vn"] for wall, numbers in comparisons.items()},
        "grazing": grazing_verdicts(fits.get("grazing")),
        "wall_grazing": {
            wall: grazing_verdicts(by_lattice)
            for wall, by_lattice in fits.get("wall_grazing", {}).items()
        },
        "significant": SIGNIFICANT,
        "angle_list": angle_list,
        "isfinite": np.isfinite,
    }
    return render("binary_findings.md.j2", **context).rstrip("\n").splitlines() + [""]
