"""Command line: python -m runner {impact,run,demo} --help"""

from __future__ import annotations

import sys

from builder.cli import OneLineParser, add_scene_arguments, count, positive_float, spec_from_args
from builder.errors import BuildError, InputError

from .lammps_run import LammpsError
from .options import CONTACTS, INTEGRATORS, ROUTES, RULES, SPRINGS, RunOptions


def add_run_arguments(parser) -> None:
    group = parser.add_argument_group("run")
    defaults = RunOptions()
    group.add_argument("--dt", type=positive_float, default=defaults.dt,
                       help=f"time step in R/c (default: {defaults.dt})")
    group.add_argument("--integrator", choices=INTEGRATORS, default=defaults.integrator)
    group.add_argument("--nrespa", type=count(1), default=defaults.nrespa,
                       help="respa: spring steps per step (springs on the inner level)")
    group.add_argument("--contact", choices=CONTACTS, default=defaults.contact,
                       help="segment: the paper's point-to-polyline contact (default); "
                            "pair: the same exponential between points")
    group.add_argument("--rule", choices=RULES, default=defaults.rule,
                       help="segment contact: lever rule (default) or explicit gradient")
    group.add_argument("--springs", choices=SPRINGS, default=defaults.springs)
    group.add_argument("--tmax", type=positive_float, default=defaults.tmax,
                       help="stop with an error if the disk has not left by then (R/c)")
    group.add_argument("--dump-every", type=count(0), default=0,
                       help="steps between dump frames (0: no dump)")
    group.add_argument("--np", dest="nprocs", type=count(1), default=1, help="MPI ranks")
    group.add_argument("--route", choices=ROUTES, default="lmp",
                       help="lmp program (default) or the lammps Python module")


def options_from_args(args) -> RunOptions:
    return RunOptions(dt=args.dt, integrator=args.integrator, nrespa=args.nrespa,
                      contact=args.contact, rule=args.rule, springs=args.springs,
                      tmax=args.tmax, dump_every=args.dump_every, nprocs=args.nprocs,
                      route=args.route)


def main(argv: list[str] | None = None) -> int:
    from .demo import run_demo
    from .impact import run_impact, run_scene
    from .report import format_table

    parser = OneLineParser(prog="python -m runner", description="Run oblique impacts with LAMMPS.")
    commands = parser.add_subparsers(dest="command", required=True)

    impact = commands.add_parser("impact", help="build a scene, run one impact, print its result")
    add_scene_arguments(impact)
    add_run_arguments(impact)
    impact.add_argument("--out", default=None,
                        help="run folder (default: runs/<lattice>_s<seed>_g<gamma>)")

    run = commands.add_parser("run", help="run an existing scene folder (python -m builder scene)")
    run.add_argument("scene", help="folder with scene.data, scene.lmp and scene.json")
    add_run_arguments(run)

    demo = commands.add_parser("demo", help="a few angles for a couple of seeds, as a table")
    demo.add_argument("--seeds", type=count(1), default=2, help="number of samples (default: 2)")
    demo.add_argument("--out", default="runs/demo", help="folder for the runs (default: runs/demo)")
    add_run_arguments(demo)

    args = parser.parse_args(argv)
    try:
        if args.command == "impact":
            spec = spec_from_args(args)
            out = args.out or f"runs/{spec.lattice}_s{spec.seed}_g{spec.gamma_deg:g}"
            results = [run_impact(spec, out, options_from_args(args))]
        elif args.command == "run":
            results = [run_scene(args.scene, options_from_args(args))]
        else:
            results = run_demo(args.out, args.seeds, options_from_args(args))
    except (InputError, BuildError, LammpsError) as error:
        print(f"python -m runner: error: {error}", file=sys.stderr)
        return 2 if isinstance(error, InputError) else 1
    print(format_table(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
