"""The fact sensitivity page (analysis.kinds.fact_sensitivity's numbers): the
facts at every point of the sweep, and their figure."""

from __future__ import annotations

from pathlib import Path

from analysis.kinds.fact_sensitivity import AXES, FACTS, facts, label, points
from analysis.kinds.readings import Setup
from ground.gate import write_figure

from .render import render
from .text import markdown_table

TITLE = "How the facts move with speed and roughness"
FIGURE = "fact_sensitivity.png"


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
    write_figure(fig, path, 110)
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
