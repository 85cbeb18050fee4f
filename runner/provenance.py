"""Where and how long a study ran: the machine, LAMMPS and the wall clock."""

from __future__ import annotations

import json
import os
from pathlib import Path


def record_wall_clock(study, seconds: float, counts: dict) -> None:
    """Keep in study.json how long the study's run took, if it ran the whole
    study at once (a resumed study's time is only part of it), and where the
    workers' and the driver's time went."""
    path = study.folder / "study.json"
    info = json.loads(path.read_text())
    if counts.get("ran") == len(study.jobs()):
        info["wall_clock"] = {
            "seconds": round(seconds, 1),
            "workers": counts.get("workers", 0),
            "cpu": cpu_name(),
            "cores": os.cpu_count(),
            "worker_seconds": {k: round(v, 1) for k, v in counts["worker_seconds"].items()},
            "driver_cpu_seconds": round(counts.get("driver_cpu_seconds", 0.0), 2),
        }
        path.write_text(json.dumps(info, indent=1))


def machine() -> str:
    """The machine and LAMMPS a page's numbers were measured on, and the date."""
    import platform
    import re
    import subprocess
    from datetime import date

    lmp = subprocess.run(["lmp", "-h"], capture_output=True, text=True).stdout
    version = re.search(r"LAMMPS - (.*?) -", lmp) or re.search(r"Simulator - (.*)\n", lmp)
    return (
        f"{cpu_name()}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, "
        f"LAMMPS {version.group(1).strip() if version else 'unknown'}, {date.today()}"
    )


def cpu_name() -> str:
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown CPU"
