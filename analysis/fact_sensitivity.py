"""How the paper's facts move with the impact speed and the roughness around
one reading (studies/fact_sensitivity.toml, docs/fact_sensitivity.md).

The study sweeps v_n and the roughness one at a time around its base (each
axis's first value); for each point, e (mean over cot gamma >= 1), Walton's
mu and beta0 fitted the paper's way (e 0.8, K 3), each with its
seed-bootstrap error (analysis.estimates, analysis.claims), and one figure of
how they move. These are the paper's stated values, not readings: the figure
shows how sensitive each fact is to them.
"""

from __future__ import annotations

from pathlib import Path

from .claims import claims
from .estimates import study_estimates
from .model_readings import COLUMNS as READING_COLUMNS
from .model_readings import FACTS as READING_FACTS
from .model_readings import fact_numbers
from .readings import Setup, markdown_table
from .render import render

TITLE = "How the facts move with speed and roughness"
FIGURE = "fact_sensitivity.png"
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


def draw(summaries: dict, base: tuple[float, float], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    vns = sorted({p[0] for p in summaries if p[1] == base[1]})
    roughnesses = sorted({p[1] for p in summaries if p[0] == base[0]})
    fig, axes = plt.subplots(len(FACTS), 2, figsize=(9, 7.5), sharex="col")
    for column, (axis, values, fixed) in enumerate(
        (
            ("v_n, in units of the reading's speed unit", vns, lambda v: (v, base[1])),
            ("roughness, R", roughnesses, lambda r: (base[0], r)),
        )
    ):
        for row, (name, _, _, paper) in enumerate(FACTS):
            ax = axes[row][column]
            shown = [
                (v, summaries[fixed(v)][name])
                for v in values
                if name in (summaries.get(fixed(v)) or {})
            ]
            if shown:
                ax.errorbar(
                    [v for v, _ in shown],
                    [f[0] for _, f in shown],
                    [f[1] for _, f in shown],
                    marker="o",
                    capsize=3,
                )
            ax.axhline(paper, color="grey", lw=0.8)
            ax.set_xscale("log")
            ax.set_xticks(values, [f"{v:g}" for v in values])
            ax.minorticks_off()
            ax.set_ylabel(name)
            if row == len(FACTS) - 1:
                ax.set_xlabel(axis)
    fig.suptitle(
        "Random disk: the paper's facts against its stated speed and roughness\n"
        "(error bars: seed-bootstrap sd, with the fit's systematic error where it fails; "
        "grey: the paper's values)"
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body; its figure goes into ``figures``."""
    study = setup.study
    shown = points(setup)
    summaries = {
        p: facts([r for r in rows if r["reading"] == label(dict(zip(AXES, p)))]) for p in shown
    }
    header = ["v_n", "roughness, R", "impacts", "failed", *(name for name, *_ in FACTS)]
    table = []
    for point in shown:
        s = summaries[point]
        cells = [f"{point[0]:g}", f"{point[1]:g}"]
        if s is None:
            table.append(cells + ["-"] * (len(header) - 2))
            continue
        cells += [str(s["impacts"]), str(s["failed"])]
        cells += [f"{s[n][0]:.3f} +- {s[n][1]:.3f}" if n in s else "-" for n, *_ in FACTS]
        table.append(cells)
    base = tuple(setup.choices[0][a] for a in AXES)
    draw(summaries, base, figures / FIGURE)
    return render(
        "fact_sensitivity.md.j2",
        wall=setup.named.get("wall"),
        model=setup.named.get("model"),
        angles=study["angles"],
        samples=study["samples"],
        dt=study["options"]["dt"],
        table=markdown_table(header, table),
        figures=setup.figures,
        figure=FIGURE,
        name=study["name"],
    )
