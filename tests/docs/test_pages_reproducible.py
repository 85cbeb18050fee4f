"""A page made again from its committed tables is the committed page, byte for
byte, and so are its tables and figures, also as another CPU would make it:
`runner page NAME` from tables whose measured numbers are moved by a few ulps
(tests/perturbed_page.py), with numpy's dispatch limited to the x86-64
baseline and OpenBLAS's oldest AVX kernels, leaves `git status` clean for
every study whose tables are committed in docs/."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from ground.paths import study_docs
from runner.study.studies import built_in_pages
from tests.helpers import ROOT
from tests.perturbed_page import EPS, MEASURED, OLDER_CPU, READ_MARK, moved

DOCS = ROOT / "docs"
WITH_TABLES = [
    name
    for name, page in built_in_pages()[0].items()
    if (study_docs(page) / "study.json").is_file() or (study_docs(page) / "rows.csv").is_file()
]
ULPS = 4


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


def test_a_moved_number_is_moved_by_a_few_ulps_and_the_same_on_every_run():
    for text in ("0.8648123456789", "-0.98", "1.5e-07", "20.55"):
        value = float(text)
        out = moved(text, "7/e", ULPS)
        assert out == moved(text, "7/e", ULPS) and float(out) != value
        assert abs(float(out) - value) <= ULPS * EPS * abs(value)
    assert moved("12", "7/seed", ULPS) == "12"  # integers and words as they are
    assert moved("random", "7/lattice", ULPS) == "random"


def same_table_but_moved(path: Path, committed: bytes) -> list[str]:
    """How a table the page read and wrote back differs from the committed
    one beyond the moved numbers (it should not)."""
    old = list(csv.reader(committed.decode().splitlines()))
    new = list(csv.reader(path.read_text().splitlines()))
    if len(old) != len(new) or old[:1] != new[:1]:
        return [f"{path.name}: other rows or columns"]
    measured = {i for i, k in enumerate(old[0]) if k in MEASURED}
    bad = []
    for line, (a, b) in enumerate(zip(old[1:], new[1:], strict=True), start=2):
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            if x == y:
                continue
            close = i in measured and abs(float(x) - float(y)) <= 2 * ULPS * EPS * abs(float(x))
            if not close:
                bad.append(f"{path.name} line {line}: {x} -> {y}")
    return bad


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
def test_a_page_made_again_as_another_cpu_would_is_the_committed_page(name):
    """The page, its tables and figures written in place, as the command
    does, from tables read with their measured numbers moved; what differs
    afterwards is put back as it was (and fails the test). A table the page
    read and writes back may differ by the moves alone."""
    before = {p: p.read_bytes() for p in DOCS.rglob("*") if p.is_file()}
    status = docs_status()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "tests.perturbed_page", name, "--ulps", str(ULPS)],
            cwd=ROOT,
            env={**os.environ, **OLDER_CPU},
            capture_output=True,
            text=True,
            timeout=1800,
        )
        assert proc.returncode == 0, proc.stderr
        read = json.loads(proc.stdout.split(READ_MARK)[-1])
        assert read, "the page read no table"
        changed, moved_only = [], []
        for path in sorted(p for p in DOCS.rglob("*") if p.is_file()):
            if before.get(path) == path.read_bytes():
                continue
            if str(path.resolve()) in read and path in before:
                moved_only += same_table_but_moved(path, before[path])
            else:
                changed.append(str(path.relative_to(ROOT)))
        assert not changed, f"runner page {name} changed {changed}"
        assert not moved_only, moved_only[:5]
    finally:
        # new files removed in the page's own folder only: another writer's
        # are reported above, never deleted
        own = study_docs(built_in_pages()[0][name])
        for path in own.rglob("*"):
            if path.is_file() and path not in before:
                path.unlink()
        for path, data in before.items():
            if not path.is_file() or path.read_bytes() != data:
                path.write_bytes(data)
    assert docs_status() == status
