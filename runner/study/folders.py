"""An impact's folder: its state, and what is set aside or pruned in it.

Every impact has its own folder, runs/<study>/<lattice>/s<seed>/g<gamma>/;
it is finished when it holds result.json (written atomically, last) and
failed when it holds failed.json. A study that is started again runs only
what is neither, so a killed study loses nothing already done.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from ground.gate import remove

from ..options import RunOptions, halved_step

# What a finished impact keeps: the rest (the data file above all, 1.5 MB) is
# rebuilt from its seed in a second if needed.
KEEP = ("result.json", "run.json", "scene.json", "series.dat", "energy.dat")
# An unreadable result.json is moved aside to this name, kept for a look, and
# its impact runs again.
CORRUPT = "result.json.corrupt"
# A result (or failure) on a wall of other springs than the study's (the
# triangular and square disks' walls before every lattice met the random
# disk's) is moved aside to a name with this suffix, and its impact runs again.
OTHER_WALL = ".other-wall"
# An impact's mark that a worker started it (runner/cluster/tasks.py), which
# rebuilding its scene leaves in its folder.
STARTED = "started.json"
# What rebuilding or pruning a folder leaves in it.
SET_ASIDE = (CORRUPT, "result.json" + OTHER_WALL, "failed.json" + OTHER_WALL)


def state(job: dict) -> str:
    folder = Path(job["folder"])
    if (folder / "result.json").exists():
        return "done"
    if (folder / "failed.json").exists():
        return "failed"
    return "pending"


def failed_state(job: dict) -> str:
    """A failed impact's state: failed, or stuck (analysis.impact.failures.impact_state)."""
    from analysis.study_tables import read_failure

    return read_failure(job)["state"]


def set_aside_if_unreadable(job: dict) -> None:
    """Move an unreadable result.json to result.json.corrupt, so that its
    impact counts as not run (a half-written file cannot come from this
    program, which writes atomically, but from a full disk or a copy)."""
    from analysis.impact.result import UnreadableResult, read_result

    result = Path(job["folder"]) / "result.json"
    if result.exists():
        try:
            read_result(result)
        except UnreadableResult as error:
            result.replace(result.with_name(CORRUPT))
            print(
                f"warning: {error}; moved aside to {CORRUPT}, its impact runs again",
                file=sys.stderr,
                flush=True,
            )


def set_aside_if_other_wall(job: dict, ka_wall: float) -> None:
    """Move the result.json or failed.json of an impact whose wall had other
    springs than ``ka_wall`` to the same name + .other-wall, so that the impact
    runs again on the study's wall and no table mixes two walls."""
    folder = Path(job["folder"])
    scene = folder / "scene.json"
    done = [folder / name for name in ("result.json", "failed.json") if (folder / name).exists()]
    if not (done and scene.exists()):
        return
    try:
        recorded = float(json.loads(scene.read_text())["ka_wall"])
    except (OSError, ValueError, KeyError, TypeError):
        return  # an unreadable record: check_made_as_asked sets the result aside
    if not np.isclose(recorded, ka_wall, rtol=1e-12, atol=0.0):
        for path in done:
            path.replace(path.with_name(path.name + OTHER_WALL))
        print(
            f"warning: {folder}: its wall's ka {recorded:.6g} is not the study's {ka_wall:.6g}; "
            f"{' and '.join(p.name for p in done)} moved aside (+{OTHER_WALL}), it runs again",
            file=sys.stderr,
            flush=True,
        )


def prune(folder: Path) -> None:
    """Keep only the small files of a finished impact."""
    for path in folder.iterdir():
        if path.name not in KEEP and path.name not in SET_ASIDE:
            remove(path)


# What may differ between a finished impact's run and its study's without
# changing its result: where and how its ranks ran.
# barrier_halvings is a budget of retries, not how a run ran: a done
# impact's step is compared at the halvings it took (run.json), and one that
# took more than the study allows is refused in check_made_as_asked.
RUN_ANY_WAY = ("nprocs", "route", "dump_every", "every", "barrier_halvings")


def first_difference(recorded: dict, asked: dict, prefix: str = "") -> tuple[str, object, object]:
    """The first key (dotted into nested records) whose value ``recorded``
    and ``asked`` give differently (numbers to 1e-12), or ('', None, None).
    A key ``recorded`` lacks (a record older than the option) is not compared."""
    for key, want in asked.items():
        if key not in recorded:
            continue
        had = recorded[key]
        if isinstance(want, dict) and isinstance(had, dict):
            found = first_difference(had, want, f"{prefix}{key}.")
            if found[0]:
                return found
            continue
        if isinstance(want, tuple):
            want = list(want)
        same = had == want
        numbers = (int, float)
        if not same and isinstance(had, numbers) and isinstance(want, numbers):
            same = not isinstance(had, bool) and bool(np.isclose(had, want, rtol=1e-12, atol=0.0))
        if not same:
            return f"{prefix}{key}", had, want
    return "", None, None


def check_made_as_asked(job: dict, scene: dict, options: RunOptions) -> None:
    """Refuse a finished impact that another study made: its scene.json's
    scene or its run.json's options differ from the study's (``scene``,
    ``options``, what the study would run it with, at the step its run
    halved after a barrier crossing: run.json's dt_halvings). An impact
    whose records cannot be read is set aside (CORRUPT) and runs again.

    Raises
    ------
    ground.errors.InputError
        One line naming the impact's folder and the option that differs.
    """
    from ground.errors import InputError

    folder = Path(job["folder"])
    result = folder / "result.json"
    if not result.exists():
        return
    try:
        recorded = json.loads((folder / "scene.json").read_text())["spec"]
        run = json.loads((folder / "run.json").read_text())
        ran, halvings = run["options"], run.get("dt_halvings", 0)
        if not (isinstance(recorded, dict) and isinstance(ran, dict)):
            raise TypeError("not a record")
        if type(halvings) is not int or halvings < 0:  # a count; one beyond the
            # study's barrier_halvings differs in that option, refused below
            raise TypeError(f"dt_halvings {halvings!r} is not a count")
    except (OSError, ValueError, KeyError, TypeError) as error:
        result.replace(result.with_name(CORRUPT))
        print(
            f"warning: {folder}: its scene.json or run.json cannot be read ({error}); "
            f"its result moved aside to {CORRUPT}, the impact runs again",
            file=sys.stderr,
            flush=True,
        )
        return
    if halvings > options.barrier_halvings:
        raise InputError(
            f"impact {folder} ran at its step halved {halvings} times; the study allows "
            f"barrier_halvings {options.barrier_halvings}: remove the study's folder (or that "
            "impact's) to run it anew, or give another --name"
        )
    asked = halved_step(options, halvings).as_dict()
    options = {k: v for k, v in asked.items() if k not in RUN_ANY_WAY}
    key, had, want = first_difference(
        {"scene": recorded, "run": ran}, {"scene": scene, "run": options}
    )
    if key:
        name = key.split(".", 1)[1]
        raise InputError(
            f"impact {folder} was made with {name} {had!r}; the study asks {want!r}: remove "
            "the study's folder (or that impact's) to run it anew, or give another --name"
        )
