"""Sections that every study's page has alike: its failures, its inaccurate
impacts, the wall's ends, where its tables are (analysis.report's results
page and analysis.speed_page's speed page)."""

from __future__ import annotations

import re
from collections import Counter

from builder.study_names import SECTIONS  # noqa: F401 (plain data there)

# What a run says when its disk never leaves the wall (decks/impact.lmp) or two
# disks never part (decks/binary.lmp) by tmax: a physical outcome with no
# rebound to measure, its own state in failed.csv (``state``), not a failure
# of the run; a study whose impacts all ran as asked has succeeded.
STUCK = ("has not left the wall by tmax", "have not parted by tmax")
STATES = ("failed", "stuck")


def impact_state(error: str) -> str:
    """An impact without a result: ``stuck`` (it stayed in contact until tmax)
    or ``failed`` (the run did not go as asked)."""
    return "stuck" if any(words in error for words in STUCK) else "failed"


def state_of(failure: dict) -> str:
    """A failed.csv row's state; rows from before the column, from its error."""
    return failure.get("state") or impact_state(failure["error"])


def genuine(failed: list[dict]) -> list[dict]:
    """The impacts whose run failed, not those that stayed on the wall."""
    return [f for f in failed if state_of(f) == "failed"]


def outcome_note(failed: list[dict]) -> str:
    """'N impacts failed' and, if any, how many stayed on the wall, for a page's first lines."""
    lost, stuck = len(genuine(failed)), len(failed) - len(genuine(failed))
    note = f"{lost} impact{'' if lost == 1 else 's'} failed"
    if stuck:
        note += (
            f"; in {stuck} the disk{' had' if stuck == 1 else 's had'} not left the wall by "
            "tmax (below)"
        )
    return note


NUMBER = re.compile(r"(?:(?<!\d)[-+])?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|\b(?:nan|inf)\b")


def failure_cause(message: str) -> str:
    """A failure's message without LAMMPS's prefix, when and where it struck
    and its numbers: what failures are counted by."""
    text = re.sub(r"^ERROR( on proc \d+)?:\s*", "", message.strip())
    text = re.split(r",| at time | at step ", text, maxsplit=1)[0]
    return NUMBER.sub("#", text).strip()


def failure_causes(failed: list[dict]) -> dict[str, int]:
    """How many failures each cause has, most first (not the impacts that
    stayed on the wall: ``genuine``)."""
    return dict(Counter(failure_cause(f["error"]) for f in genuine(failed)).most_common())


def where(impacts: list[dict]) -> str:
    """Lattices and angles of some impacts, with their seeds (or their count)."""
    by_angle: dict[tuple, list] = {}
    for impact in impacts:
        by_angle.setdefault((impact["lattice"], float(impact["gamma"])), []).append(impact["seed"])
    parts = []
    for (lattice, gamma), seeds in sorted(by_angle.items()):
        seeds = sorted(seeds)
        listed = (
            f"seed{'s' if len(seeds) > 1 else ''} {', '.join(map(str, seeds))}"
            if len(seeds) <= 6
            else f"{len(seeds)} seeds"
        )
        parts.append(f"{lattice} {gamma:g} deg: {listed}")
    return "; ".join(parts)


def failure_section(failed: list[dict]) -> list[str]:
    """The failed impacts by cause: count, where, and one message in full;
    then those that stayed on the wall (``stuck_section``)."""
    stuck = stuck_section(failed)
    failed = genuine(failed)
    if not failed:
        return stuck
    lines = [
        "## Failed impacts",
        "",
        f"{len(failed)} impact{'' if len(failed) == 1 else 's'} failed, "
        "by cause (`failed.json` in each impact's folder has its message; `--retry-failed` "
        "runs them again):",
        "",
        "| cause | impacts | where | a message |",
        "|---|---|---|---|",
    ]
    for cause, count in failure_causes(failed).items():
        these = [f for f in failed if failure_cause(f["error"]) == cause]
        lines.append(
            f"| {cause} | {count} | {where(these)} | {these[0]['error'][:160].replace('|', '/')} |"
        )
    return lines + [""] + stuck


def stuck_section(failed: list[dict]) -> list[str]:
    """The impacts whose disk stayed on the wall (state stuck): where, and the message."""
    stuck = [f for f in failed if state_of(f) == "stuck"]
    if not stuck:
        return []
    return [
        "## Disks that stayed on the wall",
        "",
        f"In {len(stuck)} impact{'' if len(stuck) == 1 else 's'} the disk had not left the "
        "wall (or the two disks had not parted) when the run reached its tmax: a physical "
        "outcome, not a failed run, with no rebound to measure, so no e or beta; they are "
        "not in the means and fits (`failed.csv`, state `stuck`). Where: "
        f"{where(stuck)}; the message: {stuck[0]['error'][:160]}.",
        "",
    ]


def drift_section(rows: list[dict]) -> list[str]:
    """Impacts whose energy drift exceeded the threshold: their time step was too large."""
    flagged = [r for r in rows if str(r["drift_exceeded"]) == "True"]
    if not flagged:
        return []
    worst = max(flagged, key=lambda r: abs(float(r["energy_drift"])))
    impacts = [
        {"lattice": r["study_lattice"], "gamma": r["gamma_deg"], "seed": r["seed"]} for r in flagged
    ]
    return [
        "## Inaccurate impacts",
        "",
        f"{len(flagged)} of the {len(rows)} impacts have an energy drift (change of the total "
        "energy over the initial kinetic energy) above the study's threshold (`--max-drift`, "
        "column `drift_exceeded` of impacts.csv); the largest is "
        f"{float(worst['energy_drift']):.3g} "
        f"at dt = {worst['dt']} R/c. Their time step is too large for them, and they are in the "
        f"tables and fits above. Where: {where(impacts)}.",
        "",
    ]


def wall_end_section(means: list[dict], wall_width: float) -> list[str]:
    """How many contacts felt the wall's ends."""
    near = [m for m in means if m["near_side"]]
    if not near:
        return []
    lines = [
        "## The wall's ends",
        "",
        f"This study's wall is {wall_width:g} R wide (docs/model.md's is 8 R), and the contact "
        "must not reach its fixed sides. At grazing angles the disk slides, and after the "
        "main contact skims the rough wall, over a long way. Contacts whose disk centre "
        "came within 1 R of a fixed side:",
        "",
        "| lattice | gamma | contacts near a side | impacts |",
        "|---|---|---|---|",
    ]
    lines += [
        f"| {m['study_lattice']} | {m['gamma_deg']:g} | {m['near_side']} | {m['samples']} |"
        for m in near
    ]
    lines += [
        "",
        "On a 16 R wall of the reading before today's default (the disk's density, sides "
        "and bottom held) 1 of 12 contacts came near a side at 80.5 "
        "degrees, and the mean e moved by 0.026 to 0.034 at 63.5 to 80.5 degrees (0.9 to "
        "1.6 standard errors), beta by at most 0.011 (random lattice, 12 samples: "
        "`python bench/wall_width.py` at c9a6597, docs/model.md; docs/wall_width.md has "
        "it with today's springs and held sides). "
        "The fits over the angles where at most 10 % of the contacts came near a side are "
        "among the fitting choices above (`angles` clear).",
        "",
    ]
    return lines


def tables_where(tables: str, preset: str) -> str:
    """Where a page's tables are and the command that remakes it from them."""
    if not tables:
        return ""
    return (
        f" (in `{tables}`, from which `python -m runner study {preset} --from-tables {tables}` "
        "makes this page again without the runs)"
    )
