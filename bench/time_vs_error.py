"""Run time against error: LAMMPS settings and the reference, on the validation scenes.

    make bench          (python bench/time_vs_error.py --docs)
    python bench/time_vs_error.py [--out runs/bench] [--only WORD ...] [--summarise] [--docs]

The nine scenes of make validate (random, triangular and square lattices at
5.7, 45 and 80.4 degrees), each twice: with smooth surfaces, where e and beta
of an impact converge, for the error against the converged reference
(Suzuki, dt = 1e-3); and with the model's rough surfaces, which are chaotic
(reference/validate.py), for the wall time, the energy error and whether the
run survives. Settings: LAMMPS velocity Verlet over a range of time steps up
to where it fails; rRESPA with the contact alone on the inner level, over
outer and inner steps; the pair variant; and the reference's schemes
(Forest-Ruth at 1e-3 is the paper's). Writes time_vs_error.md, .png and .json
into runs/bench/ (with --docs into docs/benchmarks/, the committed ones) and
picks, for Verlet and for rRESPA, the largest step whose error stays below
1e-3 on every smooth scene, whose energy error stays below 5e-3 on every rough
one, and that survives every rough scene (for rRESPA the largest outer step,
then the largest inner one). The runs and their rows (rows.json, and
rows.partial.json, from which a killed sweep resumes) go under --out.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from pathlib import Path

import numpy as np

from analysis.impact.result import MAX_DRIFT
from bench.common import (
    bench_parser,
    loop_seconds,
    markdown_table,
    median,
    output_folder,
    refuse,
    write_report,
)
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from ground.checks import OutFolder
from ground.errors import InputError
from ground.gate import runs_folder, write_figure
from ground.launch import LammpsError
from reference.run import ReferenceOptions, Unstable, run_reference
from reference.validate import reference_runs, scenes
from runner.impact import run_scene
from runner.options import DEFAULT_DT, RunOptions

TOLERANCE = 1e-3  # on e and beta, smooth scenes
ENERGY_TOLERANCE = 5e-3  # rough scenes: the kinks of l give ~1e-3 at 2e-3 (drift_floor.md)
VERLET_STEPS = (1e-3, 2e-3, 3e-3, 4e-3, 6e-3, 8e-3, 1.2e-2, 1.6e-2)
# rRESPA: (outer step, contact steps per step): the contact at Verlet's 2e-3
# with the springs at 2 to 8 times that, at 1e-3, 1.7e-3, 2.5e-3 and 3e-3
RESPA_SPLITS = (
    (4e-3, 2),
    (5e-3, 2),
    (5e-3, 3),
    (6e-3, 3),
    (8e-3, 4),
    (1e-2, 5),
    (1.2e-2, 6),
    (1.6e-2, 8),
    (6e-3, 6),
    (8e-3, 8),
    (1e-2, 10),
    (1.2e-2, 4),
)
WORK = runs_folder() / "bench"  # --out's default: the runs and their rows
# What sets the drift and why --max-drift is 0.05; the numbers behind each
# claim are on the pages it names, made by the commands beside them.
DRIFT_NOTE = (
    "**The accuracy guard.** Every result.json records its energy drift (the change of the "
    "total energy over the initial kinetic energy) and is flagged (`drift_exceeded`, also a "
    f"column of impacts.csv) when it exceeds `--max-drift`, default {MAX_DRIFT:g} "
    "(`analysis.impact.result.MAX_DRIFT`); `python -m runner impact` and `run` then warn, "
    "naming dt."
    " **What sets the drift on rough scenes** ([drift_floor.md](drift_floor.md), `python "
    "bench/drift_floor.py --docs`): not the lever rule, which is the exact gradient of "
    "V0 exp(-a l) (docs/contact.md), but the kinks of l over the rough wall's valley "
    "vertices, where the force keeps its size and turns by the valley's angle. A step in "
    "which a point crosses one applies the wrong side's force for part of the step: an "
    "energy error (F_before - F_after).v dt (1/2 - theta), theta the crossing's place in the "
    "step, of first order in dt and of either sign, for fourth-order schemes too. So a rough "
    "impact's drift is a random walk whose scale halves with dt. On chaotic scenes the step's "
    "errors pick another trajectory from the chaotic spread "
    "(docs/benchmarks/validation_table.md), which only ensemble means can check: "
    "[step_ensemble_verlet.md](step_ensemble_verlet.md) "
    "(`python bench/step_ensemble.py --samples 100 --docs`). A whole study's worst drifts "
    "at the default step, run again at smaller steps: [drift_tail.md](drift_tail.md) "
    "(`python bench/drift_tail.py --impacts docs/studies/results/impacts.csv --docs`). A step too "
    "large for the scene stops the run: `python -m runner impact --gamma 60 --seed 3 --dt "
    "0.02` stretches a wall segment past the contact's reach."
)


def default_note(default: dict | None, verlet_best: dict | None) -> str:
    """The paragraph on the default step, from this table's rows of the default
    (runner.options.DEFAULT_DT) and of Verlet's pick."""
    text = (
        f"**The default is dt = {DEFAULT_DT:g}** (`runner.options.DEFAULT_DT`, the step of "
        "`--dt auto` at 800 disk points) on the default scene."
    )
    if default and verlet_best:
        text += (
            f" The criteria above admit {verlet_best['label'].split('dt=')[-1]}, with a "
            f"margin of {ENERGY_TOLERANCE / verlet_best['drift']:.1f}x on the energy; the "
            f"default keeps {ENERGY_TOLERANCE / default['drift']:.1f}x there and "
            f"{TOLERANCE / default['error']:.0f}x on e and beta, for a median loop of "
            f"{default['loop']:.2f} s per impact against {verlet_best['loop']:.2f} s."
        )
    return text + (
        " The ensemble means at the admitted step and at half of it agree over 100 seeds "
        "([step_ensemble_verlet.md](step_ensemble_verlet.md)), and the paper study's worst "
        "drifts at the default shrink with the step ([drift_tail.md](drift_tail.md))."
    )


def settings() -> list[tuple[str, str, object]]:
    """(label, kind, options) of every configuration, cheapest last within a family."""
    runs = [(f"verlet dt={dt:g}", "lammps", RunOptions(dt=dt)) for dt in VERLET_STEPS]
    runs += [
        (f"respa {n} dt={dt:g}", "lammps", RunOptions(dt=dt, integrator="respa", nrespa=n))
        for dt, n in RESPA_SPLITS
    ]
    runs += [("verlet dt=0.004 pair", "lammps", RunOptions(dt=4e-3, contact="pair"))]
    runs += [
        (
            "reference forest-ruth dt=0.001 (paper)",
            "reference",
            ReferenceOptions(integrator="forest-ruth", dt=1e-3),
        )
    ]
    return runs


def setting_word(text: str) -> str:
    """--only: a word that some setting's label contains."""
    if not text or not any(text in label for label, _, _ in settings()):
        raise argparse.ArgumentTypeError(
            "must be part of a setting's label (verlet, respa, pair, reference, dt=0.004, "
            f"...: the first column of time_vs_error.md), got {text!r}"
        )
    return text


setting_word.__name__ = "word"
setting_word.bad_values = ("", "no-such-setting")


def run_one(kind: str, options, folder: Path) -> dict:
    try:
        if kind == "lammps":
            return run_scene(folder, options)
        return run_reference(folder, options)
    except (LammpsError, Unstable) as error:
        return {"error": str(error)}


def measure(out: Path, only: list[str] | None) -> dict:
    # the nine scenes on the wall, which its committed page measured
    smooth, rough = scenes(roughness=0.0, two_disks=False), scenes(two_disks=False)
    references = reference_runs(smooth, out / "smooth")
    # Rows are kept as they come, so a killed sweep resumes where it stopped;
    # rows of other scenes (a changed default) are not resumed but run again.
    partial = out / "rows.partial.json"
    these = {
        f"{s}|{n}": asdict(spec)
        for s, specs in (("smooth", smooth), ("rough", rough))
        for n, spec in specs.items()
    }
    saved = json.loads(partial.read_text()) if partial.exists() else {}
    done = saved.get("rows", {}) if saved.get("scenes") == these else {}
    built = {}
    rows = {}
    for label, kind, options in settings():
        if only and not any(word in label for word in only):
            continue
        tag = label.replace(" ", "_").replace("=", "").replace("(", "").replace(")", "")
        for surface, specs in (("smooth", smooth), ("rough", rough)):
            for name, spec in specs.items():
                key = (label, surface, name)
                if "|".join(key) in done:
                    rows[key] = done["|".join(key)]
                    continue
                folder = out / surface / name / tag
                if (surface, name) not in built:
                    built[surface, name] = build_scene(spec)
                write_scene(built[surface, name], folder)
                result = run_one(kind, options, folder)
                row = {"surface": surface}
                if "error" in result:
                    row["error"] = result["error"]
                else:
                    row.update(
                        seconds=result["wall_seconds"],
                        steps=result["steps"],
                        drift=abs(result["energy_drift"]),
                    )
                    if kind == "lammps":  # the time inside LAMMPS's run loops
                        row["loop"] = loop_seconds(folder / "log.lammps")[0]
                    if surface == "smooth":
                        row.update(
                            de=abs(result["e"] - references[name]["e"]),
                            dbeta=abs(result["beta"] - references[name]["beta"]),
                        )
                rows[key] = row
                done["|".join(key)] = row
                partial.write_text(json.dumps({"scenes": these, "rows": done}, indent=1))
                print(label, surface, name, row, flush=True)
    return rows


def summary(rows: dict) -> list[dict]:
    labels = list(dict.fromkeys(label for label, _, _ in rows))
    out = []
    for label in labels:
        smooth = [
            r
            for (lab, s, _), r in rows.items()
            if lab == label and s == "smooth" and "error" not in r
        ]
        rough = [r for (lab, s, _), r in rows.items() if lab == label and s == "rough"]
        failed = [r["error"] for r in rough if "error" in r]
        survived = [r for r in rough if "error" not in r]
        out.append(
            {
                "label": label,
                "failed": len(failed),
                "first_error": failed[0] if failed else "",
                "de": max((r["de"] for r in smooth), default=np.nan),
                "dbeta": max((r["dbeta"] for r in smooth), default=np.nan),
                "error": max((max(r["de"], r["dbeta"]) for r in smooth), default=np.nan),
                "drift": max((r["drift"] for r in survived), default=np.nan),
                "seconds": median([r["seconds"] for r in survived]) if survived else np.nan,
                "loop": (
                    median([r["loop"] for r in survived])
                    if survived and all("loop" in r for r in survived)
                    else np.nan
                ),
                "steps": median([r["steps"] for r in survived]) if survived else np.nan,
            }
        )
    return out


def plot(table: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for family, marker in (("verlet dt", "o"), ("respa", "s"), ("reference", "^"), ("pair", "x")):
        points = [
            r
            for r in table
            if r["label"].startswith(family) or (family == "pair" and "pair" in r["label"])
        ]
        points = [
            r for r in points if not r["failed"] and not (family != "pair" and "pair" in r["label"])
        ]
        if points:
            ax.loglog(
                [r["error"] for r in points],
                [r["seconds"] for r in points],
                marker,
                label=family.replace(" dt", ""),
                linestyle="-" if family == "verlet dt" else "",
            )
            for r in points:
                # the step; rRESPA's as outer/contact steps per step
                words = r["label"].split()
                step = r["label"].split("dt=")[-1].split(" ")[0]
                ax.annotate(
                    f"{step}/{words[1]}" if words[0] == "respa" else step,
                    (r["error"], r["seconds"]),
                    fontsize=7,
                    xytext=(3, 3),
                    textcoords="offset points",
                )
    ax.axvline(TOLERANCE, color="grey", linestyle=":", label="1e-3")
    ax.set_xlabel("largest error of e or beta, nine smooth scenes")
    ax.set_ylabel("median wall time per rough impact (s)")
    ax.legend()
    fig.tight_layout()
    write_figure(fig, path, 110)


def picks(table: list[dict], options: dict[str, RunOptions]) -> tuple[dict | None, dict | None]:
    """Verlet's largest step, and rRESPA's largest outer then inner step, that meet
    the criteria (the model's segment contact only)."""

    def meets(r: dict) -> bool:
        return not r["failed"] and r["error"] < TOLERANCE and r["drift"] < ENERGY_TOLERANCE

    ok = [
        (r, options[r["label"]])
        for r in table
        if r["label"] in options and options[r["label"]].contact == "segment" and meets(r)
    ]
    verlet = [(r, o) for r, o in ok if o.integrator == "verlet"]
    respa = [(r, o) for r, o in ok if o.integrator == "respa"]
    verlet_best = max(verlet, key=lambda ro: ro[1].dt)[0] if verlet else None
    respa_best = (
        max(respa, key=lambda ro: (ro[1].dt, ro[1].dt / ro[1].nrespa))[0] if respa else None
    )
    return verlet_best, respa_best


def render(table: list[dict]) -> str:
    """The page's text below its header, from the summary table alone (the
    committed time_vs_error.json), so that the page can be made again from it."""
    options = {label: opts for label, kind, opts in settings() if kind == "lammps"}
    verlet_best, respa_best = picks(table, options)
    default = next((r for r in table if r["label"] == f"verlet dt={DEFAULT_DT:g}"), None)
    paper = next((r for r in table if "paper" in r["label"]), None)
    lines = []
    for r in table:
        status = f"{r['failed']} of 9 failed: {r['first_error'][:70]}" if r["failed"] else ""
        lines.append(
            [
                r["label"],
                f"{r['de']:.1e}",
                f"{r['dbeta']:.1e}",
                f"{r['drift']:.1e}",
                f"{r['steps']:.0f}",
                f"{r['seconds']:.2f}",
                f"{r['loop']:.2f}",
                status,
            ]
        )
    body = markdown_table(
        [
            "setting",
            "max error e (smooth)",
            "max error beta (smooth)",
            "max energy error (rough)",
            "median steps",
            "median s per impact (rough)",
            "median loop s per impact (rough)",
            "rough runs that failed",
        ],
        lines,
    )
    body += (
        "\n\nSettings: `verlet dt=X` is velocity Verlet at step X; `respa N dt=X` is rRESPA "
        "with the springs at the outer step X and the contact alone on the inner level at "
        "X / N (decks/setup.lmp); steps are outer steps. The seconds per impact count "
        "starting lmp for each impact; the loop seconds only LAMMPS's run loop."
    )
    criteria = (
        f"errors of e and beta below {TOLERANCE:g} on every smooth scene, an energy error "
        f"below {ENERGY_TOLERANCE:g} on every rough scene, and no failure"
    )
    if verlet_best:
        body += (
            f"\n\n**Verlet**: the largest step with {criteria} (a study pays per step): "
            f"**{verlet_best['label']}**, largest error {verlet_best['error']:.1e} (margin "
            f"{TOLERANCE / verlet_best['error']:.1f}x), energy error {verlet_best['drift']:.1e} "
            f"(margin {ENERGY_TOLERANCE / verlet_best['drift']:.1f}x), median "
            f"{verlet_best['seconds']:.2f} s per impact."
        )
    if respa_best:
        split = options[respa_best["label"]]
        body += (
            f"\n\n**rRESPA**, the contact alone on the inner level: the largest outer step, "
            f"then the largest inner one, with the same criteria: **{respa_best['label']}** "
            f"(the springs at {split.dt:g}, the contact at {split.dt / split.nrespa:g}), "
            f"largest error {respa_best['error']:.1e} (margin "
            f"{TOLERANCE / respa_best['error']:.1f}x), energy error {respa_best['drift']:.1e} "
            f"(margin {ENERGY_TOLERANCE / respa_best['drift']:.1f}x), median "
            f"{respa_best['seconds']:.2f} s per impact, {respa_best['loop']:.2f} s in the loop."
        )
        if default:
            body += (
                f" Against the default, {default['label']}, in this run: "
                f"{default['seconds'] / respa_best['seconds']:.2f} times as fast by whole "
                f"impacts ({default['seconds']:.2f} s), "
                f"{default['loop'] / respa_best['loop']:.2f} times in the loop "
                f"({default['loop']:.2f} s) (medians over the nine rough scenes). It is not "
                "the default"
                + (
                    ": it is slower in the loop."
                    if default["loop"] < respa_best["loop"]
                    else ": that waits for a whole study's check against Verlet's."
                )
            )
    if verlet_best and paper:
        body += (
            f"\n\nThe paper's scheme (Forest-Ruth at 1e-3, our numpy implementation) takes a "
            f"median {paper['seconds']:.1f} s "
            f"({paper['seconds'] / verlet_best['seconds']:.0f}x Verlet's pick) with "
            f"largest error {paper['error']:.1e}."
        )
    body += "\n\n" + default_note(default, verlet_best) + "\n\n" + DRIFT_NOTE
    return body + "\n\n![time against error](time_vs_error.png)\n"


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--out",
        type=OutFolder(),
        default=str(WORK),  # a text, so that argparse checks it
        help="folder for the runs and their rows (default: runs/bench)",
    )
    parser.add_argument(
        "--only",
        type=setting_word,
        nargs="+",
        default=None,
        help="only settings whose label contains one of these words (verlet, respa, pair, "
        "reference, dt=0.004, ...)",
    )
    parser.add_argument(
        "--summarise",
        action="store_true",
        help="only redo the table from the rows of the last run (--out's rows.json)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    out = Path(args.out)
    saved = out / "rows.json"
    try:
        if args.summarise and args.only:
            raise InputError("--only does not apply with --summarise (it redoes the last table)")
        if args.summarise and not saved.is_file():
            raise InputError(f"--summarise: {saved} is missing (run without --summarise first)")
        if args.summarise:
            try:
                rows = {tuple(k.split("|")): v for k, v in json.loads(saved.read_text()).items()}
            except (ValueError, AttributeError):
                raise InputError(f"--summarise: {saved} is not a table of rows") from None
    except InputError as error:
        return refuse(__file__, error)
    if not args.summarise:
        out.mkdir(parents=True, exist_ok=True)
        rows = measure(out, args.only)
        saved.write_text(json.dumps({"|".join(k): v for k, v in rows.items()}, indent=1))
    table = summary(rows)
    body = render(table)
    folder = output_folder(args.docs)
    plot(table, folder / "time_vs_error.png")
    (folder / "time_vs_error.json").write_text(json.dumps(table, indent=1) + "\n")
    print(body)
    # make bench passes --docs and nothing else
    plain = not args.only and not args.summarise and out.resolve() == WORK.resolve()
    command = (
        "make bench"
        if args.docs and plain
        else "python bench/time_vs_error.py"
        + ("" if out.resolve() == WORK.resolve() else f" --out {args.out}")
        + (" --only " + " ".join(args.only) if args.only else "")
        + (" --summarise" if args.summarise else "")
        + (" --docs" if args.docs else "")
    )
    title = "Run time against error"
    print(f"wrote {write_report('time_vs_error', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
