"""The time step on rough scenes, in distribution: ensemble means at a step and at half of it.

    python bench/step_ensemble.py                       # Verlet at the default dt and at half
    python bench/step_ensemble.py --samples 100 --docs  # the committed check

A rough impact is chaotic (round-off grows tenfold per 100 steps in the
contact), so one impact at two steps cannot be compared; their ensembles can.
Two studies of the same seeds and angles (the study's own path: `python -m
runner study demo --cot-gamma ... --dt ...`), one with the candidate
integrator and step, one with Verlet at half the candidate's step; for each
angle, e and beta averaged over the seeds, and their paired difference
(the same seed's disk and wall in both) with its standard error over seeds.
The candidate passes where every difference is within 2 standard errors.
"""

from __future__ import annotations

import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from bench.common import bench_parser, markdown_table, write_report
from ground.errors import InputError
from runner.cluster.driver import run_study
from runner.cluster.workers import WORKERS
from runner.options import DT, INTEGRATORS, NRESPA
from runner.study import COT_GAMMA, SAMPLES, Study
from runner.study.studies import load_study

ANGLES = (10.0, 1.0, 0.3)  # cot gamma: near normal, a middle angle, sliding
PASS = 2.0  # standard errors


def parser():
    parser = bench_parser(__file__, __doc__)
    defaults = load_study("paper").options
    parser.add_argument(
        "--samples", type=SAMPLES, default=100, help=f"seeds, {SAMPLES.describe()} (default: 100)"
    )
    parser.add_argument(
        "--cot-gamma",
        type=COT_GAMMA,
        nargs="+",
        default=list(ANGLES),
        help=f"angles as cot gamma, each {COT_GAMMA.describe()} (default: 10 1 0.3)",
    )
    parser.add_argument(
        "--dt",
        type=DT,
        default=defaults.dt,
        help=f"the candidate's step, {DT.describe()} (default: the study's, {defaults.dt:g})",
    )
    parser.add_argument(
        "--integrator",
        choices=INTEGRATORS,
        default=defaults.integrator,
        help=f"the candidate's integrator (default: {defaults.integrator})",
    )
    parser.add_argument(
        "--nrespa", type=NRESPA, default=defaults.nrespa, help=f"respa: {NRESPA.describe()}"
    )
    parser.add_argument(
        "--workers", type=WORKERS, default=2, help=f"{WORKERS.describe()} (default: 2)"
    )
    return parser


def study(name: str, samples: int, cot_gamma: tuple[float, ...], **options) -> Study:
    base = load_study("paper")
    return replace(
        base,
        name=name,
        lattices=("random",),
        samples=samples,
        angles=len(cot_gamma),
        cot_gamma=cot_gamma,
        options=replace(base.options, **options),
    )


def per_seed(study: Study) -> dict[tuple[float, int], tuple[float, float]]:
    """(gamma, seed) -> (e, beta) of every finished impact."""
    out = {}
    for job in study.jobs():
        result = Path(job["folder"]) / "result.json"
        if result.exists():
            values = json.loads(result.read_text())
            out[(job["gamma"], job["seed"])] = (values["e"], values["beta"])
    return out


def compare(a: dict, b: dict, gammas: list[float]) -> tuple[list[list[str]], bool]:
    rows, passed = [], True
    for gamma in gammas:
        seeds = sorted(s for (g, s) in a if g == gamma and (g, s) in b)
        for k, name in enumerate(("e", "beta")):
            x = np.array([a[(gamma, s)][k] for s in seeds])
            y = np.array([b[(gamma, s)][k] for s in seeds])
            d = x - y
            se = d.std(ddof=1) / np.sqrt(len(d))
            ok = abs(d.mean()) <= PASS * se
            passed &= bool(ok)
            rows.append(
                [
                    f"{1.0 / np.tan(np.radians(gamma)):.3g}",
                    name,
                    str(len(seeds)),
                    f"{x.mean():.4f} +- {x.std(ddof=1) / np.sqrt(len(x)):.4f}",
                    f"{y.mean():.4f} +- {y.std(ddof=1) / np.sqrt(len(y)):.4f}",
                    f"{d.mean():+.4f} +- {se:.4f}",
                    f"{abs(d.mean()) / se:.1f}",
                    "yes" if ok else "no",
                ]
            )
    return rows, passed


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        cot = tuple(sorted(set(args.cot_gamma), reverse=True))
        label = f"{args.integrator}{args.nrespa if args.integrator == 'respa' else ''}"
        candidate = study(
            f"step_{label}_dt{args.dt:g}",
            args.samples,
            cot,
            dt=args.dt,
            integrator=args.integrator,
            nrespa=args.nrespa,
        )
        half = study(f"step_verlet_dt{args.dt / 2:g}", args.samples, cot, dt=args.dt / 2)
        for each in (candidate, half):
            each.validate()
    except InputError as error:
        print(f"python bench/step_ensemble.py: error: {error}", file=sys.stderr)
        return 2
    for each in (candidate, half):
        run_study(each, args.workers)
    rows, passed = compare(per_seed(candidate), per_seed(half), candidate.gammas())
    what = (
        f"{args.integrator}"
        + (f" with {args.nrespa} inner steps" if args.integrator == "respa" else "")
        + f" at dt {args.dt:g}"
    )
    body = (
        f"Random disk on the default scene, seeds 1 to {args.samples}, the same seeds in "
        f"both. Candidate: {what}; against Verlet at dt {args.dt / 2:g}. Means +- their "
        "standard error over seeds; the difference is paired by seed, +- its standard "
        f"error over seeds. Agrees: the difference within {PASS:g} standard errors.\n\n"
        + markdown_table(
            [
                "cot gamma",
                "",
                "seeds",
                f"candidate ({what})",
                f"Verlet dt {args.dt / 2:g}",
                "difference",
                "|difference| / se",
                "agrees",
            ],
            rows,
        )
        + f"\n\n**{'Every mean agrees' if passed else 'Some means differ'}**: the candidate "
        f"{'passes' if passed else 'fails'} the check."
    )
    print(body)
    command = (
        f"python bench/step_ensemble.py --samples {args.samples} --cot-gamma "
        + " ".join(f"{c:g}" for c in cot)
        + f" --dt {args.dt:g} --integrator {args.integrator}"
        + (f" --nrespa {args.nrespa}" if args.integrator == "respa" else "")
        + (" --docs" if args.docs else "")
    )
    page = write_report(
        f"step_ensemble_{label}", "Time step in distribution", command, body, args.docs
    )
    print(f"wrote {page}")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
