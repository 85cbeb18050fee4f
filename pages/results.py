"""The results page of one study (pages.kinds' results, grazing and binary
kinds): its first lines, then its sections in the order of
pages.sections.SECTIONS, the figures, the inaccurate and failed impacts.
The prose: pages/templates/results/."""

from __future__ import annotations

from analysis import poisson, table
from analysis.impact.failures import drifted, outcome
from analysis.statistics import claims, fit_verdicts, measures, sliding

from .command import made_by
from .render import macro, render
from .sections import SECTIONS, section_text

# The sections every results page may have, each a template of
# pages/templates/results/ (the others come from the page's kind).
OWN = ("earlier_runs", "statistics", "claims", "fits", "measures", "nu", "wall_ends")


def own_section(name: str, study: dict, rows: list[dict], means: list[dict], fits: dict,
                figures: str, preset: str) -> str:  # fmt: skip
    """One of ``OWN``'s sections (Markdown, ending with an empty line, or "")."""
    if name == "wall_ends":
        near = [m for m in means if m["near_side"]]
        return macro("sections.md.j2", "wall_ends", near, study.get("wall_width", 8.0))
    return render(
        f"results/{name}.md.j2",
        preset=preset,
        fits=fits,
        claims=fits.get("claims") or claims.claims(fits),
        same=claims.SAME,
        differs=claims.DIFFERS,
        differ=poisson.DIFFER,
        near=claims.NEAR,
        described=fit_verdicts.described(fits) if fits["lattices"] else {},
        failing=fit_verdicts.failing(fits),
        sliding=fit_verdicts.mu_eff_table(fits) if fits["lattices"] else [],
        p=poisson.poisson_pair(fits, study, rows, means) if name == "nu" else None,
        branch_p=sliding.BRANCH_P,
        e_normal_psi=measures.E_NORMAL_PSI,
        beta_normal_psi=measures.BETA_NORMAL_PSI,
        grazing_angles=measures.GRAZING_ANGLES,
        near_side=table.NEAR_SIDE,
        near_side_share=table.NEAR_SIDE_SHARE,
        figures=figures,
    )


def angle_span(rows: list[dict], failed: list[dict]) -> tuple[float, float]:
    """The angles the page's impacts ran at, lowest and highest: the
    finished impacts', or where every impact failed, the failed ones'."""
    gammas = [float(r["gamma_deg"]) for r in rows] or [float(f["gamma"]) for f in failed]
    if not gammas:
        raise ValueError("a results page needs at least one impact, finished or failed")
    return min(gammas), max(gammas)


def results_page(
    study: dict,
    rows: list[dict],
    means: list[dict],
    fits: dict,
    figure_dir: str,
    failed: list[dict],
    seconds: float,
    samples_done: int,
    preset: str = "paper",
    tables: str = "",
    extra: dict[str, list[str] | str] | None = None,
    sections: tuple[str, ...] | None = None,
) -> str:
    """The results page (Markdown) of a study from its tables and estimates.

    ``extra``: the sections of the page's kind, by name (grazing, readings,
    ...); ``sections``: which of ``SECTIONS`` the page has, in order
    (default: all; one that has nothing to say is left out either way)."""
    extra = extra or {}
    body = "".join(
        own_section(name, study, rows, means, fits, figure_dir, preset)
        if name in OWN
        else section_text(extra.get(name, ""))
        for name in sections or SECTIONS
    )
    page = render(
        "results/page.md.j2",
        info=study,
        rows=rows,
        span=angle_span(rows, failed),
        samples_done=samples_done,
        outcome=outcome(failed),
        drift=drifted(rows),
        seconds=seconds,
        tables=tables,
        preset=preset,
        made_by=made_by(study, preset),
        # the steps dt auto took (the rows' own)
        steps_used=sorted({float(r["dt"]) for r in rows if r.get("dt") not in (None, "")}),
        body=body,
        figures=figure_dir,
    )
    return page.rstrip("\n") + "\n"
