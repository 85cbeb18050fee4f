"""The study of docs/model.md section 7: lattices x angles x samples, resumable.

A study is plain data (``Study``): its grid, its scene and its run. Its
impacts' folders follow runner/study/folders.py's protocol; the study files of
studies/ are read on demand (runner/study/studies.py).
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict, field
from pathlib import Path

import numpy as np

from builder.assembly import build_scene
from builder.declared import with_options
from builder.lammps_data import write_scene
from builder.materials import STUDY_LATTICES
from builder.outputs import NAME_MAX
from builder.scene import SCENE_OPTIONS, SEED, VN, SceneSpec, wall_spring_constant
from ground.checks import portable_problem, require_out_folder, word_problem
from ground.errors import InputError
from ground.gate import (
    gate,
    make_folder,
    remove,
    runs_folder,  # noqa: F401 (the command line's too)
    write_text,
)
from ground.paths import ROOT  # noqa: F401 (the command line's ROOT too)

from ..options import RunOptions
from ..values import ANGLES, COT_GAMMA, SAMPLES
from .folders import (
    SET_ASIDE,
    STARTED,
    check_made_as_asked,
    failed_state,
    set_aside_if_other_wall,
    set_aside_if_unreadable,
    state,
)
from .sample_bodies import SAMPLE_BODIES

LATTICES = STUDY_LATTICES  # the study's lattice names (builder.materials)
# The grid's numbers. A study larger than MAX_IMPACTS is refused with its
# size and the time it would take at IMPACTS_PER_WORKER_MINUTE, the paper
# study's rate per worker (1,010 per minute on 2 workers, docs/studies/results/results.md).
MAX_IMPACTS = 200_000
IMPACTS_PER_WORKER_MINUTE = 505.0
# What may differ between a study's study.json and a command that resumes it
# with --extend: more samples, more lattices.
EXTENDABLE = ("samples", "lattices", "angles", "cot_gamma", "options")


def extends(key: str, before, after) -> bool:
    """Whether ``after`` only adds to ``before`` in a study's grid field
    ``key`` (an EXTENDABLE one): more samples, lattices or explicit angles
    (every angle before among them), or run options that differ only in
    what does not change a done impact (study.folders.RUN_ANY_WAY)."""
    from .folders import RUN_ANY_WAY

    if key == "samples":
        return after >= before
    if key == "lattices":
        return set(before) <= set(after)
    if key == "cot_gamma":
        return bool(before) and set(before) <= set(after)
    if key == "angles":
        return after >= before
    if key == "options":
        return all(before.get(k) == v for k, v in after.items() if k not in RUN_ANY_WAY)
    return False


_cap = [MAX_IMPACTS]


def impact_cap(impacts: int | None = None) -> int:
    """The most impacts a command may run (a study, or every combination of a
    study file's axes together): MAX_IMPACTS, or what --max-impacts allows
    (``impacts``, set once by the command line)."""
    if impacts is not None:
        _cap[0] = impacts
    return _cap[0]


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
    return word_problem(name) or portable_problem(name)


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


# The scene's options a study takes (builder.scene.SCENE_OPTIONS): Study's
# fields, a study file's [scene] keys, runner study's options, study.json's.
STUDY_SCENE = tuple(option for option in SCENE_OPTIONS if option.study)


@with_options(STUDY_SCENE, after="speeds")
class Study:
    """A study: its grid (lattices x angles x samples, speeds), its scene's
    options (STUDY_SCENE, a field each) and its run (``options``)."""

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
    # here: the scene's options a study takes (STUDY_SCENE), in their table's order
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
        size = self.size()
        if size > impact_cap():
            hours = size / (IMPACTS_PER_WORKER_MINUTE * 2) / 60.0
            raise InputError(
                f"samples x angles x lattices x speeds must be at most {impact_cap()} impacts, "
                f"got {self.samples} x {self.angles} x {len(self.lattices)} x "
                f"{len(self.velocities())} = {size}, about "
                f"{hours:,.0f} hours on 2 workers of this project's machine "
                "(--max-impacts allows more)"
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
            job = {"lattice": lattice, "seed": self.first_seed, "gamma": 45.0}
            self.spec(job).validate()
            # the slowest speed at the largest angle: the longest run, the farthest start
            slowest = self.spec({**job, "vn": min(self.velocities()), "gamma": max(self.gammas())})
            if problem := self.options.scene_problem(slowest):
                raise InputError(problem)

    def size(self) -> int:
        """How many impacts the study has."""
        return self.samples * self.angles * len(self.lattices) * len(self.velocities())

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
            info = json.loads(path.read_text(encoding="utf-8"))
            if not isinstance(info, dict):
                raise TypeError(f"a JSON {type(info).__name__}, not an object")
            fields = {k: v for k, v in info.items() if k in cls.__dataclass_fields__}
            fields["lattices"] = tuple(fields.get("lattices", cls.lattices))
            fields["cot_gamma"] = tuple(fields.get("cot_gamma", ()))
            fields["speeds"] = tuple(fields.get("speeds", ()))
            options = fields.pop("options", {})
            known = RunOptions.__dataclass_fields__
            return cls(
                **fields, options=RunOptions(**{k: v for k, v in options.items() if k in known})
            )
        except (OSError, ValueError, TypeError, AttributeError) as error:
            raise InputError(
                f"{path}: not a study's record ({error}); remove it: the next run records the "
                "study again and checks every finished impact against it"
            ) from None

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
        scene = {option.name: getattr(self, option.name) for option in STUDY_SCENE}
        scene["surface_row"] = "even" if own_surface else self.surface_row
        scene["regular_surface"] = self.regular_surface if regular else SceneSpec.regular_surface
        return SceneSpec(
            **scene,
            seed=job["seed"],
            gamma_deg=job["gamma"],
            vn=job.get("vn", self.vn),
            **LATTICES[job["lattice"]],
        )

    def prepare(self, retry_failed: bool = False) -> list[dict]:
        """Check the study, record it in its folder, and return its jobs."""
        self.validate()
        make_folder(self.folder, "--name")
        # common_wall: every lattice meets the same wall (builder.scene.wall_spring_constant),
        # which the results page reads; study.json files from before lack it
        record = {**asdict(self), "common_wall": True}
        path = self.folder / "study.json"
        if path.exists():  # the whole study's time stays while its grid does
            old = json.loads(path.read_text())
            if "wall_clock" in old and Study.from_json(path).grid() == self.grid():
                record["wall_clock"] = old["wall_clock"]
        jobs = self.jobs()
        for job in jobs:  # a link in the study's folder may not lead a write elsewhere
            gate(job["folder"], f"study {self.name}")
        if retry_failed:
            for job in jobs:
                (Path(job["folder"]) / "failed.json").unlink(missing_ok=True)
        for job in jobs:
            set_aside_if_unreadable(job)
            if self.target == "wall":
                set_aside_if_other_wall(job, wall_spring_constant(self.spec(job))[0])
        self.check_done(jobs)  # before study.json says the study is this one
        write_text(path, json.dumps(record, indent=1))
        return jobs

    def check_done(self, jobs: list[dict]) -> None:
        """Refuse finished impacts that another study made (runner.study.folders:
        every option of their scene and run against the study's), whatever
        study.json says; unreadable records are set aside and run again."""
        for job in jobs:
            if (Path(job["folder"]) / "result.json").exists():
                spec = self.spec(job)
                check_made_as_asked(job, asdict(spec), self.options.for_scene(spec))

    def build(self, job: dict) -> Path:
        """The job's scene, written afresh into its folder (an impact killed
        half-way starts over); a result moved aside stays. The data file is
        its sample's bodies, written once per process (``SAMPLE_BODIES``);
        on several ranks, the impact's own placed scene."""
        folder = Path(job["folder"])
        if folder.is_symlink():  # its own folder, never a link's target emptied
            remove(folder)
        make_folder(folder)
        for path in folder.iterdir():
            if path.name not in (*SET_ASIDE, STARTED):
                remove(path)
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
