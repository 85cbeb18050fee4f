"""How the paper's facts move with the impact speed and the roughness around
one reading (studies/fact_sensitivity.toml, docs/studies/fact_sensitivity/fact_sensitivity.md).

The study sweeps v_n and the roughness one at a time around its base (each
axis's first value); for each point, e (mean over cot gamma >= 1), Walton's
mu and beta0 fitted the paper's way (e 0.8, K 3), each with its
seed-bootstrap error (analysis.statistics.estimates, analysis.statistics.claims), and one figure of
how they move. These are the paper's stated values, not readings: the figure
shows how sensitive each fact is to them.
"""

from __future__ import annotations

from ..statistics.claims import claims
from ..statistics.estimates import study_estimates
from .model_readings import COLUMNS as READING_COLUMNS
from .model_readings import FACTS as READING_FACTS
from .model_readings import fact_numbers
from .readings import Setup

FACTS = READING_FACTS[:3]  # e, mu, beta0
AXES = ("vn", "roughness")
COLUMNS = (*READING_COLUMNS, "roughness", "study_reading")


def label(choice: dict) -> str:
    """A point's reading: ``vn0.05_roughness0.03``."""
    return f"vn{choice['vn']:g}_roughness{choice['roughness']:g}"


def row_fields(choice: dict, setup: Setup) -> dict:
    """What each row of a point records besides its impact's columns."""
    reading = f"{setup.named.get('wall', '-')}/{setup.named.get('model', '-')}"
    return {"vn": choice["vn"], "roughness": choice["roughness"], "study_reading": reading}


def points(setup: Setup) -> list[tuple[float, float]]:
    """(v_n, roughness) of every point, the table's order: each axis's values in
    increasing order with the other at the base (its first value), the base once."""
    base = setup.choices[0]
    out = []
    for axis in AXES:
        for value in sorted({c[axis] for c in setup.choices}):
            out.append(tuple(value if a == axis else base[a] for a in AXES))
    return list(dict.fromkeys(out))


def facts(rows: list[dict]) -> dict | None:
    """The counts of a point's impacts, and its facts if it has three angles or more."""
    if not rows:
        return None
    done = [r for r in rows if not r.get("error")]
    out = {"impacts": len(rows), "failed": len(rows) - len(done)}
    if len({r["gamma_deg"] for r in done}) < 3:
        return out
    table = claims(study_estimates(done, compliant=False)[0])
    for name, number in fact_numbers(table, FACTS).items():
        out[name] = (number["value"], number["error"]) if number else (float("nan"),) * 2
    return out
