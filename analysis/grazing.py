"""e at grazing incidence: its peak against tan gamma, and whether e > 1.

The seed paper's authors, in a companion letter (Phys. Rev. Lett. 93,
154301, 2004; cond-mat/0310058), reported e above 1 in oblique impacts, peaking against the
angle of incidence. A study whose angles go past the paper's last, 80.5
degrees, gets this section: per lattice, the peak of the mean e against
tan gamma (a parabola through the largest mean and its two neighbours), its
position and height with seed-bootstrap errors (whole seeds resampled, as
everywhere), and whether the largest mean e is above 1 by more than two of
its errors once the look-elsewhere effect is counted: the largest of A means
was chosen after the fact, so its (e - 1) / error is compared with the
largest of the A angles' standardised deviations over resamples of whole
seeds (a max-statistic test, which keeps the angles' correlation), not with
one normal variate.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import norm

from .page import pm
from .sections import genuine
from .seeds import SeedTable, seed_bootstrap, seed_draws, seed_tables

PAPER_LAST_ANGLE = 80.5  # degrees: the paper's last angle
SIGNIFICANT = 2.0  # e > 1 counts when it is above 1 by this many errors (look-elsewhere counted)
# Resamples of the look-elsewhere test: its p is a tail share, which 200 would
# resolve only to 0.005
LOOK_ELSEWHERE_RESAMPLES = 4000


def look_elsewhere(table: SeedTable, z: float, resamples: int = LOOK_ELSEWHERE_RESAMPLES) -> dict:
    """How often the largest of the angles' standardised deviations reaches ``z``.

    Each resample of whole seeds gives every angle's mean e; its deviation
    from the study's mean over that angle's bootstrap error, maximised over
    the angles, is what the largest of A means would show by chance if no
    angle's e were above the level tested. The share of resamples whose
    maximum reaches ``z`` is the global p (with the usual +1 in numerator and
    denominator), and its normal quantile the global z.

    Parameters
    ----------
    table : SeedTable
        One lattice's impacts.
    z : float
        The largest mean's (e - 1) / error.
    resamples : int
        Resamples of whole seeds (generator ``seeds.RNG_SEED``).

    Returns
    -------
    dict
        ``angles``, ``resamples``, ``p`` and ``z`` (global), NaN if z is.
    """
    draws = seed_draws({"t": table}, lambda ts: {"e": ts["t"].mean("e")}, resamples)["e"]
    centre, spread = table.mean("e"), np.nanstd(draws, axis=0, ddof=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        largest = np.nanmax((draws - centre) / spread, axis=1)
    if not np.isfinite(z):
        return {"angles": int(len(centre)), "resamples": resamples, "p": np.nan, "z": np.nan}
    reached = int(np.sum(largest >= z))
    p = (reached + 1) / (resamples + 1)
    return {
        "angles": int(np.sum(np.isfinite(centre))),
        "resamples": resamples,
        "p": float(p),
        "z": float(norm.isf(p)),
        # no resample reached z: p is a bound, and z at least this
        "bound": reached == 0,
    }


def peak(x, y) -> tuple[float, float] | None:
    """The top of y(x): the vertex of the parabola through the largest y and
    its two neighbours; None where the largest y is at either end (no peak
    inside the range) or is not finite.

    Parameters
    ----------
    x, y : array_like
        Increasing x, and the values there.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if not np.all(np.isfinite(y)) or len(y) < 3:
        return None
    i = int(np.argmax(y))
    if i in (0, len(y) - 1):
        return None
    a, b, c = np.polyfit(x[i - 1 : i + 2], y[i - 1 : i + 2], 2)
    if a >= 0:
        return None
    top = -b / (2 * a)
    return float(top), float(c - b * b / (4 * a))


def grazing_numbers(rows: list[dict], resamples: int = 200, check: dict | None = None) -> dict:
    """Per lattice: tan gamma, mean e with errors, the peak, the largest mean
    and, with the normals' check (``analysis.normal_check.robustness``), each
    angle's verdict and the largest mean that the normals agree on.

    Parameters
    ----------
    rows : list of dict
        impacts.csv rows.
    resamples : int
        Seed-bootstrap resamples.
    check : dict, optional
        The normals' check of the same rows.

    Returns
    -------
    dict
        Per lattice; ``largest`` and ``largest_robust`` each with its e,
        error, local z and global (look-elsewhere) p and z.
    """
    tables = seed_tables(rows, ("e", "beta"))

    def tan(table: SeedTable) -> np.ndarray:
        return np.tan(np.radians(table.gamma_deg))

    def statistic(ts: dict[str, SeedTable]) -> dict:
        out = {}
        for name, t in ts.items():
            top = peak(tan(t), t.mean("e"))
            out[name + "/peak_x"], out[name + "/peak_e"] = top if top else (np.nan, np.nan)
            out[name + "/e"] = t.mean("e")
        return out

    central = statistic(tables)
    error = seed_bootstrap(tables, statistic, resamples)
    out = {}
    for name, t in tables.items():
        e, e_err = central[name + "/e"], error[name + "/e"]
        above = np.nan_to_num(t.values["e"]) > 1.0
        entry = (check or {}).get("lattices", {}).get(name)
        robust = spread = contact = None
        if entry is not None:
            index = {round(g, 9): j for j, g in enumerate(entry["gamma_deg"])}
            at = [index[round(float(g), 9)] for g in t.gamma_deg]
            robust = np.array([bool(entry["e_robust"][j]) for j in at])
            spread = np.array([float(entry["e_spread"][j]) for j in at])
            if "e_contact_robust" in entry:  # the headline and the impulse's normal alone
                contact = np.array([bool(entry["e_contact_robust"][j]) for j in at])

        def largest(among: np.ndarray) -> dict | None:
            if not among.any():
                return None
            top = int(np.nanargmax(np.where(among, e, -np.inf)))
            z = float((e[top] - 1.0) / e_err[top]) if e_err[top] > 0 else float("nan")
            return {
                "gamma_deg": float(t.gamma_deg[top]),
                "e": float(e[top]),
                "error": float(e_err[top]),
                "z": z,
                # the null of the largest of all the angles: conservative for a subset
                "global": look_elsewhere(t, z),
                "robust": True if robust is None else bool(robust[top]),
                "spread": None if spread is None else float(spread[top]),
            }

        everywhere = np.isfinite(e)
        out[name] = {
            "tan_gamma": tan(t).tolist(),
            "gamma_deg": t.gamma_deg.tolist(),
            "e": e.tolist(),
            "e_error": e_err.tolist(),
            "impacts": t.counts().tolist(),
            "share_above_1": (above.sum(axis=0) / np.maximum(t.counts(), 1)).tolist(),
            "peak_tan_gamma": central[name + "/peak_x"],
            "peak_tan_gamma_error": float(error[name + "/peak_x"]),
            "peak_e": central[name + "/peak_e"],
            "peak_e_error": float(error[name + "/peak_e"]),
            "largest": largest(everywhere),
            "largest_robust": largest(everywhere if robust is None else everywhere & robust),
            # where the headline and the impulse's normal agree, the first touch set aside
            "largest_contact": None if contact is None else largest(everywhere & contact),
        }
        if robust is not None:
            out[name].update(
                robust=robust.tolist(), spread=spread.tolist(), normals=check["normals"]
            )
    return out


def has_grazing_angles(rows: list[dict]) -> bool:
    return any(float(r["gamma_deg"]) > PAPER_LAST_ANGLE + 1e-6 for r in rows)


def peak_cells(numbers: dict) -> tuple[str, str, str]:
    """A lattice's peak as a table gives it: at tan gamma, in degrees, its e."""
    if not np.isfinite(numbers["peak_tan_gamma"]):
        return "none inside the range", "-", "-"
    return (
        pm(numbers["peak_tan_gamma"], numbers["peak_tan_gamma_error"], 2),
        f"{np.degrees(np.arctan(numbers['peak_tan_gamma'])):.1f}",
        pm(numbers["peak_e"], numbers["peak_e_error"]),
    )


def significant(numbers: dict) -> bool:
    """e > 1 counts: the largest mean that the normals agree on is above 1
    beyond SIGNIFICANT errors once the look-elsewhere is counted."""
    largest = numbers.get("largest_robust")
    if not largest:
        return False
    z = largest["global"]["z"]
    return z is not None and np.isfinite(z) and z > SIGNIFICANT


def largest_cells(largest: dict | None) -> str:
    """A largest mean's cells: e +- error | at, deg | (e - 1) / error."""
    if not largest:
        return "none | - | -"
    return f"{pm(largest['e'], largest['error'])} | {largest['gamma_deg']:g} | {largest['z']:+.1f}"


def robust_cell(largest: dict) -> str:
    """Whether the normals agree at the largest mean, and by how much they differ."""
    if largest["spread"] is None:
        return "-"
    verdict = "yes" if largest["robust"] else "no"
    return f"{verdict} ({largest['spread']:.3f})"


def global_cells(largest: dict | None) -> str:
    """The look-elsewhere test's cells: angles | global p | global z."""
    if not largest:
        return "- | - | -"
    g = largest["global"]
    if largest["e"] <= 1.0:  # nothing above 1 to test
        return f"{g['angles']} | - | -"
    if g["p"] is None or not np.isfinite(g["p"]):
        return f"{g['angles']} | - | -"
    if g.get("bound"):
        return f"{g['angles']} | <= {g['p']:.2g} | >= {g['z']:+.1f}"
    return f"{g['angles']} | {g['p']:.2g} | {g['z']:+.1f}"


def grazing_section(numbers: dict, figure_dir: str) -> list[str]:
    lines = [
        "## Grazing incidence: the peak of e and e > 1",
        "",
        "The seed paper's authors (Phys. Rev. Lett. 93, 154301, 2004) reported e above 1 in "
        "oblique impacts, with a peak against the angle of incidence, and put it down to the local "
        "deformation of the wall, which tilts the contact plane. The peak: the vertex of the "
        "parabola through the largest mean e and its two neighbours, against tan gamma; none "
        "where the largest mean is at the first or last angle. Errors: the seed bootstrap. "
        "The largest mean is the largest of the study's angles, chosen after the fact: its "
        "(e - 1) / error is compared with the largest standardised deviation of all the "
        "angles' means over resamples of whole seeds (the look-elsewhere effect: "
        f"{LOOK_ELSEWHERE_RESAMPLES} resamples), which gives its global p and the normal z of "
        "that p. Where the normals' check has measured the study (analysis/normal_check.py: "
        "does e stay within its seed error when measured at another normal?), the test takes "
        "the largest mean that the normals agree on (its global p from the largest of all the "
        "angles, which is conservative), and the table gives how far the normals differ at "
        f"the largest mean. e > 1 counts where that global z is above {SIGNIFICANT:g}.",
        "",
        "| lattice | peak at tan gamma | (degrees) | peak e | largest mean e | at, deg | "
        "(e - 1) / error | normals agree (their spread) | largest robust mean e | at, deg | "
        "(e - 1) / error | of how many angles | global p | global z | e > 1 significant |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, n in numbers.items():
        big, kept = n["largest"], n["largest_robust"]
        where, degrees, height = peak_cells(n)
        lines.append(
            f"| {name} | {where} | {degrees} | {height} | {largest_cells(big)} | "
            f"{robust_cell(big)} | {largest_cells(kept)} | {global_cells(kept)} | "
            f"{'yes' if significant(n) else 'no'} |"
        )
    checked = any("robust" in n for n in numbers.values())
    if checked:
        normals = next(n["normals"] for n in numbers.values() if "normals" in n)
        lines += [
            "",
            "e is measured at the headline normal; the normals' check (analysis/normal_check.py; "
            f"normals: {', '.join(normals)}) reports it only where the means at the normals "
            "agree within its seed error, and withholds the verdict on e > 1 where they do not.",
        ]
    lines += [
        "",
        "e per angle, with the share of impacts whose e is above 1"
        + (" and the spread of the mean e over the normals:" if checked else ":"),
        "",
        "| lattice | gamma, deg | tan gamma | impacts | e | share e > 1 |"
        + (" normals' spread | robust |" if checked else ""),
        "|---|---|---|---|---|---|" + ("---|---|" if checked else ""),
    ]
    for name, n in numbers.items():
        for j, (g, t, k, e, s, share) in enumerate(zip(
            n["gamma_deg"], n["tan_gamma"], n["impacts"], n["e"], n["e_error"],
            n["share_above_1"], strict=True,
        )):  # fmt: skip
            line = f"| {name} | {g:g} | {t:.3g} | {k} | {pm(e, s)} | {share:.2f} |"
            if "robust" in n:
                line += f" {n['spread'][j]:.3f} | {'yes' if n['robust'][j] else 'withheld'} |"
            elif checked:
                line += " - | - |"
            lines.append(line)
    lines += [
        "",
        f"![e against tan gamma]({figure_dir}/grazing_e.png)",
        "",
        "*e against tan gamma; error bars: seed-bootstrap errors; the line at e = 1.*",
        "",
    ]
    return lines


def draw(numbers: dict, folder) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .figures import LABELS, STYLE

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for name, n in numbers.items():
        colour, marker = STYLE.get(name, ("k", "o"))
        ax.errorbar(
            n["tan_gamma"], n["e"], n["e_error"], fmt=marker + "-", color=colour, lw=0.8,
            label=LABELS.get(name, name),
        )  # fmt: skip
    ax.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("tan gamma")
    ax.set_ylabel("e")
    ax.legend(fontsize=8)
    fig.tight_layout()
    folder.mkdir(parents=True, exist_ok=True)
    fig.savefig(folder / "grazing_e.png", dpi=120)
    plt.close(fig)


# What a reading's study.json may differ in from the study's and still be a
# reading of it: everything but its name and the records of its run (how
# long it took, what its study file said).
NOT_A_READING = ("name", "wall_clock", "common_wall", "lammps_seconds", "source")


def reading_differences(study: dict, reading: dict) -> str:
    """The options a reading's study.json sets otherwise than the study's."""
    words = []
    for key in sorted(set(study) | set(reading)):
        if key in NOT_A_READING or study.get(key) == reading.get(key):
            continue
        if isinstance(reading.get(key), dict):  # the run's options
            inner = reading[key]
            words += [
                f"{k} {inner[k]}"
                for k in sorted(inner)
                if inner.get(k) != study.get(key, {}).get(k)
            ]
        else:
            words.append(f"{key} {reading.get(key)}")
    return ", ".join(words) or "none"


def readings_section(study: dict, readings: dict[str, tuple[dict, list[dict], list[dict]]],
                     resamples: int = 200) -> list[str]:  # fmt: skip
    """The same grazing study under other readings, a row each: what differs,
    the peak of e and whether e > 1 is significant (as above), and the share
    of contacts whose disk centre came within 1 R of a held side."""
    if not readings:
        return []
    lines = [
        "## The same study under other readings",
        "",
        "Each row: this study's command with other options (`--name <reading>`), its "
        "tables in `docs/<reading>/`; the peak and the largest mean as above, for the "
        "random disk; near a side: the share of its contacts whose disk centre came within "
        "1 R of a held side of the wall (column `side_clearance` < 1), where e measures the "
        "wall's end as much as the impact.",
        "",
        "| reading | options that differ | impacts | failed | peak at tan gamma | (degrees) | "
        "peak e | largest mean e | at, deg | (e - 1) / error | normals agree (their spread) | "
        "largest robust mean e | at, deg | (e - 1) / error | of how many angles | global p | "
        "global z | e > 1 significant | near a side |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    from .normal_check import robustness

    for name, (info, rows, failed) in readings.items():
        numbers = grazing_numbers(rows, resamples, robustness(rows, resamples))
        for lattice, n in numbers.items():
            big = n["largest"]
            where, degrees, height = peak_cells(n)
            mine = [r for r in rows if r["study_lattice"] == lattice]
            # a pair of disks has no wall, so no side to come near
            sides = [float(r["side_clearance"]) for r in mine if r.get("side_clearance") != ""]
            near = f"{np.mean([c < 1.0 for c in sides]):.0%}" if sides else "-"
            label = name if len(info["lattices"]) == 1 else f"{name} ({lattice})"
            lost = len(genuine(failed))
            stuck = f" (+{len(failed) - lost} on the wall at tmax)" if len(failed) > lost else ""
            lines.append(
                f"| {label} | {reading_differences(study, info)} | {len(mine)} | {lost}{stuck} | "
                f"{where} | {degrees} | {height} | {largest_cells(big)} | {robust_cell(big)} | "
                f"{largest_cells(n['largest_robust'])} | {global_cells(n['largest_robust'])} | "
                f"{'yes' if significant(n) else 'no'} | {near} |"
            )
    return lines + [""]
