"""What a worker does: whole impacts, each built, run, analysed and recorded here.

A task is a group of impacts (those of one sample, which share their bodies:
``builder`` memoizes them per process). For each impact the task builds the
scene, runs LAMMPS in-process through the ``lammps`` module, analyses the run
and writes result.json into the impact's folder, or failed.json.

Debian's LAMMPS has no C++ exceptions: an error ends the worker's process,
and Dask runs the task again on another worker. The task, not the scheduler's
count of failures, decides what that means, from the impact's folder:

- result.json or failed.json: the impact is settled; it is not run again
  (Dask also reruns tasks whose results were held by a worker that died);
- started.json without a result: an earlier attempt ended its worker. If that
  attempt's log holds a LAMMPS ERROR, the impact failed with that error, but
  for a triangle that crossed the area barrier within one step: the impact
  runs again at half the step, up to the run's barrier_halvings times
  (started.json counts them). If not, the worker was killed from outside
  (SIGKILL, a walltime, the study stopped) and the impact runs again, up to
  MAX_ATTEMPTS times.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import socket
import time
from pathlib import Path

from analysis.impact.failures import impact_state
from analysis.impact.result import write_json_atomically
from ground.gate import make_folder
from ground.launch import lammps_error

from ..impact import may_halve, run_scene
from ..options import AUTO, halved_step
from ..study import Study
from ..study.folders import STARTED, prune

# Starts of one impact that may end their worker without a LAMMPS error
# (killed from outside) before it counts as failed: a crash that leaves no
# ERROR line (a segfault, the kernel's OOM killer) must not run for ever.
MAX_ATTEMPTS = 3
# Where a worker's time goes, summed over a study's impacts: building the
# scene (bodies, data file), LAMMPS (its instance, read_data, the run), the
# rest (analysis, result files).
WORKER_PHASES = ("build", "lammps", "rest")


# Errors of the disk rather than of an impact: a full disk, a file size
# limit, a read-only folder. An impact is not failed for them; the study
# stops with one line naming the file (runner.cli.parser).
DISK_ERRORS = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EROFS, errno.EACCES, errno.EPERM)


def fail(job: dict, message: str) -> dict:
    """Record the impact as without a result (failed.json), with its state:
    failed, or stuck (its disk stayed on the wall, a physical outcome:
    analysis.impact.failures.impact_state), and say so."""
    folder = Path(job["folder"])
    make_folder(folder)
    state = impact_state(message)
    write_json_atomically({**job, "state": state, "error": message}, folder / "failed.json")
    (folder / STARTED).unlink(missing_ok=True)
    return {**job, "state": state, "error": message}


def earlier_attempt(job: dict) -> tuple[int, str, int]:
    """How often the impact was started without a result, the LAMMPS error
    that ended the last start ('' if none: killed from outside), and the
    halvings of the step that start ran at."""
    folder = Path(job["folder"])
    try:
        started = json.loads((folder / STARTED).read_text())
        attempts = started["attempts"]
    except (OSError, ValueError, KeyError, TypeError):
        return 0, "", 0
    halvings = started.get("dt_halvings", 0) if isinstance(started, dict) else 0
    return attempts, lammps_error(folder / "log.lammps", ""), halvings


def impact_task(study: Study, job: dict) -> dict:
    """Settle one impact: run it unless its folder says it is settled.

    Returns
    -------
    dict
        ``state``: done (ran here, with its times), failed (with its error),
        or settled (done or failed before, not run again).
    """
    folder = Path(job["folder"])
    if (folder / "result.json").exists() or (folder / "failed.json").exists():
        return {"folder": job["folder"], "state": "settled"}
    attempts, error, halvings = earlier_attempt(job)
    if error:  # the last start ended its worker with this LAMMPS error
        options = halved_step(study.options.for_scene(study.spec(job)), halvings)
        if not may_halve(error, halvings, options, automatic=study.options.dt == AUTO):
            return fail(job, error)
        # a step too long for the area barrier: this start runs at half of
        # it, and counts the starts killed from outside anew
        halvings, attempts = halvings + 1, 0
    if attempts >= MAX_ATTEMPTS:
        return fail(
            job,
            f"the impact ended its worker {attempts} times without a LAMMPS error "
            "(killed from outside, out of memory, or a crash)",
        )
    start = time.perf_counter()
    try:
        # marked before building: writing the sample's restart runs LAMMPS too,
        # and an error there ends this process as one in the run does
        started = {
            "attempts": attempts + 1,
            "host": socket.gethostname(),
            "pid": os.getpid(),
            "dt_halvings": halvings,
        }
        make_folder(folder)
        write_json_atomically(started, folder / STARTED)
        study.build(job)  # afresh: what an earlier start left goes, but the mark
        built = time.perf_counter()
        result = run_scene(folder, study.options, halvings=halvings)
    except OSError as error:
        if error.errno in DISK_ERRORS:  # the machine's, not the impact's: the study stops
            with contextlib.suppress(OSError):  # not an attempt of the impact's
                (folder / STARTED).unlink(missing_ok=True)
            return {**job, "state": "disk", "error": [error.errno, error.strerror, error.filename]}
        return fail(job, lammps_error(folder / "log.lammps", f"{type(error).__name__}: {error}"))
    except Exception as error:  # a Python error, or LAMMPS's with exceptions built in
        return fail(job, lammps_error(folder / "log.lammps", f"{type(error).__name__}: {error}"))
    prune(folder)  # started.json with the rest
    lammps = result["wall_seconds"]
    return {
        "folder": job["folder"],
        "state": "done",
        "e": result["e"],
        "beta": result["beta"],
        "steps": result["steps"],
        "build": built - start,
        "lammps": lammps,
        "rest": time.perf_counter() - built - lammps,
    }


def group_task(study: Study, jobs: list[dict]) -> list[dict]:
    """Settle every impact of a group, in order, in this worker."""
    outcomes = []
    for job in jobs:
        outcomes.append(impact_task(study, job))
        if outcomes[-1]["state"] == "disk":  # the rest would meet the same disk
            break
    return outcomes
