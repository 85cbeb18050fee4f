"""What a finished study gives: tables, fits, figures and a results page."""

from __future__ import annotations

import csv
import json
import math
from collections import Counter
from pathlib import Path

from builder.run_options import RUN_OPTIONS
from builder.scene import SCENE_OPTIONS
from ground.errors import InputError
from ground.paths import ROOT

from . import binary_findings, binary_page, figures, grazing, normal_check, speed, speed_page
from .claims import claims
from .estimates import study_estimates
from .page import claims_section, fits_section, measures_section, nu_section, statistics_section
from .result import BINARY_FINITE, FINITE
from .sections import (  # noqa: F401 (failure_cause: the benchmarks' rows)
    SECTIONS,
    drift_section,
    failure_cause,
    failure_causes,
    failure_section,
    genuine,
    impact_state,
    outcome_note,
    state_of,
    tables_where,
    wall_end_section,
)
from .table import (
    MEAN_COLUMNS,
    TIMING_COLUMNS,
    TIMINGS,
    collect,
    mean_rows,
    rounded,
    table_columns,
    with_model_readings,
    write_csv,
)


def angle_span(rows: list[dict]) -> str:
    """The study's smallest and largest angle, as the page states them."""
    gammas = [float(r["gamma_deg"]) for r in rows] or [float("nan")]
    return f"{min(gammas):.1f} to {max(gammas):.1f}"


def angle_options(study: dict) -> str:
    """--cot-gamma's values if the study gave them, else --angles."""
    if study.get("cot_gamma"):
        return "--cot-gamma " + " ".join(f"{c:g}" for c in study["cot_gamma"])
    return f"--angles {study['angles']}"


def speed_options(study: dict) -> str:
    """--speeds if the study has a speed axis, else --vn."""
    if study.get("speeds"):
        return "--speeds " + " ".join(f"{v:g}" for v in study["speeds"])
    return f"--vn {study.get('vn', 0.1):g}"


def stop_rule(study: dict) -> str:
    """How the study's runs ended: the stop rule, or two disks' own (decks/binary.lmp)."""
    if study.get("target") == "disk":
        return "of two disks (parted for good)"
    return study["options"]["stop_rule"]


def made_by(study: dict, preset: str) -> str:
    """The command that runs the study again, every option spelled out: the
    grid, then each scene and run option the way its declaration says
    (builder.declared.Option.made_by_words; a binary study has no wall, a
    wall study no partner)."""
    grid = (
        f"python -m runner study {preset} --name {study['name']} --lattices "
        f"{' '.join(study['lattices'])} {angle_options(study)} --samples {study['samples']} "
        f"{speed_options(study)}"
    )
    scene = [option.made_by_words(study) for option in SCENE_OPTIONS if option.study]
    run = [option.made_by_words(study["options"]) for option in RUN_OPTIONS]
    return " ".join(word for word in (grid, *scene, *run) if word)


def speed_unit_name(study: dict) -> str:
    """The unit of the study's v_n (builder.scene.speed_unit)."""
    if study.get("speed_unit", "c") == "spring":
        return "d sqrt(ka / m) (the disk springs' sound speed)"
    return "c"


def wall_clock(study: dict) -> str:
    """How long the whole study took, where study.json records it."""
    clock = study.get("wall_clock")
    if not clock:
        return ""
    spent = clock.get("worker_seconds")
    split = ""
    if spent:
        total = sum(spent.values()) or 1.0
        split = "; its workers spent " + ", ".join(
            f"{100 * s / total:.0f} % in {WORKER_PHASE_NAMES[k]}" for k, s in spent.items()
        )
    return (
        f"; the whole study took {clock['seconds'] / 60:.1f} min of wall-clock time with "
        f"{clock['workers']} workers on {clock['cores']} cores ({clock['cpu']}){split}"
    )


# runner.study.WORKER_PHASES, as the results page names them
WORKER_PHASE_NAMES = {
    "build": "building scenes",
    "lammps": "LAMMPS",
    "rest": "analysis and files",
}


# The pages that compare a preset's committed tables with an earlier run of
# the same seeds (bench/paper_ensemble.py), by preset.
EARLIER_RUNS = {"paper": "benchmarks/paper_ensemble.md"}


def earlier_runs_section(preset: str) -> list[str]:
    """Where the page's e and beta are compared with an earlier run of its seeds."""
    if preset not in EARLIER_RUNS:
        return []
    return [
        "Against the run before, seed by seed and in distribution (each impact's e and "
        "beta move by round-off where the code sums its forces in another order, and "
        "the contact's chaos grows some of those): "
        f"[{EARLIER_RUNS[preset]}]({EARLIER_RUNS[preset]}).",
        "",
    ]


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
    extra: dict[str, list[str]] | None = None,
    sections: tuple[str, ...] | None = None,
) -> str:
    """The results page (markdown) of a study from its tables and estimates.

    ``extra``: sections made beforehand, by name (grazing, readings);
    ``sections``: which of ``SECTIONS`` the page has, in order (default:
    all; one that has nothing to say is left out either way)."""
    where_tables = tables_where(tables, preset)
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
        f"from {angle_span(rows)} degrees; {samples}; "
        f"v_n = {study['vn']} {speed_unit_name(study)}; "
        f"velocity Verlet, dt = {study['options']['dt']} R/c, stop rule "
        f"{stop_rule(study)}. {outcome_note(failed)}{drift_note}. LAMMPS time "
        f"{seconds / 3600:.2f} core-hours{wall_clock(study)}. "
        f"Tables{where_tables}: `impacts.csv` (one row per impact), "
        "`means.csv` (means per lattice and angle, with their seed-bootstrap errors "
        "`*_seed_sd`), `fits.json` (the fits, the model-free measures and the claims below, "
        "with their errors), `failed.csv`. "
        f"Made by `{made_by(study, preset)}`.",
        "",
    ]
    made = {
        "earlier_runs": lambda: earlier_runs_section(preset),
        "statistics": lambda: statistics_section(fits),
        "claims": lambda: claims_section(fits),
        "fits": lambda: fits_section(fits),
        "measures": lambda: measures_section(fits, figure_dir),
        "nu": lambda: nu_section(fits, study, rows, means),
        "wall_ends": lambda: wall_end_section(means, study.get("wall_width", 8.0)),
    }
    for name in sections or SECTIONS:
        lines += made[name]() if name in made else (extra or {}).get(name, [])
    lines += [
        "## Figures",
        "",
        "Error bars: the seed-bootstrap errors of the per-angle means. Solid lines: the "
        "measured-way fits; dashed: the paper's way.",
        "",
    ]
    for name, title in (
        (
            "beta_random_triangular",
            "beta against cot gamma, random and triangular, with Walton's fits",
        ),
        ("e", "e against cot gamma"),
        ("beta_compliant", "beta against cot gamma, random lattice, with the compliant model"),
        ("beta_square", "beta against cot gamma, square lattices, with Walton's fits"),
    ):
        lines += [f"![{title}]({figure_dir}/{name}.png)", "", f"*{title}*", ""]
    lines += drift_section(rows) + failure_section(failed)
    return "\n".join(lines).rstrip("\n") + "\n"


def read_failure(job: dict) -> dict:
    """A failed impact's failed.json, with its state (failed, or stuck: its
    disk stayed on the wall); a damaged one is a failure of its own cause."""
    path = Path(job["folder"]) / "failed.json"
    try:
        failure = json.loads(path.read_text())
        failure["state"] = failure.get("state") or impact_state(failure["error"])
        return failure
    except (ValueError, TypeError, KeyError) as error:
        return {
            **job,
            "state": "failed",
            "error": f"unreadable failed.json ({type(error).__name__})",
        }


# failed.csv: the impacts without a result; state: failed (the run did not go
# as asked) or stuck (the disk had not left the wall by tmax: analysis.sections)
FAILED_COLUMNS = ("lattice", "seed", "gamma", "vn", "state", "error")


def record_timings(study, rows: list[dict]) -> dict:
    """timings.csv in the study's folder (each finished impact's LAMMPS
    seconds), and their sum in its study.json (lammps_seconds, which the page
    states and which the tables' copy of study.json keeps); returns study.json."""
    write_csv(rows, study.folder / TIMINGS, TIMING_COLUMNS)
    path = study.folder / "study.json"
    info = json.loads(path.read_text())
    info["lammps_seconds"] = round(sum(float(r["wall_seconds"] or 0.0) for r in rows), 1)
    path.write_text(json.dumps(info, indent=1))
    return info


def public_record(info: dict) -> str:
    """study.json as a study's tables keep it: without the grid its study file
    gave (runs' own record, runner.study.Study.source)."""
    return json.dumps({k: v for k, v in info.items() if k != "source"}, indent=1)


def report(
    study,
    resamples: int = 200,
    page: Path | None = None,
    preset: str = "paper",
    tables: Path | None = None,
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
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
    readings : dict of str to pathlib.Path, optional
        Table folders of the same study under other options, by name, which a
        grazing page tabulates (``grazing.readings_section``).
    sections : tuple of str, optional
        Which of ``SECTIONS`` the results page has, in order (default: all).

    Returns
    -------
    dict
        ``rows`` (finished impacts), ``failed`` (failed impacts), ``fits``
        (``fit_all``, as written to fits.json) and ``page`` (results.md's path).
    """
    jobs = study.jobs()
    rows = collect([(j["lattice"], Path(j["folder"])) for j in jobs])
    failed = [read_failure(j) for j in jobs if (Path(j["folder"]) / "failed.json").exists()]
    info = record_timings(study, rows)
    summary = render(
        info,
        rows,
        failed,
        study.folder,
        page or study.folder / "results.md",
        resamples,
        preset,
        shown_path(tables) if tables is not None else "",
        readings,
        sections,
    )
    if tables is not None:
        tables.mkdir(parents=True, exist_ok=True)
        for name in ("impacts.csv", "means.csv", "fits.json", "speed.json", "failed.csv"):
            if (study.folder / name).exists():  # a speed study has speed.json instead of fits
                (tables / name).write_bytes((study.folder / name).read_bytes())
        (tables / "study.json").write_text(public_record(info))
    return summary


def report_from_tables(
    tables: Path,
    page: Path,
    resamples: int = 200,
    preset: str = "paper",
    out: Path | None = None,
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
) -> dict:
    """The page and figures of a study from its tables alone (docs/results/).

    Parameters
    ----------
    tables : pathlib.Path
        A folder with impacts.csv, failed.csv and study.json (``report``'s
        ``tables``); read only, unless it is ``out``.
    page : pathlib.Path
        Where the page goes; the figures go into ``figures/`` beside it.
    resamples, preset, readings, sections
        As for ``report``.
    out : pathlib.Path, optional
        Where the tables (with means.csv and fits.json made again) and
        study.json go; default ``tables`` itself.

    Returns
    -------
    dict
        As ``report``.
    """

    info, rows, failed = read_tables(tables)
    out = Path(out) if out is not None else Path(tables)
    out.mkdir(parents=True, exist_ok=True)
    (out / "study.json").write_text(public_record(info))
    return render(
        info,
        rows,
        failed,
        out,
        page,
        resamples,
        preset,
        shown_path(tables),
        readings,
        sections,
    )


def read_tables(tables: Path) -> tuple[dict, list[dict], list[dict]]:
    """study.json, impacts.csv's rows and failed.csv's of a study's tables.

    Tables from elsewhere are checked as result.json files are: a number that
    is missing or not finite stops the page, before anything is written.

    Raises
    ------
    ground.errors.InputError
        If the folder holds no study's tables, or a row lacks a number.
    """

    def read(name: str) -> list[dict]:
        with (tables / name).open() as handle:
            return list(csv.DictReader(handle))

    try:
        info = json.loads((tables / "study.json").read_text())
        rows, failed = read("impacts.csv"), read("failed.csv")
        rows = [with_model_readings(row) for row in rows]
        for failure in failed:  # failed.csv from before its state column
            failure["state"] = state_of(failure)
        if "lammps_seconds" not in info:  # tables whose rows had their seconds
            info["lammps_seconds"] = round(sum(float(r.get("wall_seconds") or 0) for r in rows), 1)
        for line, row in enumerate(rows, start=2):
            finite = BINARY_FINITE if row.get("target") == "disk" else FINITE
            # a table's row has no time (timings.csv, study.json's lammps_seconds)
            finite = [k for k in finite if k != "wall_seconds"]
            bad = [k for k in finite if not math.isfinite(float(row.get(k) or "nan"))]
            if bad:
                raise ValueError(f"line {line}: {', '.join(bad)} not a finite number")
    except (OSError, ValueError, KeyError) as error:
        raise InputError(f"--from-tables: {tables} holds no study's tables ({error})") from None
    return info, rows, failed


def tidy_tables(tables: Path) -> None:
    """A study's tables in this version's format, from themselves alone (no
    run, nothing recomputed): impacts.csv without wall-clock seconds (their
    sum into study.json's lammps_seconds), failed.csv with each impact's
    state, the numbers of means.csv, fits.json and speed.json to
    ``TABLE_DIGITS``. Tables already so are left byte for byte."""
    info, rows, failed = read_tables(tables)
    write_csv(rows, tables / "impacts.csv", table_columns(rows))
    write_csv(failed, tables / "failed.csv", FAILED_COLUMNS)
    (tables / "study.json").write_text(public_record(info))
    if (tables / "fits.json").is_file():
        fits = rounded(json.loads((tables / "fits.json").read_text()))
        (tables / "fits.json").write_text(json.dumps(fits, indent=1) + "\n")
    if (tables / "speed.json").is_file():
        numbers = rounded(json.loads((tables / "speed.json").read_text()))
        speed.write_json(numbers, tables / "speed.json")
    if (tables / "means.csv").is_file():
        with (tables / "means.csv").open() as handle:
            means = [{k: number_text(v) for k, v in r.items()} for r in csv.DictReader(handle)]
        write_csv(means, tables / "means.csv", MEAN_COLUMNS)


def number_text(text: str) -> str:
    """A table's cell with its number (a float's: with a point or an exponent)
    to ``TABLE_DIGITS``; integers and words as they are."""
    try:
        value = float(text)
    except ValueError:
        return text
    return str(rounded(value)) if any(c in text for c in ".eE") else text


def shown_path(path: Path) -> str:
    """A folder as the page names it: from the project's root where it is inside."""
    path = Path(path).resolve()
    return path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else str(path)


def figure_folder(page: Path, out: Path) -> Path:
    """Where a page's figures go: beside its tables, or, for a page in docs/,
    docs/figures/ (the paper's results.md) or docs/figures/<page>/ (the others,
    whose figures would otherwise take the paper's names)."""
    if page.parent == out:
        return out / "figures"
    return page.parent / "figures" / ("" if page.stem == "results" else page.stem)


def render(
    info: dict,
    rows: list[dict],
    failed: list[dict],
    out: Path,
    page: Path,
    resamples: int,
    preset: str,
    tables: str = "",
    readings: dict[str, Path] | None = None,
    sections: tuple[str, ...] | None = None,
) -> dict:
    """Tables into ``out``, the figures and the page (see ``report``)."""
    rows = sorted(
        rows,
        key=lambda r: (
            r["study_lattice"],
            float(r["vn"]),
            float(r["gamma_deg"]),
            float(r["seed"]),
        ),
    )
    write_csv(rows, out / "impacts.csv", table_columns(rows))
    write_csv(failed, out / "failed.csv", FAILED_COLUMNS)
    if info.get("speeds"):
        return render_speed(info, rows, failed, out, page, resamples, preset, tables)
    fits, errors = study_estimates(rows, resamples)
    fits["claims"] = claims(fits)
    # what the tables keep, and the page says, to the digits every CPU agrees on
    fits, errors = rounded(fits), rounded(errors)
    means = rounded(mean_rows(rows, errors))
    figure_dir = figure_folder(page, out)
    shown_figures = figure_dir.relative_to(page.parent).as_posix()
    extra = {}
    if grazing.has_grazing_angles(rows):  # past the paper's 80.5 degrees
        check = normal_check.robustness(rows, resamples)
        fits["grazing"] = rounded(grazing.grazing_numbers(rows, resamples, check))
        grazing.draw(fits["grazing"], figure_dir)
        extra["grazing"] = grazing.grazing_section(fits["grazing"], shown_figures)
        others = {name: read_tables(folder) for name, folder in (readings or {}).items()}
        extra["readings"] = grazing.readings_section(info, others, resamples)
    if info.get("target") == "disk":  # two disks: beside the same disks on the wall
        loaded = {name: read_tables(folder) for name, folder in (readings or {}).items()}
        walls = {n: tables[1] for n, tables in loaded.items() if tables[0].get("target") != "disk"}
        pairs = {n: tables[1] for n, tables in loaded.items() if tables[0].get("target") == "disk"}
        fits["normals"] = rounded(binary_page.normal_checks(rows, walls, pairs, resamples))
        fits["wall_comparison"] = rounded(
            {name: binary_page.comparison(rows, wall, resamples) for name, wall in walls.items()}
        )
        for name, numbers in fits["wall_comparison"].items():
            binary_page.draw(numbers, figure_dir, name)
        extra["wall_comparison"] = binary_page.section(
            fits["wall_comparison"], shown_figures, fits["normals"]
        )
        extra["normals"] = normal_check.section(fits["normals"])
        if grazing.has_grazing_angles(rows):  # the walls' e > 1 beside the pairs'
            fits["wall_grazing"] = {}
            for name, wall in walls.items():
                paired = binary_page.paired_rows(rows, wall)[1]
                fits["wall_grazing"][name] = rounded(
                    grazing.grazing_numbers(
                        paired, resamples, normal_check.robustness(paired, resamples)
                    )
                )
        extra["findings"] = binary_findings.findings_section(fits, info)
    write_csv(means, out / "means.csv", MEAN_COLUMNS)
    (out / "fits.json").write_text(json.dumps(fits, indent=1) + "\n")
    seconds = info["lammps_seconds"]
    # a sample is complete when every impact of it is done or failed
    per_sample = len(info["lattices"]) * info["angles"]
    finished = Counter(int(float(r["seed"])) for r in rows)
    finished.update(int(float(f["seed"])) for f in failed)
    samples_done = sum(count >= per_sample for count in finished.values())
    figures.draw(means, fits, figure_dir)
    page.write_text(
        results_page(
            info,
            rows,
            means,
            fits,
            shown_figures,
            failed,
            seconds,
            samples_done,
            preset,
            tables,
            extra,
            sections,
        )
    )
    return summary(rows, failed, fits, page)


def summary(rows: list[dict], failed: list[dict], numbers: dict, page: Path) -> dict:
    """What ``report`` returns: counts, failure causes, the page's numbers."""
    return {
        "rows": len(rows),
        "failed": len(genuine(failed)),
        "stuck": len(failed) - len(genuine(failed)),
        "causes": failure_causes(failed),
        "drift_exceeded": sum(str(r["drift_exceeded"]) == "True" for r in rows),
        "fits": numbers,
        "page": str(page),
    }


def render_speed(
    info: dict,
    rows: list[dict],
    failed: list[dict],
    out: Path,
    page: Path,
    resamples: int,
    preset: str,
    tables: str,
) -> dict:
    """A study with a speed axis: speed.json, the figures and its page."""
    numbers = rounded(speed.estimates(rows, resamples))
    speed.write_json(numbers, out / "speed.json")
    figure_dir = figure_folder(page, out)
    speed_page.draw(numbers, figure_dir)
    page.write_text(
        speed_page.page(
            info,
            rows,
            failed,
            numbers,
            figure_dir.relative_to(page.parent).as_posix(),
            made_by(info, preset),
            tables,
            preset,
        )
    )
    return summary(rows, failed, numbers, page)
