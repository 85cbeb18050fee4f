"""The model readings' page (analysis.kinds.model_readings's numbers): every
reading's five facts, their misses and the rule's pick."""

from __future__ import annotations

from pathlib import Path

from analysis.kinds.model_readings import FACTS, away, rank_summaries, summaries_of
from analysis.kinds.readings import Setup

from .render import render
from .text import markdown_table

TITLE = "The readings of the model"


def page(rows: list[dict], setup: Setup, figures: Path) -> str:
    """The page's body (no figure): every reading on all its seeds, ranked."""
    study, rerun = setup.study, setup.rerun
    summaries = summaries_of(rows, setup)
    shown = list(summaries)
    ranking = rank_summaries(summaries)
    header = ["wall", "model", "impacts", "failed"]
    header += [f"{name}" for name, *_ in FACTS]
    header += [
        "Walton chi2/dof",
        "misses (e, mu, beta0, share, side)",
        "total miss",
        "away from text",
    ]
    table = []
    for reading in ranking + [r for r in shown if r not in ranking]:
        s = summaries[reading]
        cells = [*reading.split("/"), str(s["impacts"]), str(s["failed"])]
        if "total" not in s:
            table.append(cells + ["-"] * (len(header) - len(cells) - 1) + [str(away(reading))])
            continue
        cells += [f"{s[name]['value']:.3f} +- {s[name]['error']:.3f}" for name, *_ in FACTS]
        cells += [
            f"{s['chi2']:.1f}",
            ", ".join(f"{s[name]['miss']:.2f}" for name, *_ in FACTS),
            f"{s['total']:.2f} +- {s['total_se']:.2f}",
            str(away(reading)),
        ]
        table.append(cells)
    best = None
    if ranking:
        wall, model = ranking[0].split("/")
        best = {"wall": wall, "model": model, **summaries[ranking[0]]}
    return render(
        "model_readings.md.j2",
        study=study,
        rerun=rerun,
        record=setup.record,
        table=markdown_table(header, table),
        best=best,
    )
