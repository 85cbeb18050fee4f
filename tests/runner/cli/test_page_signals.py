"""A signal during `runner page` ends it in one line, exit 128 + the signal,
with no file half-written or left behind (issue 56: a signal during a page
left a committed PNG of 0 bytes and a KeyboardInterrupt traceback)."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

from tests.helpers import ROOT


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_during_a_page_ends_it_in_one_line_with_nothing_half_written(tmp_path, signum):
    out = tmp_path / "page"
    proc = subprocess.Popen(
        [sys.executable, "-m", "runner", "page", "resolution_floor", "--out", str(out)],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 120
        while not (out / "figures").is_dir() and time.monotonic() < deadline:
            time.sleep(0.05)  # the page has begun: its folder is made before any number
        assert (out / "figures").is_dir(), proc.stderr.read() if proc.poll() is not None else ""
        time.sleep(0.5)
        proc.send_signal(signum)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + signum, err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and f"stopped by {signal.Signals(signum).name}" in lines[0], err
    written = [p for p in out.rglob("*") if p.is_file()]
    assert not [p.name for p in written if p.name.endswith(".tmp")]
    assert all(p.stat().st_size > 0 for p in written)
