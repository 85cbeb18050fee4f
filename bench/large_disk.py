"""A large-resolution disk on several ranks: domain decomposition at scale.

    python bench/large_disk.py [--n-disk 20000] [--ranks 1 2]

One impact (random lattice, 45 degrees, 0.1 c) of a disk of n_disk points on
a wall at the same number density, run by lmp on each number of ranks. The
time step shrinks with the spacing (the springs' period does): dt = 4e-3 *
sqrt(800 / n_disk). So does the roughness, 0.03 R * sqrt(800 / n_disk), the
same in spacings as the study's: the model's 0.03 R is over two spacings of a
20,000-point disk, too rough for its surface row (the builder refuses it). The table gives the loop's steps per second, the wall time
of the whole impact and e and beta, which must agree between rank counts up
to the round-off that domain decomposition reorders (docs/validation.md).
"""

from __future__ import annotations

import argparse
import math
import shutil
import time

from common import ROOT, loop_seconds, markdown_table, write_report

from builder.lammps_data import write_scene
from builder.scene import SceneSpec, build_scene
from runner.impact import run_scene
from runner.options import RunOptions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-disk", type=int, default=20000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    dt = 4e-3 * math.sqrt(800 / args.n_disk)
    roughness = 0.03 * math.sqrt(800 / args.n_disk)
    start = time.monotonic()
    scene = build_scene(SceneSpec(gamma_deg=45.0, n_disk=args.n_disk, roughness=roughness))
    build_seconds = time.monotonic() - start
    rows = []
    for ranks in args.ranks:
        folder = ROOT / "runs" / "bench" / f"large_{args.n_disk}_np{ranks}"
        shutil.rmtree(folder, ignore_errors=True)
        write_scene(scene, folder, "class2")
        result = run_scene(folder, RunOptions(dt=dt, nprocs=ranks, every=100))
        seconds, steps = loop_seconds(folder / "log.lammps")
        rows.append([str(ranks), str(steps), f"{steps / seconds:,.0f}",
                     f"{result['wall_seconds']:.0f}", f"{result['e']:.6f}", f"{result['beta']:+.6f}",
                     f"{result['energy_drift']:+.1e}"])
        print(" ".join(rows[-1]), flush=True)
    body = (f"Random lattice, 45 degrees, 0.1 c: {scene.info['n_atoms']:,} atoms, "
            f"{scene.info['n_springs']:,} springs, dt = {dt:.2e} R/c, roughness {roughness:.4f} R; "
            f"building the scene took "
            f"{build_seconds:.0f} s.\n\n"
            + markdown_table(["ranks", "steps", "steps/s", "wall s", "e", "beta", "energy drift"], rows))
    command = f"python bench/large_disk.py --n-disk {args.n_disk} --ranks " + " ".join(map(str, args.ranks))
    print(body)
    print(write_report("large_disk", "A large-resolution disk on several ranks", command, body))


if __name__ == "__main__":
    main()
