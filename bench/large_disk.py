"""A large-resolution disk on several ranks: domain decomposition at scale.

    python bench/large_disk.py [--n-disk 20000] [--ranks 1 2] [--time 1.6]
                               [--no-decay-table] [--whole] [--docs]

A disk of n_disk points (random lattice, 45 degrees, 0.1 c) on a wall at the
same number density, run by lmp from the start of the approach into the
contact (to t = --time R/c) on each number of ranks. Three of the study's
settings are kept in units of the spacing, which shrinks as sqrt(800 / n_disk):
the roughness, 0.03 R * sqrt(800 / n_disk) (the model's 0.03 R is over two
spacings of a 20,000-point disk, too rough for its surface row: the builder
refuses it), and the contact's decay rate, a R = 300 * sqrt(n_disk / 800), so
that the exponential dies out within the cutoff (the spacing) as in the study
(at a R = 300 a 20,000-point disk has 4 decay lengths in the cutoff and its
energy grew by 15 % by t = 1.6 at dt = 4e-4; the builder refuses it). The time step scales
with the spacing too: the default's, 2e-3, times sqrt(800 / n_disk). The table gives the loop's
steps per second, the disk's energies at the end, which must agree between
rank counts up to the round-off that domain decomposition reorders, and the
change of the total energy.

--whole also runs the whole impact, on the largest number of ranks, with the
study's stop rule, and gives e, beta and what it took.

A further table runs 1 rank with the decay rate left at the study's a R = 300
(passed to the deck, past the builder's check) and at the scaled one, at two
time steps each: what the builder's check prevents, and that it is not cured
by a smaller step. --no-decay-table leaves it out.
"""

from __future__ import annotations

import argparse
import math
import shutil
import sys

from analysis.impact.series import read_energies
from bench.common import (
    RUNS,
    bench_parser,
    distinct,
    loop_seconds,
    markdown_table,
    refuse,
    write_report,
)
from builder.assembly import build_scene
from builder.lammps_data import write_scene
from builder.scene import N_WALL, PAPER, Scene, SceneSpec
from ground.checks import Range
from ground.errors import InputError
from ground.launch import run_lmp
from runner.impact import run_scene
from runner.options import DEFAULT_DT, NPROCS, TMAX, RunOptions

ENERGIES = ("ke_disk", "pe_disk", "ke_wall", "pe_wall", "pe_contact")
# A large disk: from the study's 800 points up to the largest whose wall, at
# the disk's number density, the builder takes (N_WALL over the default wall).
LARGE_N_DISK = Range(
    800, int(N_WALL.high * math.pi / (SceneSpec.wall_width * SceneSpec.wall_height)), integer=True
)


def run(
    scene: Scene, name: str, dt: float, ranks: int, until: float, deck: dict | None = None
) -> dict:
    """Run the scene into the contact; steps/s, the energies at the end and the
    change of the total energy. ``deck`` overrides the scene's own settings."""
    folder = RUNS / name
    shutil.rmtree(folder, ignore_errors=True)
    options = RunOptions(dt=dt, tmax=until, every=100)
    write_scene(scene, folder, options.springs)  # the data file's bond style is the deck's
    # early_stop no: run to tmax whatever the contact does
    variables = {
        "scene": str(folder),
        "out": str(folder),
        **options.deck_variables(),
        "early_stop": "no",
        **(deck or {}),
    }
    wall = run_lmp(variables, folder / "log.lammps", ranks)
    seconds, steps = loop_seconds(folder / "log.lammps")
    energies = read_energies(folder / "energy.dat")
    total = [sum(row[k] for k in ENERGIES) for row in (energies[0], energies[-1])]
    return {
        "steps": steps,
        "rate": steps / seconds,
        "wall": wall,
        "end": energies[-1],
        "change": (total[1] - total[0]) / total[0],
    }


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--n-disk",
        type=LARGE_N_DISK,
        default=20000,
        help=f"points in the disk, {LARGE_N_DISK.describe()} (default: 20000)",
    )
    parser.add_argument(
        "--ranks",
        type=NPROCS,
        nargs="+",
        default=[1, 2],
        help=f"numbers of ranks, each {NPROCS.describe()} (default: 1 2)",
    )
    parser.add_argument(
        "--time",
        type=TMAX,
        default=1.6,
        help=f"run to this time, {TMAX.describe()} (default: 1.6, into the contact)",
    )
    parser.add_argument(
        "--no-decay-table", action="store_true", help="leave out the runs at the study's decay rate"
    )
    parser.add_argument(
        "--whole",
        action="store_true",
        help="also run the whole impact on the largest number of ranks",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    scale = math.sqrt(800 / args.n_disk)
    dt, roughness, contact_a = DEFAULT_DT * scale, 0.03 * scale, 300.0 / scale
    # the scaling by hand, as the page measured it: the wall of 1,600 points, a and V0 as given
    spec = SceneSpec(
        gamma_deg=45.0,
        n_disk=args.n_disk,
        roughness=roughness,
        contact_a=contact_a,
        n_wall=1600,
        **{**PAPER, "contact_scaling": "fixed"},
    )
    try:
        distinct("--ranks", args.ranks)
        spec.validate()
    except InputError as error:
        return refuse(__file__, error)
    scene = build_scene(spec)
    cutoff = scene.info["contact"]["cutoff"]

    rows, reference = [], None
    for ranks in args.ranks:
        out = run(scene, f"large_{args.n_disk}_np{ranks}", dt, ranks, args.time)
        end = out["end"]
        reference = reference or end
        difference = max(
            abs(end[k] - reference[k]) / abs(reference[k])
            for k in ("ke_disk", "pe_disk", "pe_contact")
            if reference[k]
        )
        rows.append(
            [
                str(ranks),
                str(out["steps"]),
                f"{out['rate']:,.0f}",
                f"{out['wall']:.0f}",
                f"{end['ke_disk']:.10g}",
                f"{end['pe_contact']:.6g}",
                f"{out['change']:+.1e}",
                f"{difference:.1e}",
            ]
        )
        print(" ".join(rows[-1]), flush=True)
    body = (
        f"Random lattice, 45 degrees, 0.1 c: {scene.info['n_atoms']:,} atoms, "
        f"{scene.info['n_springs']:,} springs, dt = {dt:.2e} R/c, roughness {roughness:.4f} R, "
        f"a R = {contact_a:.0f} ({contact_a * cutoff:.1f} decay lengths within the cutoff), "
        f"run to t = {args.time} R/c (into the contact).\n\n"
        + markdown_table(
            [
                "ranks",
                "steps",
                "steps/s",
                "wall s",
                "disk kinetic energy at the end",
                "contact energy at the end",
                "total energy change",
                "largest relative difference from 1 rank",
            ],
            rows,
        )
    )

    if args.whole:
        ranks = max(args.ranks)
        folder = RUNS / f"large_{args.n_disk}_whole"
        shutil.rmtree(folder, ignore_errors=True)
        options = RunOptions(dt=dt, nprocs=ranks, every=100)
        write_scene(scene, folder, options.springs)
        result = run_scene(folder, options)
        whole = [
            [
                str(ranks),
                str(result["steps"]),
                f"{result['time_end']:.1f}",
                f"{result['wall_seconds'] / 60:.1f}",
                f"{result['e']:.4f}",
                f"{result['beta']:+.4f}",
                f"{result['energy_drift']:+.1e}",
            ]
        ]
        print(" ".join(whole[0]), flush=True)
        body += (
            "\n\n## The whole impact\n\nThe same scene to the end of the impact "
            "(the study's predictive stop rule).\n\n"
            + markdown_table(
                ["ranks", "steps", "t end, R/c", "wall min", "e", "beta", "energy drift"], whole
            )
        )

    if not args.no_decay_table:
        decay_rows = []
        for a in (300.0, contact_a):
            for step in (dt, dt / 4) if a == 300.0 else (dt, dt / 2):
                deck = {"contact_a": repr(a), "contact_V0": repr(a / 2.0)}
                out = run(scene, f"large_{args.n_disk}_a{a:g}_dt{step:g}", step, 1, args.time, deck)
                decay_rows.append(
                    [f"{a:.0f}", f"{a * cutoff:.1f}", f"{step:.1e}", f"{out['change']:+.1e}"]
                )
                print(" ".join(decay_rows[-1]), flush=True)
        body += (
            "\n\n## The contact's decay rate\n\nThe same scene on 1 rank, V0 = a m c^2 R / 2 "
            "for each a.\n\n"
            + markdown_table(
                ["a R", "decay lengths within the cutoff", "dt", "total energy change"], decay_rows
            )
        )
    flags = (" --no-decay-table" if args.no_decay_table else "") + (
        " --whole" if args.whole else ""
    )
    command = (
        f"python bench/large_disk.py --n-disk {args.n_disk} --time {args.time} --ranks "
        + " ".join(map(str, args.ranks))
        + flags
        + (" --docs" if args.docs else "")
    )
    print(body)
    title = "A large-resolution disk on several ranks"
    print(f"wrote {write_report('large_disk', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
