"""Where and how long a study ran: the machine, LAMMPS and the wall clock."""

from __future__ import annotations

import json
import os

from ground.gate import write_text
from ground.provenance import cpu_name, machine  # noqa: F401 (the runner's machine too)


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
        write_text(path, json.dumps(info, indent=1))
