"""The paper study's tables against an earlier run of them, in distribution.

    python bench/paper_ensemble.py --before 43cb672 [--docs]

A change that only reorders LAMMPS's sums (another neighbour list or atom
order) changes every rough impact's digits, and the contact's chaos grows
them: e and beta of one impact are then not comparable, their ensembles are.
For every lattice and angle of docs/studies/results/impacts.csv (or --after's), the
paired difference of e and beta over the seeds both runs finished, against
the same table at the git revision --before (analysis/statistics/ensemble.py).
"""

from __future__ import annotations

import argparse
import csv
import io
import subprocess
import sys

import numpy as np

from analysis.statistics.ensemble import impact_differences, paired_differences, summary
from bench.common import ROOT, bench_parser, file_at, markdown_table, refuse, write_report
from ground.checks import InPath
from ground.errors import InputError

TABLE = "docs/studies/results/impacts.csv"
# where the table was before each study's record had its own folder (issue 47)
EARLIER_TABLE = "docs/results/impacts.csv"
WITHIN = 2.0  # standard errors


def table_at(revision: str) -> str:
    """The paper study's impacts.csv at a git revision, wherever it was then."""
    try:
        return file_at(revision, TABLE)
    except subprocess.CalledProcessError:
        return file_at(revision, EARLIER_TABLE)


def git_revision(text: str) -> str:
    """argparse's type for a revision of this clone that holds the table."""
    try:
        table_at(text)
    except subprocess.CalledProcessError:
        raise argparse.ArgumentTypeError(
            f"must be a git revision of this clone with {TABLE}, got {text!r}"
        ) from None
    return text


git_revision.bad_values = ("no-such-revision", "HEAD~100000")


def parser():
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--before",
        type=git_revision,
        required=True,
        help=f"the git revision whose {TABLE} to compare against",
    )
    parser.add_argument(
        "--after",
        type=InPath("file"),
        default=ROOT / TABLE,
        help=f"the table of the run to check (default: {TABLE})",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    before = list(csv.DictReader(io.StringIO(table_at(args.before))))
    try:
        with args.after.open() as handle:
            after = list(csv.DictReader(handle))
        differences = paired_differences(before, after)
    except (InputError, ValueError, KeyError) as error:
        return refuse(__file__, InputError(f"the tables are not alike: {error}"))
    result = summary(differences, WITHIN)
    rows = [
        [
            d.lattice,
            f"{d.gamma_deg:g}",
            d.quantity,
            str(d.seeds),
            f"{d.before:.4f}",
            f"{d.after:.4f}",
            f"{d.difference:+.1e} +- {d.standard_error:.1e}",
            f"{d.z:+.1f}",
        ]
        for d in differences
    ]
    singles = []
    for quantity in ("e", "beta"):
        moved = np.abs(impact_differences(before, after, quantity))
        singles.append(
            [
                quantity,
                str(len(moved)),
                str(int(np.sum(moved == 0.0))),
                f"{np.median(moved):.1e}",
                f"{np.percentile(moved, 99):.1e}",
                f"{moved.max():.1e}",
                str(int(np.sum(moved > 1e-3))),
            ]
        )
    body = (
        "**Single impacts** (the same lattice, seed and angle in both):\n\n"
        + markdown_table(
            ["", "impacts", "unchanged", "median change", "99th percentile", "largest", "> 1e-3"],
            singles,
        )
        + "\n\n**Ensembles.** "
        f"Each row: one lattice and angle of `{TABLE}` at `{args.before}` (before) and "
        f"now (after), the means over the seeds both finished, and the mean paired "
        f"difference (after - before, the same seed's disk and wall) with its standard "
        f"error over those seeds.\n\n"
        f"**{result['beyond']} of {result['cells']}** differences lie beyond "
        f"{WITHIN:g} standard errors, where a normal distribution puts "
        f"{result['expected']:.1f} (the cells share seeds, so they are not independent); "
        f"the largest is {result['largest_z']:.1f} errors ({result['largest_at']}).\n\n"
        + markdown_table(
            ["lattice", "gamma", "", "seeds", "before", "after", "difference", "z"], rows
        )
        + "\n"
    )
    print(body)
    command = f"python bench/paper_ensemble.py --before {args.before}" + (
        " --docs" if args.docs else ""
    )
    title = "The paper study against an earlier run, in distribution"
    print(f"wrote {write_report('paper_ensemble', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
