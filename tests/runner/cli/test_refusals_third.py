"""Bad input, third round (issue 44): limits, values that cannot work, no
traceback, clear messages; each case the real command in its own process.

Each must exit non-zero with one line on stderr naming the option, file or
path, no traceback, and leave the clone as git has it and no runs/<name>/
where it was refused before any work. The write gate's cases are in
test_write_gate.py, the study lock's and the results' checks in
tests/runner/.
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.helpers import ROOT, RUNS

# the whole tree watched: after the others, which write into it (Makefile)
pytestmark = pytest.mark.tree

SMALL = '[grid]\nlattices = ["random"]\nangles = 2\nsamples = 1\n[scene]\nn_disk = 200\n'
PYTHON = sys.executable


@dataclass
class Case:
    id: str
    argv: list[str]  # {tmp} filled in
    says: str
    files: dict = field(default_factory=dict)  # name in the case's folder -> text or bytes
    env: dict = field(default_factory=dict)
    status: int = 2
    name: str = ""  # runs/<name>/ that must not exist afterwards


def case(id: str, argv: str, says: str, **kwargs) -> Case:
    return Case(id, argv.split(), says, **kwargs)


def study_file(id: str, text: str | bytes, says: str, *options: str, stem: str = "f") -> Case:
    return Case(id, ["study", f"{{tmp}}/{stem}.toml", *options], says, {f"{stem}.toml": text})


AXES = SMALL.replace("angles = 2", "angles = 1000").replace("samples = 1", "samples = 200")
CASES = [
    # limits that add up: every combination of a file's axes together
    study_file(
        "ten values x 1000 angles x 200 samples",
        AXES + "wall_ka = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]\n",
        "f.toml: its 10 combinations have 2,000,000 impacts together (200000 + ",
    ),
    study_file(
        "one study over the cap", AXES.replace("200", "300", 1), "--max-impacts allows more"
    ),
    # names LAMMPS cannot open
    study_file("file stem with %", SMALL, "not '%': LAMMPS cannot open", stem="a%b"),
    study_file("file stem non-ASCII", SMALL, "not '*é'", stem="é*"),
    case("--name with *", "study demo --name x*y", "argument --name: must be plain portable"),
    Case(
        "IMPACT_RUNS non-ASCII",
        ["study", "demo"],
        "IMPACT_RUNS: {tmp}/rüns must be plain portable characters",
        env={"IMPACT_RUNS": "{tmp}/rüns"},
    ),
    # values in range that cannot work
    case("tmax below one step", "impact --n-disk 200 --tmax 0.001", "shorter than one step"),
    case(
        "vn that never arrives", "impact --vn 1e-200", "is too short for the disk to reach the wall"
    ),
    case(
        "radius the step does not follow", "impact --n-disk 200 --radius 10", "radius 10: its step"
    ),
    case(
        "radius out of its range", "impact --radius 1000", "--radius: must be a number in [0.1, 10]"
    ),
    study_file(
        "both vn and speeds",
        SMALL.replace("samples = 1", "samples = 1\nvn = 0.1\nspeeds = [0.05, 0.1]"),
        "[grid] gives both vn and speeds; give one",
    ),
    study_file(
        "study tmax too short for its slowest speed",
        SMALL + "[run]\ntmax = 0.1\n",
        "f.toml: tmax 0.1 R/c is too short for the disk to reach the wall",
    ),
    Case(
        "--from-tables over a garbage impacts.csv",
        ["study", "demo", "--from-tables", "{tmp}/t"],
        "impacts.csv and failed.csv hold no impact",
        {"t/impacts.csv": "garbage\n", "t/failed.csv": "", "t/study.json": "{}"},
    ),
    # no traceback
    Case(
        "tilt over an empty table",
        ["tilt", "--tables", "{tmp}/t"],
        "--tables: {tmp}/t/impacts.csv is not a study's table (no impact in it)",
        {"t/impacts.csv": "seed,gamma_deg,e\n", "t/study.json": "{}"},
    ),
    Case(
        "lmp not on PATH",
        ["impact", "--n-disk", "200", "--route", "lmp", "--out", "{tmp}/x"],
        "lmp not found on PATH",
        env={"PATH": "{tmp}"},
        status=1,
    ),
    Case(
        "IMPACT_MPIRUN not a program",
        ["impact", "--n-disk", "200", "--np", "2", "--out", "{tmp}/x"],
        "IMPACT_MPIRUN: {tmp}/mpirun is not a program on PATH",
        env={"IMPACT_MPIRUN": "{tmp}/mpirun"},
        status=1,
    ),
    # clear messages
    case(
        "--np beyond the cores",
        f"impact --np {(os.cpu_count() or 1) + 1}",
        "--np must be at most",
        # make test exports it for the tests' own MPI runs; this case asks without
        env={"OMPI_MCA_rmaps_base_oversubscribe": ""},
    ),
    case("gamma 89.99", "impact --gamma 89.99", "gamma 89.99: the disk would start"),
    study_file(
        "gamma_deg as the user wrote it",
        SMALL.replace("angles = 2", "gamma_deg = [0.0001, 45]"),
        "[grid] gamma_deg must be each in [0.573, 88.3] degrees",
    ),
    study_file("an empty study file", "", "f.toml: an empty study file"),
    study_file("a BOM is read", b"\xef\xbb\xbf" + b"[grid]\nvn = 0.5\n", "[grid] vn must be"),
    study_file(
        "-0.0 is 0 in a file", "[scene]\nroughness = [-0.0, 0.0]\n", "(0, 0), got [0.0, 0.0]"
    ),
]


def fill(text: str, tmp: Path) -> str:
    return text.replace("{tmp}", str(tmp))


def git_status() -> str:
    return subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=all"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def run(argv: list[str], env: dict, tmp: Path, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(
        [PYTHON, "-m", "runner", *argv],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "IMPACT_RUNS": str(RUNS), **env},
        **kwargs,
    )


def one_line(done: subprocess.CompletedProcess, says: str, status: int) -> str:
    errors = done.stderr.strip()
    assert "Traceback" not in errors, errors
    assert done.returncode == status, (done.returncode, errors)
    assert len(errors.splitlines()) == 1, errors
    assert says in errors, errors
    return errors


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_refused_in_one_line(case, tmp_path):
    for name, text in case.files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(text) if isinstance(text, bytes) else path.write_text(text)
    before = git_status()
    runs = sorted(p.name for p in RUNS.iterdir())
    env = {k: fill(v, tmp_path) for k, v in case.env.items()}
    done = run([fill(a, tmp_path) for a in case.argv], env, tmp_path)
    one_line(done, fill(case.says, tmp_path), case.status)
    assert git_status() == before
    assert sorted(p.name for p in RUNS.iterdir()) == runs
    assert not (tmp_path / "x").exists()


def test_a_dangling_link_for_the_study_folder(tmp_path):
    link = RUNS / "h44_dangling"
    link.symlink_to(tmp_path / "nowhere")
    try:
        done = run(["study", "demo", "--name", "h44_dangling"], {}, tmp_path)
        one_line(done, "h44_dangling is a link to", 2)
        assert not (tmp_path / "nowhere").exists()
    finally:
        link.unlink()


def small_study(tmp_path: Path, name: str) -> list[str]:
    (tmp_path / f"{name}.toml").write_text(SMALL)
    shutil.rmtree(RUNS / name, ignore_errors=True)
    return ["study", str(tmp_path / f"{name}.toml"), "--workers", "1"]


def test_a_full_disk_is_one_line_naming_the_file(tmp_path):
    """ulimit -f: the first file past the limit is named, no impact is
    recorded as failed for it, and the study resumes once there is room."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (50_000, 50_000))

    argv = small_study(tmp_path, "h44_full")
    env = {"IMPACT_POISSON_CACHE": "off"}
    done = run(argv, env, tmp_path, preexec_fn=limit)
    errors = one_line(done, "File too large; the file size limit is reached (ulimit -f)", 1)
    assert errors.split(": ")[2].startswith(str(RUNS / "h44_full"))
    assert not list((RUNS / "h44_full").rglob("failed.json"))
    done = run(argv, env, tmp_path)
    assert done.returncode == 0, done.stderr
    assert "2 done, 0 failed" in done.stdout


@pytest.mark.skipif(shutil.which("unshare") is None, reason="needs unshare for a private mount")
def test_a_read_only_impact_folder_is_one_line_naming_it(tmp_path):
    """A folder of a study made read-only (a private read-only bind mount,
    which stops root too) stops the study with one line naming the file."""
    argv = small_study(tmp_path, "h44_read_only")
    folder = RUNS / "h44_read_only" / "random" / "s1" / "g80.5000"
    folder.mkdir(parents=True)
    command = " ".join([PYTHON, "-m", "runner", *argv])
    script = (
        f"mount --bind {folder} {folder} && mount -o remount,bind,ro {folder} && exec {command}"
    )
    if os.geteuid() != 0:  # a user's read-only folder is its mode
        folder.chmod(0o555)
        script = f"exec {command}"
    done = subprocess.run(
        ["unshare", "-m", "sh", "-c", script] if os.geteuid() == 0 else ["sh", "-c", script],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "IMPACT_RUNS": str(RUNS)},
    )
    folder.chmod(0o755)
    one_line(done, f"{folder}/", 1)
    assert "read-only" in done.stderr or "Permission denied" in done.stderr
