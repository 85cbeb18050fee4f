"""Bad input, third round (issue 44): every write through one gate
(ground.gate), run as the user runs the commands: `~` in a path, real
symbolic links, environment paths, a study file placed in studies/, `run` on
a folder of studies/. Each refusal is one line naming the path, a non-zero
exit, and nothing written: docs/ and studies/ as git has them.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from ground.errors import InputError
from ground.gate import gate, remove
from tests.helpers import ROOT, RUNS

# files put into studies/ for a moment, or studies/ listed: last (Makefile)
pytestmark = pytest.mark.last

DOCS = ROOT / "docs"
SMALL = '[grid]\nlattices = ["random"]\nangles = 2\nsamples = 1\n[scene]\nn_disk = 200\n'


def git_status() -> str:
    return subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=all", "docs", "studies"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def command(*argv: str, env: dict | None = None, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "runner", *argv],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, **(env or {})},
    )


def refused(done: subprocess.CompletedProcess, says: str) -> None:
    errors = done.stderr.strip()
    assert done.returncode != 0, done.stdout
    assert len(errors.splitlines()) == 1, errors
    assert "Traceback" not in errors
    assert says in errors, errors


@pytest.fixture
def home(tmp_path):
    """A home folder whose `~/<up>` is the clone's root."""
    home = tmp_path / "home"
    home.mkdir()
    return home, os.path.relpath(ROOT, home)


def test_tilde_is_expanded_in_the_check_and_the_write(home, tmp_path):
    folder, up = home
    before = git_status()
    env = {"HOME": str(folder)}
    refused(command("impact", "--out", f"~/{up}/studies/x", env=env), "is inside studies/")
    refused(command("impact", env={**env, "IMPACT_RUNS": f"~/{up}/docs"}), "IMPACT_RUNS")
    # no literal '~' folder anywhere: the check and the write mean the same folder
    assert not (ROOT / "~").exists() and not (tmp_path / "~").exists()
    assert git_status() == before


def test_environment_paths_pass_the_gate(tmp_path):
    before = git_status()
    done = command("impact", "--out", str(tmp_path / "x"), env={"IMPACT_POISSON_CACHE": "docs/c"})
    refused(done, "IMPACT_POISSON_CACHE: docs/c is inside docs/")
    link = tmp_path / "runs"
    link.symlink_to(DOCS)
    refused(command("impact", env={"IMPACT_RUNS": str(link)}), f"it leads to {DOCS}")
    assert not (tmp_path / "x").exists()
    assert git_status() == before


@pytest.mark.parametrize("name", ["IMPACT_POISSON_CACHE", "IMPACT_RUNS"])
def test_an_environment_path_that_is_a_file_is_refused(tmp_path, name):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    done = command("impact", "--out", str(tmp_path / "x"), env={name: str(a_file)})
    refused(done, f"{name}: {a_file} is a file, not a folder")
    assert not (tmp_path / "x").exists() and a_file.read_text() == ""


def test_run_on_a_folder_of_studies_is_refused(tmp_path):
    scene = ROOT / "studies" / "h44-gate-scene"
    try:
        scene.mkdir()
        for name in ("scene.data", "scene.lmp", "scene.json"):
            (scene / name).write_text("{}")
        refused(command("run", str(scene)), "is inside studies/")
        assert sorted(p.name for p in scene.iterdir()) == ["scene.data", "scene.json", "scene.lmp"]
    finally:
        shutil.rmtree(scene, ignore_errors=True)


@pytest.mark.parametrize("page", ["model", "usage"])
def test_a_file_placed_in_studies_may_not_take_a_committed_page(page):
    placed = ROOT / "studies" / f"h44_placed_{page}.toml"
    before = (DOCS / f"{page}.md").read_bytes()
    status = git_status()
    try:
        placed.write_text(f'page = "{page}"\n{SMALL}')
        done = command("study", placed.stem, "--docs", "--report-only")
        refused(done, f"page {page!r} is committed in docs/ and not this study's")
    finally:
        placed.unlink(missing_ok=True)
    assert (DOCS / f"{page}.md").read_bytes() == before
    assert git_status() == status


def test_two_study_files_may_not_name_the_same_new_page(tmp_path):
    placed = ROOT / "studies" / "h44_first_owner.toml"
    other = tmp_path / "h44_second_owner.toml"
    status = git_status()
    try:
        placed.write_text(f'page = "h44_shared"\n{SMALL}')
        other.write_text(f'page = "h44_shared"\n{SMALL}')
        done = command("study", str(other), "--docs", "--report-only")
        refused(done, "page 'h44_shared' is named by studies/h44_first_owner.toml too")
        done = command("study", placed.stem, "--docs", "--report-only")
        assert "Traceback" not in done.stderr
    finally:
        placed.unlink(missing_ok=True)
    assert not (DOCS / "studies" / "h44_shared").exists()
    assert git_status() == status


def test_an_impact_folder_that_links_into_docs_is_refused_not_emptied(tmp_path):
    """The issue's case: rebuilding an unfinished impact's folder that was a
    link into docs/ emptied the committed folder."""
    study = tmp_path / "study.toml"
    study.write_text(SMALL)
    name = "h44_link_docs"
    folder = RUNS / name / "random" / "s1" / "g80.5000"
    folder.parent.mkdir(parents=True, exist_ok=True)
    figures = DOCS / "studies" / "results" / "figures"
    folder.symlink_to(figures)
    status = git_status()
    listing = sorted(p.name for p in figures.iterdir())
    refused(command("study", str(study), "--name", name), "it leads to")
    assert sorted(p.name for p in figures.iterdir()) == listing
    assert git_status() == status


def test_a_folder_is_removed_as_a_link_never_through_it(tmp_path):
    target = tmp_path / "kept"
    target.mkdir()
    (target / "a.txt").write_text("a")
    link = tmp_path / "link"
    link.symlink_to(target)
    remove(link)
    assert not link.exists() and (target / "a.txt").read_text() == "a"
    with pytest.raises(InputError, match="inside docs/"):
        gate(tmp_path / ".." / os.path.relpath(DOCS / "model.md", tmp_path.parent))


def test_page_out_onto_a_study_folder_is_refused(tmp_path):
    other = tmp_path / "other"
    other.mkdir()
    (other / "study.json").write_text("{}")
    refused(command("page", "paper", "--out", str(other)), "holds a study (study.json)")
    assert sorted(p.name for p in other.iterdir()) == ["study.json"]
