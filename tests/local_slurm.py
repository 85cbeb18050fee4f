"""A one-node Slurm on this host, for the tests of the cluster path.

munged, slurmctld and slurmd are Debian's (`make test` installs them), started
directly, without systemd, from a munge key and a slurm.conf in a folder of
their own, on free ports, and stopped by their pids. Clients (sinfo, sbatch,
srun, dask-jobqueue's SLURMCluster) find this Slurm through SLURM_CONF.

    python -m tests.local_slurm FOLDER    # start one and wait (Ctrl-C stops it)
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

from tests.helpers import stop_by_pid

DAEMONS = ("munged", "mungekey", "slurmctld", "slurmd", "sinfo", "sbatch", "srun", "scancel")
PACKAGES = "slurmctld slurmd slurm-client munge"


class SlurmUnavailable(RuntimeError):
    """Slurm cannot be started here; the message says why."""


def why_not() -> str | None:
    """Why a one-node Slurm cannot be started on this host, or None."""
    if os.geteuid() != 0:
        return "a one-node Slurm needs root (slurmd starts jobs as their users)"
    missing = [name for name in DAEMONS if not shutil.which(name, path="/usr/sbin:/usr/bin")]
    if missing:
        return f"{', '.join(missing)} not found: apt-get install {PACKAGES} (make test does)"
    return None


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def node_memory_mb() -> int:
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemTotal:"):
            return int(line.split()[1]) // 1024
    raise SlurmUnavailable("no MemTotal in /proc/meminfo")


def slurm_conf(folder: Path, node: str, cpus: int, memory_mb: int) -> str:
    """A slurm.conf for one node, this host, with every path in ``folder``."""
    return f"""\
ClusterName=impacts
SlurmctldHost={node}(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket={folder}/munge.socket
CredType=cred/munge
StateSaveLocation={folder}/state
SlurmdSpoolDir={folder}/spool
SlurmctldPidFile={folder}/slurmctld.pid
SlurmdPidFile={folder}/slurmd.pid
SlurmctldLogFile={folder}/slurmctld.log
SlurmdLogFile={folder}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName={node} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory={memory_mb} State=UNKNOWN
PartitionName=debug Nodes={node} Default=YES MaxTime=INFINITE State=UP
"""


def wait_for(what: str, ready, seconds: float, log: Path | None = None) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if ready():
            return
        time.sleep(0.2)
    tail = log.read_text(errors="replace")[-2000:] if log and log.exists() else ""
    raise SlurmUnavailable(f"{what} not ready after {seconds:g} s. {tail}")


@contextlib.contextmanager
def one_node_slurm(folder: Path) -> Iterator[dict[str, str]]:
    """Start munged, slurmctld and slurmd with their files in ``folder``;
    yield the environment for Slurm's clients (SLURM_CONF); stop the three
    daemons by their pids, whatever ends the block."""
    if problem := why_not():
        raise SlurmUnavailable(problem)
    folder = Path(folder).resolve()
    folder.mkdir(parents=True, exist_ok=True)
    for sub in ("state", "spool"):
        (folder / sub).mkdir(exist_ok=True)
    os.chmod(folder, 0o755)  # munged refuses a socket folder others may write to
    node = socket.gethostname().split(".")[0]
    conf = folder / "slurm.conf"
    conf.write_text(slurm_conf(folder, node, os.cpu_count() or 1, node_memory_mb()))
    env = {**os.environ, "SLURM_CONF": str(conf)}
    key = folder / "munge.key"
    subprocess.run(["mungekey", "--create", f"--keyfile={key}"], check=True, capture_output=True)
    daemons: list[subprocess.Popen] = []
    try:
        daemons.append(
            subprocess.Popen(
                ["munged", "--foreground", "--force", f"--key-file={key}",
                 f"--socket={folder}/munge.socket", f"--pid-file={folder}/munged.pid",
                 f"--log-file={folder}/munged.log", f"--seed-file={folder}/munged.seed"],
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
            )
        )  # fmt: skip
        wait_for("munged", (folder / "munge.socket").exists, 10, folder / "munged.log")
        for daemon in ("slurmctld", "slurmd"):
            daemons.append(
                subprocess.Popen(
                    [daemon, "-D", "-f", str(conf)],
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    env=env,
                    cwd=folder,
                )
            )

        def idle() -> bool:
            out = subprocess.run(
                ["sinfo", "-h", "-o", "%T"], env=env, capture_output=True, text=True
            ).stdout
            return out.strip() == "idle"

        wait_for("the Slurm node", idle, 60, folder / "slurmd.log")
        yield {"SLURM_CONF": str(conf)}
    finally:
        stop_by_pid(daemons, 20)  # slurmd first: it ends its jobs' steps


if __name__ == "__main__":
    with one_node_slurm(Path(sys.argv[1])) as slurm_env:
        print(f"export SLURM_CONF={slurm_env['SLURM_CONF']}", flush=True)
        try:
            signal.pause()
        except KeyboardInterrupt:
            pass
