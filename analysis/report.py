"""What a finished study gives: tables, fits, figures and a results page."""

from __future__ import annotations

import csv
import json
import re
from collections import Counter
from pathlib import Path

import numpy as np

from . import figures
from .fits import bootstrap, fit_compliant, fit_walton, means, reduced_chi2
from .result import MAX_DRIFT
from .table import COLUMNS, MEAN_COLUMNS, collect, groups, mean_rows, near_the_ends, write_csv
from .theory import Compliant, compliant_beta, walton_beta

NUMBER = re.compile(r"(?:(?<!\d)[-+])?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|\b(?:nan|inf)\b")


def failure_cause(message: str) -> str:
    """A failure's message without LAMMPS's prefix, when and where it struck
    and its numbers: what failures are counted by."""
    text = re.sub(r"^ERROR( on proc \d+)?:\s*", "", message.strip())
    text = re.split(r",| at time | at step ", text, maxsplit=1)[0]
    return NUMBER.sub("#", text).strip()


def failure_causes(failed: list[dict]) -> dict[str, int]:
    """How many failures each cause has, most first."""
    return dict(Counter(failure_cause(f["error"]) for f in failed).most_common())


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
    """The failed impacts by cause: count, where, and one message in full."""
    if not failed:
        return []
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
    return lines + [""]


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


def fit_all(rows: list[dict], resamples: int = 200, compliant: bool = True) -> dict:
    """Walton's (mu, beta0) for every lattice; the compliant model's mu for the
    random lattice, with nu from the calibration and alpha = K from the inertia.

    Parameters
    ----------
    rows : list of dict
        One row per impact (impacts.csv, ``analysis.table.collect``).
    resamples : int
        Bootstrap resamples for the standard deviations (a tenth of them, at
        least 20, for the slower compliant fit).
    compliant : bool
        Fit the compliant model too (random lattice only).

    Returns
    -------
    dict
        Per study lattice with at least three angles of two samples:
        ``walton`` (mu, mu_sd, beta0, beta0_sd, K, chi2), ``nu``,
        ``inertia_ratio``, ``angles`` and, if fitted, ``compliant`` (mu, mu_sd,
        nu, alpha, chi2); plain floats, as fits.json holds them.
    """
    fits = {}
    for lattice in sorted({r["study_lattice"] for r in rows}):
        data = groups(rows, lattice)
        if len(data) < 3 or min(len(g) for g in data) < 2:
            continue
        inertia = np.mean(
            [float(r["disk_inertia_ratio"]) for r in rows if r["study_lattice"] == lattice]
        )
        nu = float(next(r["nu"] for r in rows if r["study_lattice"] == lattice))
        K = 1.0 + 1.0 / inertia
        (mu, beta0), (mu_sd, beta0_sd) = bootstrap(data, lambda d: fit_walton(d, K), resamples)
        m = means(data)
        fits[lattice] = {
            "walton": {
                "mu": mu,
                "mu_sd": mu_sd,
                "beta0": beta0,
                "beta0_sd": beta0_sd,
                "K": K,
                "chi2": reduced_chi2(m, walton_beta(m.psi, m.e, mu, beta0, K), 2),
            },
            "nu": nu,
            "inertia_ratio": inertia,
            "angles": len(data),
        }
        if lattice == "random" and compliant:
            (mu_c,), (mu_c_sd,) = bootstrap(
                data, lambda d: fit_compliant(d, nu, K), max(20, resamples // 10)
            )
            curve = [
                compliant_beta(p, Compliant(e=e, mu=mu_c, nu=nu, alpha=K))
                for p, e in zip(m.psi, m.e)
            ]
            fits[lattice]["compliant"] = {
                "mu": mu_c,
                "mu_sd": mu_c_sd,
                "nu": nu,
                "alpha": K,
                "chi2": reduced_chi2(m, curve, 1),
            }
    return json.loads(json.dumps(fits, default=float))


def model_verdicts(fits: dict) -> list[str]:
    """Which models describe which lattice's beta(psi), by chi2/dof (2: the line drawn)."""
    lines = []
    for lattice, fit in fits.items():
        for name, label in (("walton", "Walton's model"), ("compliant", "The compliant model")):
            if name in fit:
                chi2 = fit[name]["chi2"]
                verdict = (
                    "describes" if chi2 <= 2 else "does not describe, within the standard errors,"
                )
                lines.append(f"- {label} {verdict} the {lattice} lattice (chi2/dof = {chi2:.1f}).")
    return lines


def beta0_question(fits: dict) -> str:
    """Does beta0 depend on the Poisson ratio? The square lattices differ only in it."""
    a, b = fits.get("square_nu0.1"), fits.get("square_nu0.3")
    if not (a and b):
        return "This study has not both square lattices; the question needs them."
    difference = b["walton"]["beta0"] - a["walton"]["beta0"]
    sigma = np.hypot(a["walton"]["beta0_sd"], b["walton"]["beta0_sd"])
    z = abs(difference) / sigma
    verdict = (
        "depends on the Poisson ratio"
        if z > 3
        else "may depend on the Poisson ratio: a hint, not yet a finding (more samples settle it)"
        if z > 2
        else "shows no dependence on the Poisson ratio within the uncertainty"
    )
    return (
        f"beta0 = {a['walton']['beta0']:.3f} +- {a['walton']['beta0_sd']:.3f} for nu = 0.1 and "
        f"{b['walton']['beta0']:.3f} +- {b['walton']['beta0_sd']:.3f} for nu = 0.3: a difference "
        f"of {difference:+.3f} +- {sigma:.3f} ({abs(difference) / sigma:.1f} standard "
        f"deviations), so beta0 {verdict}."
    )


def clear_of_the_ends(rows: list[dict], means: list[dict]) -> list[dict]:
    """The rows at the angles where few of a lattice's contacts came within a
    radius of a fixed side of the wall (table.near_the_ends)."""
    clear = {(m["study_lattice"], m["gamma_deg"]) for m in means if not near_the_ends(m)}
    return [r for r in rows if (r["study_lattice"], float(r["gamma_deg"])) in clear]


def wall_end_section(means: list[dict], fits_clear: dict, wall_width: float) -> list[str]:
    """How many contacts felt the wall's ends, and the fits without those angles."""
    near = [m for m in means if m["near_side"]]
    if not near:
        return []
    lines = [
        "## The wall's ends",
        "",
        f"This study's wall is {wall_width:g} R wide (MODEL.md's is 8 R), and the contact "
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
        "On a 16 R wall of the default reading 1 of 12 contacts came near a side at 80.5 "
        "degrees, and the mean e moved by 0.026 to 0.034 at 63.5 to 80.5 degrees (0.9 to "
        "1.6 standard errors), beta by at most 0.011 (random lattice, 12 samples: "
        "`python bench/wall_width.py`, docs/benchmarks/wall_width.md, docs/model.md). "
        "Walton's fit over the angles where at most 10 % of the contacts came near a side, "
        "the results that MODEL.md's 8 R wall gives where its condition holds:",
        "",
        "| lattice | angles | Walton mu | Walton beta0 | chi2/dof |",
        "|---|---|---|---|---|",
    ]
    for lattice, fit in fits_clear.items():
        walton = fit["walton"]
        lines.append(
            f"| {lattice} | {fit['angles']} | {walton['mu']:.3f} +- {walton['mu_sd']:.3f} "
            f"| {walton['beta0']:.3f} +- {walton['beta0_sd']:.3f} | {walton['chi2']:.1f} |"
        )
    return lines + [""]


def wall_options(study: dict) -> str:
    """The study's reading of the wall as options (studies from before the
    readings had the disk's density, springs for its c, the sides held)."""
    n_wall = study.get("n_wall", "density")
    wall_ka = study.get("wall_ka", "same-c")
    return (
        f"--n-wall {n_wall} --wall-ka {wall_ka if isinstance(wall_ka, str) else f'{wall_ka:g}'} "
        f"--wall-fixed {study.get('wall_fixed', 'sides')}"
    )


def wall_clock(study: dict) -> str:
    """How long the whole study took, where study.json records it."""
    clock = study.get("wall_clock")
    if not clock:
        return ""
    return (
        f"; the whole study took {clock['seconds'] / 60:.1f} min of wall-clock time with "
        f"{clock['workers']} workers on {clock['cores']} cores ({clock['cpu']})"
    )


def results_page(
    study: dict,
    rows: list[dict],
    means: list[dict],
    fits: dict,
    figure_dir: str,
    failed: list[dict],
    seconds: float,
    samples_done: int,
    fits_clear: dict | None = None,
    preset: str = "paper",
    tables: str = "",
) -> str:
    tables_where = (
        f" (in `{tables}`, from which `python -m runner study {preset} --from-tables {tables}` "
        "makes this page again without the runs)"
        if tables
        else ""
    )
    drifted = sum(str(r["drift_exceeded"]) == "True" for r in rows)
    drift_note = f"; {drifted} drifted above the energy threshold (below)" if drifted else ""
    samples = (
        f"{study['samples']} samples each"
        if samples_done >= study["samples"]
        else f"{samples_done} of the study's {study['samples']} samples complete "
        "(it resumes where it stopped)"
    )
    lines = [
        f"# Results: study `{study['name']}`",
        "",
        f"{len(rows)} impacts: lattices {', '.join(study['lattices'])}; {study['angles']} angles "
        f"from 5.7 to 80.5 degrees; {samples}; v_n = {study['vn']} c; "
        f"velocity Verlet, dt = {study['options']['dt']} R/c, stop rule "
        f"{study['options']['stop_rule']}. {len(failed)} impact{'' if len(failed) == 1 else 's'} "
        f"failed{drift_note}. LAMMPS time "
        f"{seconds / 3600:.2f} core-hours{wall_clock(study)}. "
        f"Tables{tables_where}: `impacts.csv` (one row per impact), "
        "`means.csv` (means and standard errors per lattice and angle), `fits.json`, "
        "`failed.csv`. "
        f"Made by `python -m runner study {preset} --name {study['name']} --lattices "
        f"{' '.join(study['lattices'])} --angles {study['angles']} --samples {study['samples']} "
        f"--n-disk {study['n_disk']} --wall-width {study.get('wall_width', 8.0):g} "
        f"--contact-a {study.get('contact_a', 300.0):g} {wall_options(study)} "
        f"--dt {study['options']['dt']:g} "
        f"--max-drift {study['options'].get('max_drift', MAX_DRIFT):g}`.",
        "",
        "## Fitted parameters",
        "",
        "| lattice | nu | I/(MR^2) | Walton mu | Walton beta0 | Walton chi2/dof | compliant mu "
        "| compliant chi2/dof |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for lattice, fit in fits.items():
        walton = fit["walton"]
        compliant = fit.get("compliant")
        compliant_mu = (
            f"{compliant['mu']:.3f} +- {compliant['mu_sd']:.3f} | {compliant['chi2']:.1f}"
            if compliant
            else "- | -"
        )
        lines.append(
            f"| {lattice} | {fit['nu']:.3f} | {fit['inertia_ratio']:.4f} "
            f"| {walton['mu']:.3f} +- {walton['mu_sd']:.3f} "
            f"| {walton['beta0']:.3f} +- {walton['beta0_sd']:.3f} | {walton['chi2']:.1f} "
            f"| {compliant_mu} |"
        )
    lines += [
        "",
        "Uncertainties: standard deviations of the fits to bootstrap resamples of the "
        "samples at each angle. Walton's e is the measured mean e at each angle; K = 1 + "
        "MR^2/I from the measured inertia. The compliant model takes nu from the "
        "calibration (docs/materials.md). chi2/dof: the fit's weighted squared residuals "
        "per degree of freedom against the means per angle; about 1 if the model "
        "describes the data within its standard errors, well above 1 if it does not.",
        "",
        *model_verdicts(fits),
        "",
        "## Does beta0 depend on the Poisson ratio?",
        "",
        beta0_question(fits),
        "",
    ]
    if fits_clear and fits_clear.keys() >= {"square_nu0.1", "square_nu0.3"}:
        lines += [
            "Over the angles whose contacts stayed clear of the wall's ends (below): "
            + beta0_question(fits_clear),
            "",
        ]
    lines += [
        *wall_end_section(means, fits_clear or {}, study.get("wall_width", 8.0)),
        "## Figures",
        "",
    ]
    for name, title in (
        (
            "beta_random_triangular",
            "beta against cot gamma, random and triangular, with Walton's fits",
        ),
        ("e", "e against cot gamma"),
        ("beta_compliant", "beta against cot gamma, random lattice, with the compliant model"),
        ("beta_square", "beta against cot gamma, square lattices (nu = 0.1 and 0.3)"),
    ):
        lines += [f"![{title}]({figure_dir}/{name}.png)", "", f"*{title}*", ""]
    lines += drift_section(rows) + failure_section(failed)
    return "\n".join(lines).rstrip("\n") + "\n"


def read_failure(job: dict) -> dict:
    """A failed impact's failed.json; a damaged one is a failure of its own cause."""
    path = Path(job["folder"]) / "failed.json"
    try:
        failure = json.loads(path.read_text())
        failure["error"]  # noqa: B018 -- must have one
        return failure
    except (ValueError, TypeError, KeyError) as error:
        return {**job, "error": f"unreadable failed.json ({type(error).__name__})"}


FAILED_COLUMNS = ("lattice", "seed", "gamma", "error")


def report(
    study,
    resamples: int = 200,
    page: Path | None = None,
    preset: str = "paper",
    tables: Path | None = None,
) -> dict:
    """Write impacts.csv, means.csv, fits.json, failed.csv, figures/ and results.md for a study.

    Parameters
    ----------
    study : runner.study.Study
        The study, with its folder under runs/.
    resamples : int
        Bootstrap resamples of the fits.
    page : pathlib.Path, optional
        Where results.md goes (default: the study's folder); the figures go
        into ``figures/`` beside it.
    preset : str
        The preset the study was run from, for the command on the page.
    tables : pathlib.Path, optional
        A folder that gets a copy of the tables and study.json, from which
        ``report_from_tables`` remakes the page (docs/results/ for the paper).

    Returns
    -------
    dict
        ``rows`` (finished impacts), ``failed`` (failed impacts), ``fits``
        (``fit_all``, as written to fits.json) and ``page`` (results.md's path).
    """
    jobs = study.jobs()
    rows = collect([(j["lattice"], Path(j["folder"])) for j in jobs])
    failed = [read_failure(j) for j in jobs if (Path(j["folder"]) / "failed.json").exists()]
    info = json.loads((study.folder / "study.json").read_text())
    summary = render(
        info,
        rows,
        failed,
        study.folder,
        page or study.folder / "results.md",
        resamples,
        preset,
        shown_path(tables) if tables is not None else "",
    )
    if tables is not None:
        tables.mkdir(parents=True, exist_ok=True)
        for name in ("impacts.csv", "means.csv", "fits.json", "failed.csv", "study.json"):
            (tables / name).write_bytes((study.folder / name).read_bytes())
    return summary


def report_from_tables(
    tables: Path,
    page: Path,
    resamples: int = 200,
    preset: str = "paper",
    out: Path | None = None,
) -> dict:
    """The page and figures of a study from its tables alone (docs/results/).

    Parameters
    ----------
    tables : pathlib.Path
        A folder with impacts.csv, failed.csv and study.json (``report``'s
        ``tables``); read only, unless it is ``out``.
    page : pathlib.Path
        Where the page goes; the figures go into ``figures/`` beside it.
    resamples, preset
        As for ``report``.
    out : pathlib.Path, optional
        Where the tables (with means.csv and fits.json made again) and
        study.json go; default ``tables`` itself.

    Returns
    -------
    dict
        As ``report``.
    """

    def read(name: str) -> list[dict]:
        with (tables / name).open() as handle:
            return list(csv.DictReader(handle))

    info = json.loads((tables / "study.json").read_text())
    out = Path(out) if out is not None else Path(tables)
    out.mkdir(parents=True, exist_ok=True)
    if out.resolve() != Path(tables).resolve():
        (out / "study.json").write_bytes((tables / "study.json").read_bytes())
    return render(
        info,
        read("impacts.csv"),
        read("failed.csv"),
        out,
        page,
        resamples,
        preset,
        shown_path(tables),
    )


def shown_path(path: Path) -> str:
    """A folder as the page names it: from the project's root where it is inside."""
    root = Path(__file__).resolve().parents[1]
    path = Path(path).resolve()
    return path.relative_to(root).as_posix() if path.is_relative_to(root) else str(path)


def render(
    info: dict,
    rows: list[dict],
    failed: list[dict],
    out: Path,
    page: Path,
    resamples: int,
    preset: str,
    tables: str = "",
) -> dict:
    """Tables into ``out``, the figures and the page (see ``report``)."""
    rows = sorted(rows, key=lambda r: (r["study_lattice"], float(r["gamma_deg"]), float(r["seed"])))
    write_csv(rows, out / "impacts.csv", COLUMNS)
    write_csv(failed, out / "failed.csv", FAILED_COLUMNS)
    means = mean_rows(rows)
    write_csv(means, out / "means.csv", MEAN_COLUMNS)
    fits = fit_all(rows, resamples)
    (out / "fits.json").write_text(json.dumps(fits, indent=1) + "\n")
    figure_dir = page.parent / "figures" if page.parent != out else out / "figures"
    seconds = sum(float(r["wall_seconds"]) for r in rows)
    # a sample is complete when every impact of it is done or failed
    per_sample = len(info["lattices"]) * info["angles"]
    finished = Counter(int(float(r["seed"])) for r in rows)
    finished.update(int(float(f["seed"])) for f in failed)
    samples_done = sum(count >= per_sample for count in finished.values())
    fits_clear = fit_all(clear_of_the_ends(rows, means), resamples, compliant=False)
    figures.draw(means, fits, figure_dir, fits_clear)
    page.write_text(
        results_page(
            info,
            rows,
            means,
            fits,
            figure_dir.relative_to(page.parent).as_posix(),
            failed,
            seconds,
            samples_done,
            fits_clear,
            preset,
            tables,
        )
    )
    return {
        "rows": len(rows),
        "failed": len(failed),
        "causes": failure_causes(failed),
        "drift_exceeded": sum(str(r["drift_exceeded"]) == "True" for r in rows),
        "fits": fits,
        "page": str(page),
    }
