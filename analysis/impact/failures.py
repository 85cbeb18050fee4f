"""Impacts without a result, classified: stuck (the disk stayed on the wall,
a physical outcome) or failed (the run did not go as asked), and the
failures' causes (pages.sections states them on a page)."""

from __future__ import annotations

import re
from collections import Counter

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


def by_angle(impacts: list[dict]) -> list[dict]:
    """Impacts (each with lattice, gamma, seed) grouped by lattice and angle,
    in that order, each group's seeds sorted."""
    groups: dict[tuple, list] = {}
    for impact in impacts:
        groups.setdefault((impact["lattice"], float(impact["gamma"])), []).append(impact["seed"])
    return [
        {"lattice": lattice, "gamma": gamma, "seeds": sorted(seeds)}
        for (lattice, gamma), seeds in sorted(groups.items())
    ]


def outcome(failed: list[dict]) -> dict:
    """The impacts without a result, as a page states them: the failed ones
    by cause (count, where, the first's message) and those that stayed on
    the wall (count, where, the first's message)."""
    lost = genuine(failed)
    stuck = [f for f in failed if state_of(f) == "stuck"]
    causes = []
    for cause, count in failure_causes(lost).items():
        these = [f for f in lost if failure_cause(f["error"]) == cause]
        causes.append(
            {"cause": cause, "count": count, "where": by_angle(these), "message": these[0]["error"]}
        )
    return {
        "failed": len(lost),
        "causes": causes,
        "stuck": len(stuck),
        "stuck_where": by_angle(stuck),
        "stuck_message": stuck[0]["error"] if stuck else "",
    }


def drifted(rows: list[dict]) -> dict:
    """The impacts whose energy drift exceeded the study's threshold
    (``drift_exceeded``): how many of all, the largest drift, its dt, where."""
    flagged = [r for r in rows if str(r["drift_exceeded"]) == "True"]
    worst = max(flagged, key=lambda r: abs(float(r["energy_drift"])), default=None)
    impacts = [
        {"lattice": r["study_lattice"], "gamma": r["gamma_deg"], "seed": r["seed"]} for r in flagged
    ]
    return {
        "count": len(flagged),
        "impacts": len(rows),
        "largest": float(worst["energy_drift"]) if worst else None,
        "dt": worst["dt"] if worst else None,
        "where": by_angle(impacts),
    }
