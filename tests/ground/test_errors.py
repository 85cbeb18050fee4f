"""Error lines worded for the person who typed them (ground/errors.py): a
value echoed back is clipped, so a huge input still gives one readable line."""

from __future__ import annotations

import subprocess
import sys

from ground.errors import LINE, QUOTE, clipped
from tests.helpers import ROOT


def test_an_error_line_quotes_at_most_200_characters_of_a_value():
    line = clipped(f"--gamma must be in (0, 90), got {'9' * 1000}")
    assert line.endswith(f"got {'9' * QUOTE}... (1000 characters)")
    # a long list of short items is cut as a whole, its length said
    items = ", ".join(["1"] * 100_000)
    line = clipped(f"samples: {items}")
    assert len(line) < LINE + 40 and line.endswith(f"({len(items) + 9} characters in all)")
    assert clipped("a short message") == "a short message"


def test_the_command_line_echoes_a_huge_value_clipped(tmp_path):
    out = tmp_path / "x"
    command = ["-m", "runner", "impact", "--gamma", "9" * 5000, "--out", str(out)]
    proc = subprocess.run([sys.executable, *command], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 2 and len(proc.stderr.splitlines()) == 1
    assert "(5000 characters)" in proc.stderr and len(proc.stderr) < 400
    assert not out.exists()
