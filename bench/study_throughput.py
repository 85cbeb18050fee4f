"""Impacts per minute of the study: worker processes against LAMMPS partitions.

    python bench/study_throughput.py [--samples 1] [--angles 8] [--repeats 2] [--docs]

A small study with every lattice of the paper (lattices x angles x samples
impacts, 800-point disks, the default settings), run in fresh folders by each
way the runner has, interleaved and repeated: two worker processes driving
the `lammps` module in-process (the default), two LAMMPS partitions under
mpirun (the cluster path), and one worker. The wall time includes building
the scenes and the analysis of every impact; the last column projects the
paper's 6,400 impacts.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import time

from common import ROOT, add_repeats, bench_parser, markdown_table, median, write_report

from runner.study import ANGLES, SAMPLES, runs_folder

WAYS = {
    "2 workers (lammps module)": ["--workers", "2"],
    "2 partitions (mpirun lmp -partition 2x1)": ["--partitions", "2"],
    "1 worker": ["--workers", "1"],
}
PAPER_IMPACTS = 6400


def run(name: str, extra: list[str], samples: int, angles: int) -> tuple[float, int]:
    shutil.rmtree(runs_folder() / name, ignore_errors=True)
    command = [
        sys.executable,
        "-m",
        "runner",
        "study",
        "paper",
        "--name",
        name,
        "--samples",
        str(samples),
        "--angles",
        str(angles),
        *extra,
    ]
    start = time.monotonic()
    proc = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    if proc.returncode not in (0, 1):  # 1: some impacts failed, which the count shows
        raise subprocess.CalledProcessError(proc.returncode, command, proc.stdout, proc.stderr)
    seconds = time.monotonic() - start
    impacts = len(list((runs_folder() / name).glob("*/*/*/result.json")))
    return seconds, impacts


def parser() -> argparse.ArgumentParser:
    parser = bench_parser(__file__, __doc__)
    parser.add_argument(
        "--samples",
        type=SAMPLES,
        default=1,
        help=f"samples per angle and lattice, {SAMPLES.describe()} (default: 1)",
    )
    parser.add_argument(
        "--angles", type=ANGLES, default=8, help=f"angles, {ANGLES.describe()} (default: 8)"
    )
    add_repeats(parser, 2, "runs of every way")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    times: dict[str, list[float]] = {way: [] for way in WAYS}
    counts: dict[str, int] = {}
    for _ in range(args.repeats):
        for k, (way, extra) in enumerate(WAYS.items()):
            seconds, counts[way] = run(f"bench_throughput_{k}", extra, args.samples, args.angles)
            times[way].append(seconds)
            print(f"{way}: {counts[way]} impacts in {seconds:.1f} s", flush=True)
    rows = []
    for way in WAYS:
        seconds = median(times[way])
        rate = counts[way] / seconds * 60
        rows.append(
            [
                way,
                str(counts[way]),
                f"{seconds:.1f}",
                f"{rate:.1f}",
                f"{PAPER_IMPACTS / rate / 60:.2f} h",
            ]
        )
    body = (
        f"{args.samples} sample(s) x {args.angles} angles x 4 lattices, 800-point disks, default "
        f"settings; medians of {args.repeats} interleaved runs, wall time of the whole command.\n\n"
        + markdown_table(
            ["way", "impacts", "s", "impacts per minute", "paper (6,400 impacts)"], rows
        )
    )
    command = (
        f"python bench/study_throughput.py --samples {args.samples} --angles {args.angles} "
        f"--repeats {args.repeats}" + (" --docs" if args.docs else "")
    )
    print(body)
    title = "Study throughput"
    print(f"wrote {write_report('study_throughput', title, command, body, args.docs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
