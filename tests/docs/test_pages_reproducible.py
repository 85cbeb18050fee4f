"""A page made again from its committed tables is the committed page, byte for
byte, and so are its tables and figures: `runner page NAME` leaves `git
status` clean for every study whose tables are committed in docs/."""

from __future__ import annotations

import subprocess

import pytest

from ground.paths import study_docs
from runner.study.studies import built_in_pages
from tests.helpers import ROOT

DOCS = ROOT / "docs"
WITH_TABLES = [
    name
    for name, page in built_in_pages()[0].items()
    if (study_docs(page) / "study.json").is_file() or (study_docs(page) / "rows.csv").is_file()
]


def docs_status() -> str:
    return subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=all", "--", "docs"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def test_every_study_with_a_page_has_its_tables():
    assert {"paper", "speed", "grazing", "binary", "scene_readings", "wall_width"} <= set(
        WITH_TABLES
    )


# pages that take more than ~10 s to make again (pytest --durations=0 on 2026-11-25:
# 26 to 368 s each on the two cores loaded by other runs; the others under 11 s)
SLOW_PAGES = {
    "binary",
    "binary_grazing",
    "binary_references",
    "model_readings",
    "paper",
    "resolution",
    "grazing",
}


@pytest.mark.parametrize(
    "name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_PAGES else n for n in WITH_TABLES]
)
def test_runner_page_leaves_git_status_clean(name, capsys):
    """The page, its tables and figures written in place, as the command
    does; what differs afterwards is put back as it was (and fails the test)."""
    from runner.__main__ import main

    before = {p: p.read_bytes() for p in DOCS.rglob("*") if p.is_file()}
    status = docs_status()
    try:
        assert main(["page", name]) == 0, capsys.readouterr().err
        changed = sorted(
            str(p.relative_to(ROOT))
            for p in DOCS.rglob("*")
            if p.is_file() and before.get(p) != p.read_bytes()
        )
        assert not changed, f"runner page {name} changed {changed}"
        assert docs_status() == status
    finally:
        for path in DOCS.rglob("*"):
            if path.is_file() and path not in before:
                path.unlink()
        for path, data in before.items():
            if not path.is_file() or path.read_bytes() != data:
                path.write_bytes(data)
