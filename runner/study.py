"""The study of MODEL.md section 7: lattices x angles x samples, resumable.

Every impact has its own folder, runs/<study>/<lattice>/s<seed>/g<gamma>/;
it is finished when it holds result.json (written atomically, last) and
failed when it holds failed.json. A study that is started again runs only
what is neither, so a killed study loses nothing already done.
"""

from __future__ import annotations

import json
import os
import shutil
import socket
import sys
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from analysis.result import UnreadableResult, read_result
from builder.assembly import build_scene
from builder.lammps_data import write_bodies, write_scene
from builder.materials import STUDY_LATTICES, calibrated
from builder.outputs import NAME_MAX
from builder.scene import MODEL_READINGS, SEED, VN, SceneSpec, speed_warning, wall_spring_constant
from ground.checks import require_out_folder, word_problem
from ground.errors import InputError
from ground.launch import STYLE_LIBRARIES, data_to_restart
from ground.paths import ROOT, runs_folder
from ground.provenance import cpu_name

from .options import RunOptions, on_ranks
from .values import ANGLES, COT_GAMMA, SAMPLES  # noqa: F401 (the command line's too)

LATTICES = STUDY_LATTICES  # the study's lattice names (builder.materials)
# What a finished impact keeps: the rest (the data file above all, 1.5 MB) is
# rebuilt from its seed in a second if needed.
KEEP = ("result.json", "run.json", "scene.json", "series.dat", "energy.dat")
# The grid's numbers. A study larger than MAX_IMPACTS is refused with its
# size and the time it would take at IMPACTS_PER_WORKER_MINUTE, the paper
# study's rate per worker (1,010 per minute on 2 workers, docs/results.md).
MAX_IMPACTS = 200_000
IMPACTS_PER_WORKER_MINUTE = 505.0
# What may differ between a study's study.json and a command that resumes it
# with --extend: more samples, more lattices.
EXTENDABLE = ("samples", "lattices")
# An unreadable result.json is moved aside to this name, kept for a look, and
# its impact runs again.
CORRUPT = "result.json.corrupt"
# A result (or failure) on a wall of other springs than the study's (the
# triangular and square disks' walls before every lattice met the random
# disk's) is moved aside to a name with this suffix, and its impact runs again.
OTHER_WALL = ".other-wall"
# An impact's mark that a worker started it (runner/tasks.py), which
# rebuilding its scene leaves in its folder.
STARTED = "started.json"
# What rebuilding or pruning a folder leaves in it.
SET_ASIDE = (CORRUPT, "result.json" + OTHER_WALL, "failed.json" + OTHER_WALL)


def name_problem(name: str) -> str | None:
    """Why ``name`` cannot be a study's folder under runs/, or None.

    One folder, right under runs/: no path separator or '..', which would put
    it elsewhere, nor empty or '.', which would be runs/ itself; no whitespace,
    at which LAMMPS splits its commands (every impact would fail).
    """
    if name in ("", "."):
        return "must be a non-empty folder name"
    if os.sep in name or (os.altsep and os.altsep in name) or ".." in name:
        return "must be one folder under runs/, without '/' or '..'"
    if len(name.encode()) > NAME_MAX:
        return f"must be a folder name of at most {NAME_MAX} bytes ({len(name.encode())} given)"
    return word_problem(name)


def study_angles(count: int) -> list[float]:
    """Angles whose cotangents are evenly spaced in log from 10 to cot 80.5 degrees.

    Parameters
    ----------
    count : int
        Number of angles.

    Returns
    -------
    list of float
        Angles from the wall's normal, degrees, increasing, rounded to 1e-4.
    """
    psi = np.geomspace(10.0, 1.0 / np.tan(np.radians(80.5)), count)
    return [round(float(np.degrees(np.arctan(1.0 / p))), 4) for p in psi]


@dataclass
class Study:
    name: str
    lattices: tuple[str, ...] = tuple(LATTICES)
    angles: int = 16
    # explicit angles, as cot gamma; empty: `angles` of them log-spaced (study_angles)
    cot_gamma: tuple[float, ...] = ()
    samples: int = 100
    first_seed: int = 1
    vn: float = 0.1
    # impact speeds as a study axis (the speed preset); empty: `vn` alone
    speeds: tuple[float, ...] = ()
    n_disk: int = 800
    radius: float = SceneSpec.radius  # R; lengths and times scale with it
    roughness: float = SceneSpec.roughness
    roughness_length: float = SceneSpec.roughness_length  # R; 0: each point on its own
    wall_width: float = 8.0  # R; MODEL.md's, too short at grazing angles (docs/model.md)
    contact_a: float = 300.0  # a R at 800 points (contact_scaling spacing: docs/model.md)
    contact_scaling: str = SceneSpec.contact_scaling
    # the reading of the wall (MODEL.md section 8); None: twice the disk's points
    n_wall: int | str | None = SceneSpec.n_wall
    wall_ka: float | str = SceneSpec.wall_ka
    wall_fixed: str = SceneSpec.wall_fixed
    # the readings of the model (MODEL.md section 8; builder.scene.MODEL_READINGS)
    contact_mass: str = SceneSpec.contact_mass
    speed_unit: str = SceneSpec.speed_unit
    roughness_direction: str = SceneSpec.roughness_direction
    surface_row: str = SceneSpec.surface_row
    regular_surface: str = SceneSpec.regular_surface
    # what the disk hits: the wall, or a second disk (builder/binary.py), of
    # the disk's lattice unless partner_lattice names another
    target: str = SceneSpec.target
    partner_lattice: str | None = SceneSpec.partner_lattice
    partner: str = SceneSpec.partner  # or "image": the disk turned by 180 degrees
    options: RunOptions = field(default_factory=lambda: RunOptions(route="python"))
    # the grid its study file gave when the study was first run (study.json
    # keeps it): a file changed since is refused, not run on the old grid
    source: dict | None = field(default=None, compare=False, repr=False)

    @property
    def folder(self) -> Path:
        return runs_folder() / self.name

    def validate(self) -> None:
        if problem := name_problem(self.name):
            raise InputError(f"name {problem}, got {self.name!r}")
        require_out_folder(f"--name {self.name}", self.folder)
        if not self.lattices:
            raise InputError(f"lattices must be among {', '.join(LATTICES)}; got none")
        for lattice in self.lattices:
            if not isinstance(lattice, str) or lattice not in LATTICES:
                raise InputError(f"lattices must be among {', '.join(LATTICES)}; got {lattice!r}")
        if len(set(self.lattices)) != len(self.lattices):
            raise InputError(f"lattices names a lattice twice: {' '.join(self.lattices)}")
        ANGLES.check("angles", self.angles)
        for value in self.cot_gamma:
            COT_GAMMA.check("cot_gamma", value)
        if self.cot_gamma and len(self.cot_gamma) != self.angles:
            raise InputError(
                f"angles must be the number of cot_gamma values ({len(self.cot_gamma)}), "
                f"got {self.angles}"
            )
        SAMPLES.check("samples", self.samples)
        SEED.check("first_seed", self.first_seed)
        last = self.first_seed + self.samples - 1
        if last > SEED.high:  # every sample's seed, not the first alone
            raise InputError(
                f"first_seed + samples - 1 must be at most {SEED.high:.0f} (the last seed), got "
                f"{self.first_seed} + {self.samples} - 1 = {last}"
            )
        VN.check("vn", self.vn)
        for value in self.speeds:
            VN.check("speeds", value)
        # one folder per angle and speed: values that share one would run once
        # and count twice (g<gamma to 1e-4 degrees>, v<speed>)
        for what, words in (
            ("cot_gamma", [f"g{g:.4f}" for g in self.gammas()]),
            ("speeds", [f"v{v:g}" for v in self.speeds]),
        ):
            if len(set(words)) != len(words):
                twice = sorted({w for w in words if words.count(w) > 1})
                raise InputError(
                    f"{what} names an impact's folder twice ({', '.join(twice)}): "
                    "give distinct values"
                )
        size = self.samples * self.angles * len(self.lattices) * len(self.velocities())
        if size > MAX_IMPACTS:
            hours = size / (IMPACTS_PER_WORKER_MINUTE * 2) / 60.0
            raise InputError(
                f"samples x angles x lattices x speeds must be at most {MAX_IMPACTS} impacts, "
                f"got {self.samples} x {self.angles} x {len(self.lattices)} x "
                f"{len(self.velocities())} = {size}, about "
                f"{hours:,.0f} hours on 2 workers of this project's machine"
            )
        regular = [x for x in self.lattices if LATTICES[x]["lattice"] != "random"]
        if self.regular_surface != SceneSpec.regular_surface and not regular:
            raise InputError(
                f"--regular-surface {self.regular_surface} applies to the triangular and square "
                "disks, and the study has none"
            )
        if self.surface_row != SceneSpec.surface_row and self.regular_surface == "lattice":
            if len(regular) == len(self.lattices):
                raise InputError(
                    f"--surface-row {self.surface_row}: no disk of the study has a surface row "
                    "(with --regular-surface lattice a regular disk's surface is its own points)"
                )
        self.options.validate()
        for lattice in self.lattices:  # once here, rather than in every impact
            self.spec({"lattice": lattice, "seed": self.first_seed, "gamma": 45.0}).validate()

    def velocities(self) -> list[float]:
        """The study's normal approach speeds, increasing."""
        return sorted(self.speeds) if self.speeds else [self.vn]

    def gammas(self) -> list[float]:
        """The study's angles from the wall's normal, degrees, rounded to 1e-4."""
        if self.cot_gamma:
            return [round(float(np.degrees(np.arctan(1.0 / c))), 4) for c in self.cot_gamma]
        return study_angles(self.angles)

    def grid(self) -> dict:
        """What the study's tables depend on, as study.json records it."""
        values = asdict(self)
        values.pop("name")
        values.pop("source")
        return values

    @classmethod
    def from_json(cls, path: Path) -> Study:
        """The study a study.json records; fields it lacks (older studies) take
        their defaults, keys that are not fields (wall_clock) are skipped."""
        try:
            info = json.loads(path.read_text())
            fields = {k: v for k, v in info.items() if k in cls.__dataclass_fields__}
            fields["lattices"] = tuple(fields.get("lattices", cls.lattices))
            fields["cot_gamma"] = tuple(fields.get("cot_gamma", ()))
            fields["speeds"] = tuple(fields.get("speeds", ()))
            options = fields.pop("options", {})
            known = RunOptions.__dataclass_fields__
            return cls(
                **fields, options=RunOptions(**{k: v for k, v in options.items() if k in known})
            )
        except (OSError, ValueError, TypeError) as error:
            raise InputError(f"{path}: not a study's record ({error})") from None

    def jobs(self) -> list[dict]:
        """Every impact, grouped by sample: (lattice, seed), then speed and angle.
        A study with a speed axis has a folder per speed above the angles'."""
        out = []
        for seed in range(self.first_seed, self.first_seed + self.samples):
            for lattice in self.lattices:
                for vn in self.velocities():
                    sample = self.folder / lattice / f"s{seed}"
                    if self.speeds:
                        sample = sample / f"v{vn:g}"
                    for gamma in self.gammas():
                        folder = sample / f"g{gamma:.4f}"
                        out.append(
                            {
                                "lattice": lattice,
                                "seed": seed,
                                "gamma": gamma,
                                "vn": vn,
                                "folder": str(folder),
                            }
                        )
        return out

    def spec(self, job: dict) -> SceneSpec:
        """The scene of a job. The regular disks' surface reading applies to them
        only; where their surface is the lattice's own, they have no row to place."""
        regular = LATTICES[job["lattice"]]["lattice"] != "random"
        own_surface = regular and self.regular_surface == "lattice"
        return SceneSpec(
            contact_mass=self.contact_mass,
            speed_unit=self.speed_unit,
            roughness_direction=self.roughness_direction,
            surface_row="even" if own_surface else self.surface_row,
            regular_surface=self.regular_surface if regular else SceneSpec.regular_surface,
            seed=job["seed"],
            gamma_deg=job["gamma"],
            vn=job.get("vn", self.vn),
            radius=self.radius,
            n_disk=self.n_disk,
            roughness=self.roughness,
            roughness_length=self.roughness_length,
            wall_width=self.wall_width,
            contact_a=self.contact_a,
            contact_scaling=self.contact_scaling,
            n_wall=self.n_wall,
            wall_ka=self.wall_ka,
            wall_fixed=self.wall_fixed,
            target=self.target,
            partner_lattice=self.partner_lattice,
            partner=self.partner,
            **LATTICES[job["lattice"]],
        )

    def prepare(self, retry_failed: bool = False) -> list[dict]:
        """Check the study, record it in its folder, and return its jobs."""
        self.validate()
        self.folder.mkdir(parents=True, exist_ok=True)
        # common_wall: every lattice meets the same wall (builder.scene.wall_spring_constant),
        # which the results page reads; study.json files from before lack it
        record = {**asdict(self), "common_wall": True}
        path = self.folder / "study.json"
        if path.exists():  # the whole study's time stays while its grid does
            old = json.loads(path.read_text())
            if "wall_clock" in old and Study.from_json(path).grid() == self.grid():
                record["wall_clock"] = old["wall_clock"]
        path.write_text(json.dumps(record, indent=1))
        jobs = self.jobs()
        if retry_failed:
            for job in jobs:
                (Path(job["folder"]) / "failed.json").unlink(missing_ok=True)
        for job in jobs:
            set_aside_if_unreadable(job)
            if self.target == "wall":
                set_aside_if_other_wall(job, wall_spring_constant(self.spec(job))[0])
        return jobs

    def build(self, job: dict) -> Path:
        """The job's scene, written afresh into its folder (an impact killed
        half-way starts over); a result moved aside stays. The data file is
        its sample's bodies, written once per process (``SAMPLE_BODIES``);
        on several ranks, the impact's own placed scene."""
        folder = Path(job["folder"])
        folder.mkdir(parents=True, exist_ok=True)
        for path in folder.iterdir():
            if path.name not in (*SET_ASIDE, STARTED):
                shutil.rmtree(path) if path.is_dir() else path.unlink()
        scene = build_scene(self.spec(job))
        if self.options.nprocs > 1:  # the placed scene, as runner impact --np runs it: on
            # several ranks the bodies' restart has another box, so another decomposition
            return write_scene(scene, folder, self.options.springs)
        bodies = SAMPLE_BODIES.path(scene, self.options.springs, self.folder, folder / "log.lammps")
        return write_scene(scene, folder, self.options.springs, bodies=bodies, restart=True)

    def summary(self, jobs: list[dict]) -> dict:
        counts = {s: sum(state(j) == s for j in jobs) for s in ("done", "failed", "pending")}
        stuck = sum(failed_state(j) == "stuck" for j in jobs if state(j) == "failed")
        said = f", {stuck} on the wall at tmax" if stuck else ""
        print(
            f"study {self.name}: {counts['done']} done, {counts['failed'] - stuck} failed{said}",
            flush=True,
        )
        return counts


# Where a study's workers keep the bodies of the samples they run: a folder
# per worker process under the study's folder, which the driver removes when
# the study's run ends (a worker that LAMMPS ended cannot clean up itself).
BODIES_FOLDER = ".bodies"


class SampleBodies:
    """The bodies of the samples this process runs, as binary restarts of
    their data files: one per sample (its bodies in their own frames, which
    its angles and speeds share; the deck places the disk), in the study's
    runs/<study>/.bodies/<host>-<pid>/, the last few kept. Only the disk's
    placement and velocity differ between a sample's impacts
    (builder.lammps_data); the restart is read in a tenth of the data file's
    time, into the same atoms in the same order (tests/runner/test_sample_bodies.py;
    on one rank: on several, LAMMPS splits the box among them, and a restart
    of the unplaced bodies has another box than a placed data file)."""

    KEPT = 8

    def __init__(self) -> None:
        self.files: dict[str, Path] = {}
        self.written = 0

    def path(self, scene, springs: str, study_folder: Path, log: Path) -> Path:
        """The restart of ``scene``'s sample, written if this process has not.

        LAMMPS writes it with its log in ``log`` (an impact's log.lammps: an
        error there, which ends this process, is its impact's failure).

        Raises
        ------
        ground.errors.InputError
            If the folder's path is not one word, which LAMMPS needs.
        """
        spec = asdict(scene.spec)
        for placement in ("gamma_deg", "vn", "contact_time_guess", "start_gap"):
            spec.pop(placement)
        key = json.dumps([spec, springs, str(study_folder)], sort_keys=True)
        # a run of the study that ended removed its workers' folders, also
        # under a worker that a joined cluster keeps for the next run
        if key not in self.files or not self.files[key].is_file():
            folder = study_folder / BODIES_FOLDER / f"{socket.gethostname()}-{os.getpid()}"
            if problem := word_problem(str(folder)):
                raise InputError(f"the workers' folder for the bodies {problem}: {folder}")
            folder.mkdir(parents=True, exist_ok=True)
            self.files.pop(key, None)
            if len(self.files) >= self.KEPT:
                self.files.pop(next(iter(self.files))).unlink(missing_ok=True)
            self.written += 1
            data = folder / f"{scene.spec.lattice}-s{scene.spec.seed}-{self.written}.data"
            write_bodies(scene, data, springs)
            self.files[key] = data_to_restart(data, data.with_suffix(".restart"), springs, log)
            data.unlink()
        return self.files[key]


SAMPLE_BODIES = SampleBodies()


class EnvironmentFault(RuntimeError):
    """Something every impact needs is missing: no impact is run or marked failed."""


def check_environment(study: Study) -> None:
    """The project's LAMMPS styles and every lattice's calibration, before any impact."""
    for library, _ in STYLE_LIBRARIES.values():
        path = ROOT / "build" / library
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


def study_from_args(args, file: Path | None = None) -> Study:
    """The study a `runner study` command names: the preset's, or, if its
    folder holds a study, that study's study.json; the options given change
    it. A study that exists is never changed silently: an option that differs
    from its record is refused, but for --extend's more samples or lattices,
    and so is a study file (``file``) that differs from what it said when the
    study was first run."""
    from dataclasses import replace

    name = args.name or args.preset
    record = runs_folder() / name / "study.json"
    existing = record.exists()
    base = Study.from_json(record) if existing else PRESETS[args.preset]
    base = replace(base, name=name)
    said = replace(PRESETS[args.preset], name=name).grid()  # what the file says today
    file_changes = (
        file_changed(base.source, said, args.extend, name, file or args.preset) if existing else {}
    )
    if "samples" in file_changes:  # more than the file said before, never fewer than ran
        file_changes["samples"] = max(file_changes["samples"], base.samples)
    if "lattices" in file_changes:
        file_changes["lattices"] = tuple(dict.fromkeys((*base.lattices, *said["lattices"])))
    changes = {
        key: getattr(args, key)
        for key in (
            "samples",
            "angles",
            "vn",
            "roughness",
            "roughness_length",
            "n_disk",
            "radius",
            "wall_width",
            "contact_a",
            "contact_scaling",
            "n_wall",
            "wall_ka",
            "wall_fixed",
            *MODEL_READINGS,
            "target",
            "partner_lattice",
            "partner",
        )
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
        key: getattr(args, key) for key in ("dt", "max_drift") if getattr(args, key) is not None
    }
    if options:
        changes["options"] = replace(base.options, **options)
    if getattr(args, "ranks", None) is not None:
        changes["options"] = on_ranks(changes.get("options", base.options), args.ranks)
    study = replace(base, **changes, source=said)
    if existing:
        before, after = base.grid(), study.grid()
        differ = [key for key in after if after[key] != before.get(key)]
        grows = {
            "samples": study.samples >= base.samples,
            "lattices": set(base.lattices) <= set(study.lattices),
        }
        refused = [k for k in differ if not (args.extend and k in EXTENDABLE and grows[k])]
        if refused:
            said = "; ".join(f"{k} {before.get(k)!r} there, {after[k]!r} asked" for k in refused)
            hint = (
                " (--extend adds samples or lattices)"
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


def file_changed(source: dict | None, said: dict, extend: bool, name: str, file) -> dict:
    """What a study file changed since its study was first run (``source``,
    recorded in study.json) that --extend lets it change: more samples or
    lattices, as {field: value}.

    Raises
    ------
    ground.errors.InputError
        One line naming the file and what differs, for any other change (a
        record from before files were recorded has no ``source``: no check).
    """
    if source is None:
        return {}
    said = json.loads(json.dumps(said))  # tuples as JSON's lists, as recorded
    differ = [key for key in said if said[key] != source.get(key)]
    grows = {
        "samples": said["samples"] >= source.get("samples", 0),
        "lattices": set(source.get("lattices", ())) <= set(said["lattices"]),
    }
    refused = [k for k in differ if not (extend and k in EXTENDABLE and grows[k])]
    if refused:
        told = "; ".join(f"{k} {source.get(k)!r} then, {said[k]!r} now" for k in refused)
        hint = (
            "; --extend takes more samples or lattices"
            if set(refused) <= set(EXTENDABLE) and not extend
            else ""
        )
        raise InputError(
            f"{file}: differs from what runs/{name}/ was first run with: "
            f"{told}{hint}; put the file back, or give another --name"
        )
    return {k: tuple(said[k]) if k == "lattices" else said[k] for k in differ}


def check_source(study: Study, file) -> None:
    """Refuse a study whose folder was first run from another version of its
    file (``file_changed``); ``study.source`` is what the file says today."""
    record = study.folder / "study.json"
    if record.exists() and study.source is not None:
        file_changed(Study.from_json(record).source, study.source, False, study.name, file)


def record_wall_clock(study: Study, seconds: float, counts: dict) -> None:
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


def load_presets() -> tuple[dict, dict, dict, dict, dict]:
    """The study files in studies/ (runner/study_file.py): each study by its
    name; the page in docs/ of those that have one; the axes of those that
    have any; the readings their pages tabulate; their pages' sections."""
    from .study_file import STUDIES, read_study_file

    found = ({}, {}, {}, {}, {})
    for path in sorted(STUDIES.glob("*.toml")):
        register(path.stem, read_study_file(path), *found)
    return found


def register(
    name: str, described, presets=None, pages=None, axes=None, readings=None, sections=None
) -> None:
    """A study file's study under ``name`` in the registries (by default this
    module's PRESETS, DOC_PAGES, AXES, READINGS, PAGE_SECTIONS)."""
    presets = PRESETS if presets is None else presets
    presets[name] = described.study
    STUDY_FILES[name] = described
    for registry, value in (
        (DOC_PAGES if pages is None else pages, described.page),
        (AXES if axes is None else axes, described.axes),
        (READINGS if readings is None else readings, described.readings),
        (PAGE_SECTIONS if sections is None else sections, described.sections),
    ):
        if value:
            registry[name] = value


def built_in_pages() -> tuple[dict, dict]:
    """The pages in docs/ of the study files in studies/ and the readings
    those pages tabulate, by study (not those of a file of one's own)."""
    built_in = [name for name, described in STUDY_FILES.items() if described.built_in]
    return (
        {name: DOC_PAGES[name] for name in built_in if name in DOC_PAGES},
        {name: READINGS[name] for name in built_in if name in READINGS},
    )


# The studies of studies/*.toml (paper, demo, speed, grazing, ...), the pages
# under docs/ of those that have one (written only with --docs), the axes of
# those that run once per combination of some options' values, and the
# readings (docs/<name>/ tables of the same study) that a page tabulates, and
# the sections of the pages that do not have all (analysis.report.SECTIONS).
STUDY_FILES: dict = {}  # what each study file of PRESETS says (runner.study_file.StudyFile)
PRESETS, DOC_PAGES, AXES, READINGS, PAGE_SECTIONS = load_presets()


def state(job: dict) -> str:
    folder = Path(job["folder"])
    if (folder / "result.json").exists():
        return "done"
    if (folder / "failed.json").exists():
        return "failed"
    return "pending"


def failed_state(job: dict) -> str:
    """A failed impact's state: failed, or stuck (analysis.sections.impact_state)."""
    from analysis.study_tables import read_failure

    return read_failure(job)["state"]


def set_aside_if_unreadable(job: dict) -> None:
    """Move an unreadable result.json to result.json.corrupt, so that its
    impact counts as not run (a half-written file cannot come from this
    program, which writes atomically, but from a full disk or a copy)."""
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
    recorded = json.loads(scene.read_text())["ka_wall"]
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
            path.unlink()
