"""The study a `runner study` command asks for: its file's, or its folder's
record, changed by the options given; never a study that exists changed
silently."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from builder.materials import calibrated
from builder.scene import speed_warning
from ground.errors import InputError
from ground.gate import runs_folder
from ground.launch import STYLE_LIBRARIES
from ground.paths import ROOT as LAMMPS_ROOT

from ..options import RUN_OPTIONS, on_ranks
from ..study import EXTENDABLE, STUDY_SCENE, Study, extends
from ..values import ANGLES

# runner study's run options (a study file's [run] takes every one).
STUDY_RUN = tuple(option for option in RUN_OPTIONS if option.study_cli)


class EnvironmentFault(RuntimeError):
    """Something every impact needs is missing: no impact is run or marked failed."""


def check_environment(study: Study) -> None:
    """The project's LAMMPS styles and every lattice's calibration, before any impact."""
    for library, _ in STYLE_LIBRARIES.values():
        path = LAMMPS_ROOT / "build" / library
        if not path.is_file():
            raise EnvironmentFault(f"{path} is missing: make setup builds it")
    for lattice in study.lattices:
        spec = study.spec({"lattice": lattice, "seed": study.first_seed, "gamma": 45.0})
        try:
            calibrated(spec.lattice, spec.k2_over_k1)
        except (OSError, ValueError) as error:
            raise EnvironmentFault(
                f"calibration/materials.json cannot give {lattice}: {error} "
                "(git checkout calibration/materials.json, or make calibrate)"
            ) from None


def study_from_args(args, preset: Study, file: Path | None = None) -> Study:
    """The study a `runner study` command names: ``preset``, its file's, or, if its
    folder holds a study, that study's study.json; the options given change
    it. A study that exists is never changed silently: an option that differs
    from its record is refused, but for --extend's more samples, lattices or angles,
    and so is a study file (``file``) that differs from what it said when the
    study was first run."""
    from dataclasses import replace

    name = args.name or args.preset
    record = runs_folder() / name / "study.json"
    existing = record.exists()
    base = Study.from_json(record) if existing else preset
    base = replace(base, name=name)
    said = replace(preset, name=name).grid()  # what the file says today
    file_changes = (
        file_changed(base.source, said, args.extend, name, file or args.preset) if existing else {}
    )
    if "samples" in file_changes:  # more than the file said before, never fewer than ran
        file_changes["samples"] = max(file_changes["samples"], base.samples)
    if "lattices" in file_changes:
        file_changes["lattices"] = tuple(dict.fromkeys((*base.lattices, *said["lattices"])))
    for key in ("angles", "cot_gamma", "options"):  # the file's, which only add (extends)
        if key in file_changes:
            file_changes[key] = getattr(preset, key)
    changes = {
        key: getattr(args, key)
        for key in ("samples", "angles", "vn", *(o.name for o in STUDY_SCENE))
        if getattr(args, key) is not None
    }
    for dest in ("lattices", "cot_gamma", "speeds"):
        values = getattr(args, dest) or []
        if len(set(values)) != len(values):
            raise InputError(
                f"--{dest.replace('_', '-')} names a value twice: {' '.join(map(str, values))}"
            )
    changes = {**file_changes, **changes}
    if args.lattices:
        changes["lattices"] = tuple(args.lattices)
    if args.cot_gamma:
        if args.angles is not None:
            raise InputError("--angles and --cot-gamma: give one of them")
        if len(args.cot_gamma) < ANGLES.low:
            raise InputError(f"--cot-gamma must give at least {ANGLES.low:g} angles")
        changes["cot_gamma"] = tuple(sorted(set(args.cot_gamma), reverse=True))
        changes["angles"] = len(changes["cot_gamma"])
    if args.speeds:
        if args.vn is not None:
            raise InputError("--vn and --speeds: give one of them")
        changes["speeds"] = tuple(sorted(args.speeds))
    elif args.vn is not None and base.speeds:
        changes["speeds"] = ()  # one speed: the study's axis collapses to --vn
    options = {
        o.name: getattr(args, o.name) for o in STUDY_RUN if getattr(args, o.name) is not None
    }
    if options:
        changes["options"] = replace(base.options, **options)
    if getattr(args, "ranks", None) is not None:
        changes["options"] = on_ranks(changes.get("options", base.options), args.ranks)
    study = replace(base, **changes, source=said)
    if existing:
        before, after = base.grid(), study.grid()
        differ = [key for key in after if after[key] != before.get(key)]
        refused = [
            k
            for k in differ
            if not (args.extend and k in EXTENDABLE and extends(k, before.get(k), after[k]))
        ]
        if refused:
            said = "; ".join(differences(refused, before, after, "there", "asked"))
            hint = (
                " (--extend adds samples, lattices or angles)"
                if set(refused) <= set(EXTENDABLE) and not args.extend
                else ""
            )
            raise InputError(
                f"--name {name}: {record.parent} holds a study with another grid: {said}; "
                f"leave the option out to use the study's{hint}, or give another --name"
            )
    elif args.report_only:
        raise InputError(f"--report-only: no study in {record.parent}; run it first")
    elif args.extend:
        raise InputError(f"--extend: no study in {record.parent} to extend")
    try:
        study.validate()
    except InputError as error:  # a value of the file's, or of the file's with the options'
        given = " with the options given" if set(changes) - set(file_changes) else ""
        raise InputError(f"{file or args.preset}{given}: {error}") from None
    if not args.report_only:
        check_environment(study)
        for vn in study.velocities():
            fast = [g for g in study.gammas() if speed_warning(vn, g)]
            if fast:
                print(
                    f"warning: at {len(fast)} angles from {fast[0]:g} degrees, "
                    f"{speed_warning(vn, fast[0])}",
                    file=sys.stderr,
                    flush=True,
                )
    return study


def differences(keys: list[str], before: dict, after: dict, then: str, now: str) -> list[str]:
    """Each of ``keys`` as 'key OLD then, NEW now'; a record's (the run's
    options) as the one field of it that differs, not the two records."""
    told = []
    for key in keys:
        old, new = before.get(key), after[key]
        if isinstance(old, dict) and isinstance(new, dict):
            told += [
                f"{key}.{k} {old.get(k)!r} {then}, {new.get(k)!r} {now}"
                for k in new
                if old.get(k) != new.get(k)
            ] or [f"{key} {old!r} {then}, {new!r} {now}"]
        else:
            told.append(f"{key} {old!r} {then}, {new!r} {now}")
    return told


def file_changed(
    source: dict | None, said: dict, extend: bool, name: str, file, ran: int | None = None
) -> dict:
    """What a study file changed since its study was first run (``source``,
    recorded in study.json) that --extend lets it change: more samples or
    lattices, as {field: value}. Samples grow if no fewer than the file
    said before nor than the study ran (``ran``).

    Raises
    ------
    ground.errors.InputError
        One line naming the file and what differs, for any other change (a
        record from before files were recorded has no ``source``: no check).
    """
    if source is None:
        return {}
    said = json.loads(json.dumps(said))  # tuples as JSON's lists, as recorded
    # a run option added since the study was first run: the file could not
    # give it, so it ran as that option's record from before says
    before = {o.name: o.recorded_before for o in RUN_OPTIONS}
    source = {**source, "options": {**before, **source.get("options", {})}}
    differ = [key for key in said if said[key] != source.get(key)]
    ran_samples = max(source.get("samples", 0), ran or 0)
    refused = [
        k
        for k in differ
        if not (
            extend
            and k in EXTENDABLE
            and extends(k, ran_samples if k == "samples" else source.get(k), said[k])
        )
    ]
    if refused:
        told = "; ".join(differences(refused, source, said, "then", "now"))
        hint = (
            "; --extend takes more samples, lattices or angles"
            if set(refused) <= set(EXTENDABLE) and not extend
            else ""
        )
        raise InputError(
            f"{file}: differs from what runs/{name}/ was first run with: "
            f"{told}{hint}; put the file back, or give another --name"
        )
    return {k: tuple(said[k]) if k == "lattices" else said[k] for k in differ}


def check_source(study: Study, file, extend: bool = False) -> None:
    """Refuse a study whose folder was first run from another version of its
    file (``file_changed``; with ``extend``, but for more samples or
    lattices); ``study.source`` is what the file says today."""
    record = study.folder / "study.json"
    if record.exists() and study.source is not None:
        recorded = Study.from_json(record)
        file_changed(recorded.source, study.source, extend, study.name, file, recorded.samples)
