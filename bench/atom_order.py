"""LAMMPS's rate per atom-step with the interiors in the sampler's order and
in spatial bins (builder.assembly.binned_order).

    python bench/atom_order.py [--sizes 12800 25600 51200] [--repeats 3]
                               [--gamma 30] [--seed 1] [--docs]

For each number of disk points N (random disk, seed --seed, --gamma degrees,
0.1 c, the scene of bench/loop_rate.py), the scene is built twice, the
interiors of both bodies in the Poisson sampler's order and in square bins of
builder.assembly.ORDER_BIN spacings (rows of bins, as LAMMPS's atom sort lays
them out), and its impact run on one rank in each, interleaved and repeated
(the deck's settings, LAMMPS's timer breakdown). The builder uses the bins
beyond builder.assembly.SAMPLE_ORDER_UP_TO disk points; here both orders run
at every size. The two orders sum each atom's forces in another order, so a
rough contact's chaos moves e's last digits; the physics is the same body
(tests/builder/test_atom_order.py).
"""

from __future__ import annotations

import os
import shutil
import sys

import builder.assembly as assembly
from bench.common import (
    RUNS,
    add_repeats,
    add_scene_pick,
    bench_parser,
    distinct,
    markdown_table,
    median,
    refuse,
    write_report,
)
from bench.loop_rate import run_once
from bench.resolution_cost import SIZE, scaled_settings, spec_at
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from ground.errors import InputError

SIZES = [12800, 25600, 51200]
ORDERS = {"sampler": 10**9, "binned": 0}  # SAMPLE_ORDER_UP_TO for each


def built(n: int, gamma: float, seed: int, order: str):
    """The scene with its interiors in ``order``, written to its run folder."""
    folder = RUNS / "atom_order" / f"n{n}_{order}"
    shutil.rmtree(folder, ignore_errors=True)
    saved = assembly.SAMPLE_ORDER_UP_TO
    assembly.SAMPLE_ORDER_UP_TO = ORDERS[order]
    try:
        return write_scene(build_scene(spec_at(n, gamma, seed)), folder)
    finally:
        assembly.SAMPLE_ORDER_UP_TO = saved


def parser():
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--sizes", type=SIZE, nargs="+", default=SIZES,
        help=f"numbers of disk points, each {SIZE.describe()} (default: "
        f"{' '.join(map(str, SIZES))})",
    )  # fmt: skip
    add_repeats(parser, 3, "runs of each order, interleaved")
    add_scene_pick(parser)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        distinct("--sizes", args.sizes)
        for n in args.sizes:
            spec_at(n, args.gamma, args.seed).validate()
    except InputError as error:
        return refuse(__file__, error)
    rows, gains = [], []
    for n in sorted(args.sizes):
        folders = {order: built(n, args.gamma, args.seed, order) for order in ORDERS}
        dt = scaled_settings(n)[0]
        load = os.getloadavg()[0]
        done = {order: [] for order in ORDERS}
        for _ in range(args.repeats):
            for order, folder in folders.items():
                done[order].append(run_once(folder, dt, 1, "now"))
        loads = f"{load:.1f} to {os.getloadavg()[0]:.1f}"
        rate = {}
        for order, runs in done.items():
            if None in runs:
                rows.append([f"{n:,}", order] + ["failed"] * 5 + [loads])
                continue
            rate[order] = median(x["rate"] for x in runs)
            rows.append([
                f"{n:,}", order, f"{runs[0]['atoms']:,}", f"{runs[0]['steps']:,}",
                f"{rate[order] / 1e6:.1f}", f"{median(x['bond'] for x in runs):.0%}",
                f"{runs[0]['e']:.6f}", loads,
            ])  # fmt: skip
        if len(rate) == 2:
            gains.append([f"{n:,}", f"{rate['binned'] / rate['sampler']:.2f}"])
        print(rows[-2:], flush=True)
    body = (
        f"Random disk, seed {args.seed}, {args.gamma:g} degrees, 0.1 c, the scene of "
        "bench/loop_rate.py; one rank, the deck's settings; medians of "
        f"{args.repeats} runs, the two orders interleaved. rate: atoms times steps over "
        "LAMMPS's loop time, in millions of atom-steps per second; Bond: its share of "
        "the loop. load: the 1-minute load average before and after the size "
        f"({os.cpu_count()} cores). The builder bins the interiors beyond "
        f"{assembly.SAMPLE_ORDER_UP_TO:,} disk points.\n\n"
        + markdown_table(
            ["disk points N", "interiors", "atoms", "steps", "M atom-steps/s", "Bond", "e", "load"],
            rows,
        )  # fmt: skip
        + "\n\nRate in bins over rate in the sampler's order, one rank:\n\n"
        + markdown_table(["disk points N", "binned / sampler"], gains)
    )
    command = (
        "python bench/atom_order.py --sizes " + " ".join(map(str, sorted(args.sizes)))
        + f" --repeats {args.repeats} --gamma {args.gamma:g} --seed {args.seed}"
        + (" --docs" if args.docs else "")
    )  # fmt: skip
    title = "The interiors' order and LAMMPS's rate per atom-step"
    print(body)
    print(f"wrote {write_report('atom_order', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
