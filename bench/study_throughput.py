"""Impacts per minute of the study: worker processes against LAMMPS partitions.

    python bench/study_throughput.py [--samples 1] [--angles 8] [--repeats 2]

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

from common import ROOT, markdown_table, median, write_report

WAYS = {
    "2 workers (lammps module)": ["--workers", "2"],
    "2 partitions (mpirun lmp -partition 2x1)": ["--partitions", "2"],
    "1 worker": ["--workers", "1"],
}
PAPER_IMPACTS = 6400


def run(name: str, extra: list[str], samples: int, angles: int) -> tuple[float, int]:
    shutil.rmtree(ROOT / "runs" / name, ignore_errors=True)
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
    impacts = len(list((ROOT / "runs" / name).glob("*/*/*/result.json")))
    return seconds, impacts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1)
    parser.add_argument("--angles", type=int, default=8)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
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
    command = "python bench/study_throughput.py" + "".join(
        f" --{k} {v}" for k, v in vars(args).items()
    )
    print(body)
    print(write_report("study_throughput", "Study throughput", command, body))


if __name__ == "__main__":
    main()
