"""Study files: a study's grid, scene and run in studies/<name>.toml.

    # studies/paper.toml
    page = "results"                 # its folder in docs/studies/ (--docs), if any
    readings = []                    # docs/studies/<name>/: tables of the same study,
                                     # other readings, which the page tabulates
    sections = [...]                 # what its page reports, in order (default:
                                     # every one of builder.study_names.SECTIONS)
    [grid]
    lattices = ["random", "triangular", "square_nu0.1", "square_nu0.3"]
    angles = 16                      # or cot_gamma = [...] or gamma_deg = [...]
    samples = 100
    vn = 0.1                         # or speeds = [...]: a folder per speed
    [scene]                          # builder.scene's readings, n_disk, ...
    [run]                            # runner.options.RunOptions: dt, ...; and
    ranks = 2                        # MPI ranks per impact (lmp under mpirun, or
                                     # srun in a Slurm job), a worker owning as many cores

Every key is a field of ``runner.study.Study`` (grid and scene) or of
``RunOptions`` (run); what a file leaves out takes the default. The study's
name is the file's. The command line's options override the file's, and
study.json records what ran.

A scene or run option given a list of values is an axis: the study runs once
for every combination of the axes' values, each a study of its own named
<name>_<option>-<value>..., and their impacts.csv rows go together into
runs/<name>/impacts.csv (whose columns record every reading and run option).

    [scene]
    wall_ka = [1.0, 10.0]            # two studies: <name>_wall_ka-1, <name>_wall_ka-10

A resolution study may give ``[grid] samples`` as a list, the seeds of each
``[scene] n_disk`` value in order (``samples = [476, 80, 48]`` with
``n_disk = [800, 1600, 3200]``): a multilevel allocation's seeds per level.

``sweep = "one-at-a-time"`` instead of the default ``"cross"`` runs each axis's
values with the other axes at their base, each axis's first value (a 1-D
sweep around one point). ``[scene] wall = "1600_10ka_sides"`` and ``model =
"disk-mass"`` name a reading of the wall and of the model
(analysis.kinds.readings.WALLS, MODELS) instead of spelling out their options; a
list of names is an axis too. ``kind`` picks the page (analysis.kinds: the
default ``results``, or a readings study's page made from its table), and a
readings study's ``[rerun]`` runs the best readings of the first pass again:

    kind = "scene_readings"
    [rerun]
    best = 5                         # the 5 best readings by the page's rule
    samples = 30                     # again, to 30 samples
    default = false                  # and today's default reading with them
    then_lattices = ["triangular"]   # then these disks ...
    then_best = 3                    # ... on the 3 best (ranked again)
"""

from __future__ import annotations

import itertools
import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

from builder.materials import STUDY_LATTICES
from builder.outputs import page_problem
from builder.study_names import FIT_ANGLES, FIT_SEEDS, KINDS, NAMED, READINGS_KINDS
from builder.study_names import SECTIONS as PAGE_SECTIONS
from ground.checks import plain_zero
from ground.errors import InputError
from ground.paths import STUDIES

from ..options import RANKS, RunOptions, on_ranks
from ..values import COT_GAMMA, VALUES
from . import Study

GRID = ("lattices", "angles", "cot_gamma", "gamma_deg", "samples", "first_seed", "vn", "speeds")
SECTIONS = ("grid", "scene", "run", "rerun")
# Fields that take a list: the study's own axes.
LISTS = ("lattices", "cot_gamma", "gamma_deg", "speeds")
# The grid's numbers that may be an axis (a study each), besides every scene
# and run option: v_n (unlike speeds, whose values share one study).
GRID_AXES = ("vn",)
SWEEPS = ("cross", "one-at-a-time")
# [rerun]'s keys and their defaults.
RERUN = {"best": 0, "samples": 0, "default": False, "then_lattices": [], "then_best": 0}


def study_path(name_or_path: str) -> Path:
    """studies/<name>.toml for a bare name, else the path given.

    Raises
    ------
    ground.errors.InputError
        If there is no such file (naming the studies there are).
    """
    path = Path(name_or_path)
    if path.suffix != ".toml" and len(path.parts) == 1:
        path = STUDIES / f"{name_or_path}.toml"
    if not path.is_file():
        known = ", ".join(sorted(p.stem for p in STUDIES.glob("*.toml")))
        raise InputError(
            f"study must be a study file or one of {known} (studies/), got {name_or_path!r}"
        )
    return path


@dataclass(frozen=True)
class StudyFile:
    """What a study file says: the study, its page in docs/ ('' for none),
    its axes (option -> values) and the readings its page tabulates (names
    of docs/ folders holding the same study's tables under other options)."""

    study: Study
    page: str = ""
    axes: dict = field(default_factory=dict)
    readings: tuple[str, ...] = ()
    sections: tuple[str, ...] = ()  # of builder.study_names.SECTIONS; () for all
    kind: str = "results"  # of analysis.kinds.KINDS
    sweep: str = "cross"  # of SWEEPS
    rerun: dict = field(default_factory=dict)  # [rerun], for a readings kind
    named: dict = field(default_factory=dict)  # wall/model names given as one value
    # n_disk -> seeds, where [grid] samples is a list (samples_by_level); {} else
    level_samples: dict = field(default_factory=dict)
    path: Path | None = field(default=None, compare=False)  # the file read

    @property
    def built_in(self) -> bool:
        """Whether the file is studies/<name>.toml, whose page is the project's."""
        return self.path is not None and self.path.resolve().parent == STUDIES.resolve()


def cot_of_degrees(degrees: float) -> float:
    """cot gamma of an angle in degrees, to 6 decimals (what a study's folder names keep)."""
    return round(1.0 / math.tan(math.radians(degrees)), 6)


# The deepest a study file's tables and lists nest (its deepest, [grid] lists
# of lists, is 3).
MAX_NESTING = 8


def nesting(value, depth: int = 0) -> int:
    """How deep ``value``'s lists and tables nest (a plain value: 0)."""
    if depth > MAX_NESTING:
        return depth
    children = (
        value.values() if isinstance(value, dict) else value if isinstance(value, list) else ()
    )
    return max((nesting(child, depth + 1) for child in children), default=depth)


def read_study_file(path: Path) -> StudyFile:
    """The study a file describes, its page, axes and readings.

    Returns
    -------
    StudyFile

    Raises
    ------
    ground.errors.InputError
        One line naming the file and the key, for a key that is not an
        option, a value of the wrong kind, or a file that is not TOML.
    """
    try:
        # utf-8-sig: a byte-order mark (some editors write one) is read, not refused
        parsed = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except UnicodeDecodeError as error:
        raise InputError(f"{path}: not a study file (not UTF-8 text: {error.reason} at byte "
                         f"{error.start})") from None  # fmt: skip
    except (OSError, tomllib.TOMLDecodeError) as error:
        raise InputError(f"{path}: not a study file ({error})") from None
    except RecursionError:  # tomllib recurses into each nested array or table
        raise InputError(
            f"{path}: a study file nests at most {MAX_NESTING} deep; this one deeper"
        ) from None
    if nesting(parsed) > MAX_NESTING:
        raise InputError(f"{path}: a study file nests at most {MAX_NESTING} deep; this one deeper")
    data = plain_zero(parsed)
    if not data:  # never the default study run in its place
        raise InputError(
            f"{path}: an empty study file; give at least one key (python -m runner study "
            "demo's file, studies/demo.toml, is a start)"
        )
    page = data.pop("page", "")
    if page != "" and (problem := page_problem(page)):
        raise InputError(f"{path}: page {problem}, got {page!r}")
    readings = data.pop("readings", [])
    if not isinstance(readings, list) or any(page_problem(r, tables=True) for r in readings):
        raise InputError(
            f"{path}: readings must be a list of plain names (docs/studies/<name>/), "
            f"got {readings!r}"
        )
    if len(set(readings)) != len(readings) or page in readings:
        raise InputError(f"{path}: readings names a table twice, got {readings!r}")
    if readings and not page:
        raise InputError(f"{path}: readings are tabulated on the study's page: give page")
    sections = data.pop("sections", [])
    if (
        not isinstance(sections, list)
        or not all(isinstance(name, str) and name in PAGE_SECTIONS for name in sections)
        or len(set(sections)) != len(sections)
    ):
        raise InputError(
            f"{path}: sections must be a list of distinct names among {', '.join(PAGE_SECTIONS)}, "
            f"got {sections!r}"
        )
    kind = data.pop("kind", "results")
    if not isinstance(kind, str) or kind not in KINDS:
        raise InputError(f"{path}: kind must be one of {', '.join(KINDS)}, got {kind!r}")
    sweep = data.pop("sweep", "cross")
    if not isinstance(sweep, str) or sweep not in SWEEPS:
        raise InputError(f"{path}: sweep must be one of {', '.join(SWEEPS)}, got {sweep!r}")
    unknown = set(data) - set(SECTIONS)
    if unknown:
        raise InputError(
            f"{path}: {sorted(unknown)[0]!r} is not a section; sections: {', '.join(SECTIONS)} "
            "(and page, readings, sections, kind, sweep)"
        )
    if kind != "results" and (sections or readings):
        raise InputError(f"{path}: sections and readings are a results page's, not a {kind} page's")
    rerun = read_rerun(path, data.pop("rerun", {}), kind)
    study_fields = {f.name for f in fields(Study)} - {"name", "options", "source"}
    allowed = {
        "grid": set(GRID),
        "scene": (study_fields - set(GRID)) | set(NAMED),
        "run": {f.name for f in fields(RunOptions)} | {"ranks"},
    }
    values: dict = {}
    axes: dict = {}
    level_samples: tuple[int, ...] = ()
    for section in ("grid", "scene", "run"):
        table = data.get(section, {})
        if not isinstance(table, dict):
            raise InputError(f"{path}: [{section}] must be a table of options")
        for key, value in table.items():
            if key not in allowed[section]:
                raise InputError(
                    f"{path}: [{section}] has no option {key!r}; options: "
                    f"{', '.join(sorted(allowed[section]))}"
                )
            where = f"{path}: [{section}] {key}"
            if (section, key) == ("run", "ranks"):  # one value: not an axis
                RANKS.check(f"{where} (MPI ranks per impact)", value)
            elif key in NAMED:
                for name in value if isinstance(value, list) else [value]:
                    if not isinstance(name, str) or name not in NAMED[key]:
                        raise InputError(
                            f"{where} must be among {', '.join(NAMED[key])}, got {name!r}"
                        )
            elif key in LISTS:
                VALUES[section][key].check(where, value)
            elif (section, key) == ("grid", "samples") and isinstance(value, list):
                # seeds per level of a resolution study (level_samples)
                if not value:
                    raise InputError(f"{where} must be a count or a list of counts, got []")
                for each in value:
                    VALUES[section][key].check(where, each)
                level_samples = tuple(value)
                value = max(value)
            elif isinstance(value, list):
                if section == "grid" and key not in GRID_AXES:
                    raise InputError(f"{where} must be one value, got {value!r}")
                for each in value:  # every value of an axis, in any position
                    VALUES[section][key].check(where, each)
            else:
                VALUES[section][key].check(where, value)
            if isinstance(value, list) and key not in LISTS:
                words = [axis_word(v) for v in value]
                if not value or len(set(words)) != len(value):
                    raise InputError(
                        f"{where}: an axis needs values distinct in their "
                        f"folder names ({', '.join(words) or 'none'}), got {value!r}"
                    )
                axes[(section, key)] = tuple(value)
                value = value[0]
            values[(section, key)] = value
    named = {k: values.pop(("scene", k)) for k in NAMED if ("scene", k) in values}
    for key, name in named.items():  # a named reading is its options
        for option, value in NAMED[key][name].items():
            if ("scene", option) in values:
                raise InputError(
                    f"{path}: [scene] gives {key} and {option}, which it sets; give one"
                )
            values[("scene", option)] = value
    if sweep != "cross" and not axes:
        raise InputError(f"{path}: sweep {sweep!r} needs axes (an option given a list)")
    grid = {k: v for (s, k), v in values.items() if s != "run"}
    if "vn" in grid and "speeds" in grid:  # one would be ignored
        raise InputError(
            f"{path}: [grid] gives both vn and speeds; give one (speeds: a folder per speed "
            "in one study; vn: one speed, or a list of them as an axis)"
        )
    if "gamma_deg" in grid:
        if "cot_gamma" in grid:
            raise InputError(f"{path}: [grid] gives both gamma_deg and cot_gamma; give one")
        grid["cot_gamma"] = [cot_of_degrees(g) for g in grid["gamma_deg"]]
        for degrees, cot in zip(grid.pop("gamma_deg"), grid["cot_gamma"], strict=True):
            if not COT_GAMMA.contains(cot):  # said as the user wrote it: gamma, not cot gamma
                low, high = (
                    math.degrees(math.atan(1.0 / c)) for c in (COT_GAMMA.high, COT_GAMMA.low)
                )
                raise InputError(
                    f"{path}: [grid] gamma_deg must be each in [{low:.3g}, {high:.3g}] degrees "
                    f"(cot gamma in [{COT_GAMMA.low:g}, {COT_GAMMA.high:g}]), got {degrees!r}"
                )
    for key in LISTS:
        if key in grid:
            grid[key] = tuple(grid[key])
    if "cot_gamma" in grid:
        grid.setdefault("angles", len(grid["cot_gamma"]))
    run = {k: v for (s, k), v in values.items() if s == "run"}
    ranks = run.pop("ranks", None)
    if ranks is not None and (both := sorted({"nprocs", "route"} & set(run))):
        raise InputError(f"{path}: [run] gives ranks and {both[0]}, which it sets; give one")
    try:
        options = replace(RunOptions(route="python"), **run)
        options = options if ranks is None else on_ranks(options, ranks)
        study = Study(name=path.stem, **grid, options=options)
    except TypeError as error:
        raise InputError(f"{path}: {error}") from None
    axes = {key: values for (section, key), values in axes.items()}
    levels = samples_by_level(path, level_samples, axes, kind)
    if kind == "resolution":  # its page fits every level: refused before any run
        fewest = min(levels.values(), default=study.samples)
        if fewest < FIT_SEEDS or study.angles < FIT_ANGLES:
            raise InputError(
                f"{path}: a resolution study fits every level, which needs at least "
                f"{FIT_ANGLES} angles and {FIT_SEEDS} samples at each; got {study.angles} "
                f"angles, {fewest} samples at its fewest"
            )
    if sections and study.speeds:
        raise InputError(f"{path}: sections are a results page's; a study of speeds has its own")
    named = {k: v for k, v in named.items() if k not in axes}
    if rerun.get("best") and rerun["samples"] <= study.samples:
        raise InputError(
            f"{path}: [rerun] samples must be more than [grid] samples ({study.samples}), "
            f"got {rerun['samples']}"
        )
    return StudyFile(
        study, page, axes, tuple(readings), tuple(sections), kind, sweep, rerun, named, levels, path
    )


def samples_by_level(path: Path, counts: tuple[int, ...], axes: dict, kind: str) -> dict:
    """[grid] samples given as a list: the seeds of each [scene] n_disk value,
    in order (a resolution study's levels, as a multilevel allocation asks
    them), as n_disk -> seeds; {} for one count."""
    if not counts:
        return {}
    n_disk = axes.get("n_disk", ())
    if kind != "resolution" or len(n_disk) != len(counts):
        raise InputError(
            f"{path}: [grid] samples as a list gives the seeds of each [scene] n_disk value "
            f"of a resolution study, as many as n_disk has ({len(n_disk)}), got {list(counts)!r}"
        )
    return dict(zip(n_disk, counts, strict=True))


def read_rerun(path: Path, table, kind: str) -> dict:
    """[rerun]'s keys, checked (a readings kind's, whose page ranks its readings)."""
    if not table:
        return {}
    if not isinstance(table, dict):
        raise InputError(f"{path}: [rerun] must be a table of {', '.join(RERUN)}")
    if kind not in READINGS_KINDS:
        raise InputError(f"{path}: [rerun] ranks a readings study's readings: give its kind")
    for key, value in table.items():
        if key not in RERUN:
            raise InputError(f"{path}: [rerun] has no option {key!r}; options: {', '.join(RERUN)}")
        wanted = type(RERUN[key])
        if type(value) is not wanted or (wanted is int and value < 0):
            raise InputError(
                f"{path}: [rerun] {key} must be {'a count' if wanted is int else wanted.__name__}"
                f", got {value!r}"
            )
    out = {**RERUN, **table}
    for lattice in out["then_lattices"]:  # refused now, not after the first pass's hours
        if not isinstance(lattice, str) or lattice not in STUDY_LATTICES:
            raise InputError(
                f"{path}: [rerun] then_lattices must be among {', '.join(STUDY_LATTICES)}, "
                f"got {lattice!r}"
            )
    if len(set(map(str, out["then_lattices"]))) != len(out["then_lattices"]):
        raise InputError(f"{path}: [rerun] then_lattices names a lattice twice")
    if out["best"] and out["samples"] == 0:
        raise InputError(f"{path}: [rerun] best needs samples, more than [grid] samples")
    if bool(out["then_lattices"]) != bool(out["then_best"]):
        raise InputError(f"{path}: [rerun] then_lattices and then_best go together")
    return out


def combinations(axes: dict[str, tuple], sweep: str = "cross") -> list[dict]:
    """The axes' combinations, option -> value: every one (``cross``), or
    (``one-at-a-time``) each axis's values with the others at their first
    value, the base, which comes first and once."""
    if sweep == "cross":
        return [dict(zip(axes, c)) for c in itertools.product(*axes.values())]
    base = {key: values[0] for key, values in axes.items()}
    out = [base]
    for key, values in axes.items():
        out += [{**base, key: value} for value in values[1:]]
    return out


def axis_word(value) -> str:
    """A value of an axis as its studies' folder names write it."""
    return f"{value:g}" if isinstance(value, float) else str(value)


def axis_studies(
    study, axes: dict[str, tuple], name: str | None = None, sweep: str = "cross"
) -> list:
    """The study once for every combination of the axes' values (a scene
    option, a named reading or a run option each; ``combinations``), named
    <name>_<option>-<value>...

    Raises
    ------
    ground.errors.InputError
        If a combination's name could not be a folder of runs/.
    """
    run_fields = {f.name for f in fields(RunOptions)}
    name = name or study.name
    out = []
    for combination in combinations(axes, sweep):
        scene, run, words = {}, {}, []
        for key, value in combination.items():
            if key in NAMED:
                scene.update(NAMED[key][value])
            else:
                (run if key in run_fields else scene)[key] = value
            words.append(f"{key}-{axis_word(value)}")
        sub = replace(
            study, name="_".join([name, *words]), options=replace(study.options, **run), **scene
        )
        out.append(sub)
    return out


def study_file_text(described: StudyFile) -> str:
    """A study file that reads back as ``described`` (its options that differ
    from the defaults, each axis's values, the page and its readings)."""
    study, page, axes = described.study, described.page, described.axes
    default, run_default = Study(study.name), RunOptions(route="python")
    lines = [f"page = {toml_value(page)}"] if page else []
    if described.readings:
        lines.append(f"readings = {toml_value(list(described.readings))}")
    if described.sections:
        lines.append(f"sections = {toml_value(list(described.sections))}")
    if described.kind != "results":
        lines.append(f"kind = {toml_value(described.kind)}")
    if described.sweep != "cross":
        lines.append(f"sweep = {toml_value(described.sweep)}")
    sections = {"grid": [], "scene": [], "run": [], "rerun": []}
    # a named reading (given, or an axis) stands for the options it sets
    named = {k: described.named.get(k, axes.get(k)) for k in NAMED}
    named = {k: v for k, v in named.items() if v is not None}
    covered = {o for k, v in named.items() for o in NAMED[k][v if isinstance(v, str) else v[0]]}
    for key, value in named.items():
        sections["scene"].append(f"{key} = {toml_value(value)}")
    for option in fields(Study):
        if option.name in ("name", "options", "source") or option.name in covered:
            continue
        value = axes.get(option.name, getattr(study, option.name))
        if option.name == "samples" and described.level_samples:
            value = list(described.level_samples.values())
        if option.name in axes or value != getattr(default, option.name):
            section = "grid" if option.name in GRID else "scene"
            sections[section].append(f"{option.name} = {toml_value(value)}")
    ranks = study.options.nprocs if study.options.route == "lmp" else 1
    if ranks > 1:  # [run] ranks stands for the two options it sets
        sections["run"].append(f"ranks = {ranks}")
    for option in fields(RunOptions):
        if ranks > 1 and option.name in ("nprocs", "route"):
            continue
        value = axes.get(option.name, getattr(study.options, option.name))
        if option.name in axes or value != getattr(run_default, option.name):
            sections["run"].append(f"{option.name} = {toml_value(value)}")
    sections["rerun"] = [f"{k} = {toml_value(v)}" for k, v in described.rerun.items()]
    for section, body in sections.items():
        if body:
            lines += ["", f"[{section}]", *body]
    return "\n".join(lines).lstrip("\n") + "\n"


def toml_value(value) -> str:
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, str):
        return '"' + value + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value)
