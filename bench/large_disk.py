"""A large-resolution disk on several ranks: domain decomposition at scale.

    python bench/large_disk.py [--n-disk 20000] [--ranks 1 2] [--time 1.6]

A disk of n_disk points (random lattice, 45 degrees, 0.1 c) on a wall at the
same number density, run by lmp from the start of the approach into the
contact (to t = --time R/c; a whole impact of a 20,000-point disk takes
about 50,000 steps, a quarter of an hour here) on each number of ranks. The
time step must shrink more than the spacing: every point has unit mass, so
a finer disk is heavier, its points press deeper into the exponential
contact, and the contact, not the springs, sets the limit (at dt = 4e-3 *
sqrt(800 / n_disk) = 8e-4 the total energy of a 20,000-point impact grew by
46 % by t = 1.6). The roughness shrinks with the spacing, 0.03 R * sqrt(800 / n_disk), the
same in spacings as the study's: the model's 0.03 R is over two spacings of a
20,000-point disk, too rough for its surface row (the builder refuses it).
The table gives the loop's steps per second and the disk's energies at the
end, which must agree between rank counts up to the round-off that domain
decomposition reorders.
"""

from __future__ import annotations

import argparse
import math
import shutil

from common import ROOT, loop_seconds, markdown_table, write_report

from analysis.series import read_energies
from builder.lammps_data import write_scene
from builder.scene import SceneSpec, build_scene
from runner.lammps_run import run_lmp
from runner.options import RunOptions


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-disk", type=int, default=20000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--time", type=float, default=1.6, help="run to this time, R/c")
    parser.add_argument("--dt", type=float, default=2e-4, help="time step, R/c")
    args = parser.parse_args()
    dt = args.dt
    roughness = 0.03 * math.sqrt(800 / args.n_disk)
    scene = build_scene(SceneSpec(gamma_deg=45.0, n_disk=args.n_disk, roughness=roughness))
    rows, reference = [], None
    for ranks in args.ranks:
        folder = ROOT / "runs" / "bench" / f"large_{args.n_disk}_np{ranks}"
        shutil.rmtree(folder, ignore_errors=True)
        write_scene(scene, folder, "class2")
        # early_stop no: run to tmax whatever the contact does
        variables = {"scene": str(folder), "out": str(folder),
                     **RunOptions(dt=dt, tmax=args.time, every=100).deck_variables(),
                     "early_stop": "no"}
        wall = run_lmp(variables, folder / "log.lammps", ranks)
        seconds, steps = loop_seconds(folder / "log.lammps")
        end = read_energies(folder / "energy.dat")[-1]
        reference = reference or end
        difference = max(abs(end[k] - reference[k]) / abs(reference[k])
                         for k in ("ke_disk", "pe_disk", "pe_contact") if reference[k])
        start = read_energies(folder / "energy.dat")[0]
        total = [sum(row[k] for k in ("ke_disk", "pe_disk", "ke_wall", "pe_wall", "pe_contact"))
                 for row in (start, end)]
        rows.append([str(ranks), str(steps), f"{steps / seconds:,.0f}", f"{wall:.0f}",
                     f"{end['ke_disk']:.10g}", f"{end['pe_contact']:.6g}",
                     f"{(total[1] - total[0]) / total[0]:+.1e}", f"{difference:.1e}"])
        print(" ".join(rows[-1]), flush=True)
    body = (f"Random lattice, 45 degrees, 0.1 c: {scene.info['n_atoms']:,} atoms, "
            f"{scene.info['n_springs']:,} springs, dt = {dt:.2e} R/c, roughness {roughness:.4f} R, "
            f"run to t = {args.time} R/c (into the contact).\n\n"
            + markdown_table(["ranks", "steps", "steps/s", "wall s", "disk kinetic energy at the end",
                              "contact energy at the end", "total energy change",
                              "largest relative difference from 1 rank"],
                             rows))
    command = (f"python bench/large_disk.py --n-disk {args.n_disk} --time {args.time} --dt {args.dt} --ranks "
               + " ".join(map(str, args.ranks)))
    print(body)
    print(write_report("large_disk", "A large-resolution disk on several ranks", command, body))


if __name__ == "__main__":
    main()
