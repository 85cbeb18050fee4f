"""Where a study's workers come from, on the command line (runner.cluster.workers)."""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

from ground.errors import InputError

from ..cluster.workers import CLUSTERS, CORES_PER_JOB, JOBS, WORKERS, ClusterSpec
from ..options import (
    RANKS,
)

WALLTIME = re.compile(r"^(?:(\d{1,3})-)?(\d{1,3}):([0-5]\d):([0-5]\d)$")
SCHEDULER = re.compile(r"^([a-z]+://)?[\w.\-]+:\d{1,5}$")


def walltime(text: str) -> str:
    """--walltime: HH:MM:SS (minutes and seconds below 60), or D-HH:MM:SS
    (hours below 24), longer than nothing."""
    match = WALLTIME.match(text)
    if (
        not match
        or (match[1] is not None and int(match[2]) > 23)
        or not any(int(part or 0) for part in match.groups())
    ):
        raise argparse.ArgumentTypeError(
            f"must be HH:MM:SS (MM and SS 00 to 59) or D-HH:MM:SS (HH 00 to 23), "
            f"longer than 00:00:00, got {text!r}"
        )
    return text


walltime.bad_values = ("1h", "10", "a:b:c", "01:00", "00:99:99", "01:60:00", "1-24:00:00",
                       "00:00:00", "-1:00:00")  # fmt: skip


def job_memory(text: str) -> str:
    from dask.utils import parse_bytes

    try:
        size = parse_bytes(text)
    except ValueError:
        size = 0
    if not text[:1].isdigit() or size < 2**20:
        raise argparse.ArgumentTypeError(f"must be a size such as 4GiB or 16GB, got {text!r}")
    return text


job_memory.bad_values = ("lots", "-4GB", "0", "GB")


def slurm_word(text: str) -> str:
    if not text or any(c.isspace() or c in "#$;&|'\"`" for c in text):
        raise argparse.ArgumentTypeError(f"must be one word of Slurm's, got {text!r}")
    return text


slurm_word.bad_values = ("", "a b", "a;b")


def scheduler_target(text: str) -> str:
    """--scheduler: an address, or a scheduler file (JSON naming an address)."""
    if Path(text).is_file():
        try:
            address = json.loads(Path(text).read_text(encoding="utf-8"))["address"]
        except (OSError, ValueError, KeyError, TypeError):
            address = None
        if (
            not isinstance(address, str)
            or not SCHEDULER.match(address)
            or (int(address.rsplit(":", 1)[1]) > 65535)
        ):
            raise argparse.ArgumentTypeError(
                f'{text} is not a Dask scheduler file (JSON with the scheduler\'s "address", '
                "as dask scheduler --scheduler-file writes it)"
            )
        return text
    if SCHEDULER.match(text) and int(text.rsplit(":", 1)[1]) <= 65535:
        return text
    raise argparse.ArgumentTypeError(
        f"must be a Dask scheduler's address (tcp://host:8786) or its scheduler file, got {text!r}"
    )


scheduler_target.bad_values = ("{tmp}/missing.json", "no address", "tcp://", "{file}",
                               "tcp://host:99999")  # fmt: skip


def retired(replacement: str):
    """The type of an option that is gone: any value is refused, with what replaces it."""

    def refuse(text: str):
        raise argparse.ArgumentTypeError(f"is retired: studies run on Dask; {replacement}")

    refuse.bad_values = ("2",)
    return refuse


def add_cluster_arguments(study) -> None:
    """Where a study's workers come from (runner.cluster.workers)."""
    group = study.add_argument_group(
        "the workers: a Dask cluster on this machine (default), Slurm jobs, or a running "
        "cluster (docs/cluster.md)"
    )
    group.add_argument(
        "--cluster",
        choices=CLUSTERS,
        default=None,
        help="local: worker processes on this machine (default); slurm: Slurm batch jobs "
        "(dask-jobqueue's SLURMCluster)",
    )
    group.add_argument(
        "--workers",
        type=WORKERS,
        default=None,
        help=f"local worker processes, {WORKERS.describe()} (default: this machine's cores, "
        "over --ranks)",
    )
    group.add_argument(
        "--ranks",
        type=RANKS,
        default=None,
        help=f"MPI ranks per impact, {RANKS.describe()}, a worker owning as many cores: lmp "
        "under mpirun (slurm: srun --mpi=pmix in the job) (default: the study's: its file's "
        "[run] ranks, or 1)",
    )
    group.add_argument(
        "--jobs", type=JOBS, default=None, help=f"slurm: batch jobs, {JOBS.describe()} (default: 1)"
    )
    group.add_argument(
        "--cores-per-job",
        type=CORES_PER_JOB,
        default=None,
        help=f"slurm: cores per job, a worker process on each (on each --ranks of them), "
        f"{CORES_PER_JOB.describe()} (default: 1)",
    )
    group.add_argument(
        "--walltime", type=walltime, default=None, help="slurm: each job's time limit, HH:MM:SS"
    )
    group.add_argument("--queue", type=slurm_word, default=None, help="slurm: the partition")
    group.add_argument("--account", type=slurm_word, default=None, help="slurm: the account")
    group.add_argument(
        "--memory",
        type=job_memory,
        default=None,
        help="slurm: memory per job, e.g. 8GiB (default: the site's; Slurm's --mem left out)",
    )
    group.add_argument(
        "--scheduler",
        type=scheduler_target,
        default=None,
        metavar="ADDRESS_OR_FILE",
        help="join this running Dask cluster (a scheduler's address, or the scheduler file "
        "of dask-mpi or dask scheduler --scheduler-file) instead of making one",
    )
    for name in ("--partitions", "--batch-size"):
        group.add_argument(
            name, type=retired("use --cluster slurm or --scheduler"), default=None,
            help=argparse.SUPPRESS,
        )  # fmt: skip


SLURM_ONLY = ("jobs", "cores_per_job", "walltime", "queue", "account", "memory")


def cluster_from_args(args, study_folder: Path) -> ClusterSpec:
    """The cluster a study command asks for; an option the cluster would not
    use is refused, not ignored."""
    slurm = args.cluster == "slurm"
    if args.scheduler and args.cluster:
        raise InputError("--scheduler joins a running cluster: give it without --cluster")
    if args.workers is not None and (slurm or args.scheduler):
        raise InputError(
            "--workers applies to --cluster local only (Slurm: --jobs and --cores-per-job)"
        )
    unused = [d for d in SLURM_ONLY if getattr(args, d) is not None]
    if unused and not slurm:
        raise InputError(f"{option(unused[0])} applies to --cluster slurm only")
    return ClusterSpec(
        kind=args.cluster or "local",
        workers=args.workers,
        jobs=args.jobs or 1,
        cores_per_job=args.cores_per_job or 1,
        walltime=args.walltime,
        queue=args.queue,
        account=args.account,
        memory=args.memory,
        scheduler=args.scheduler,
        log_directory=study_folder / "slurm" if slurm else None,
    )


def option(dest: str) -> str:
    """An argparse destination as its option: cores_per_job -> --cores-per-job."""
    return "--" + dest.replace("_", "-")
