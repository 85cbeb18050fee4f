"""The grazing sections of a results page (e at grazing incidence: its peak
and e > 1; analysis.grazing's numbers), its figure, and the table of the
same study under other readings. The prose: pages/templates/grazing.md.j2."""

from __future__ import annotations

from analysis.grazing import LOOK_ELSEWHERE_RESAMPLES, SIGNIFICANT
from ground.gate import write_figure

from .figures import LABELS, STYLE
from .render import macro


def grazing_section(numbers: dict, figure_dir: str) -> str:
    """The section on e at grazing incidence (Markdown)."""
    return macro(
        "grazing.md.j2", "grazing", numbers, figure_dir, LOOK_ELSEWHERE_RESAMPLES, SIGNIFICANT
    )


def readings_section(study: dict, readings: list[dict]) -> str:
    """The same grazing study under other readings, a row each
    (analysis.grazing.readings_numbers): what differs, the peak of e and
    whether e > 1 is significant, and the share of contacts whose disk
    centre came within 1 R of a held side."""
    return macro("grazing.md.j2", "readings", study, readings)


def draw(numbers: dict, folder) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    write_figure(fig, folder / "grazing_e.png", 120)
    plt.close(fig)
