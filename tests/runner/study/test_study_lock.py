"""One run per study folder (issue 44): two real processes on one study.

The first holds runs/<study>/.lock (runner.study.lock) for its whole run;
the second is refused in one line naming the first's pid, or with --wait
starts when the first has ended and finds every impact done.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

from tests.helpers import ROOT, RUNS

SMALL = '[grid]\nlattices = ["random"]\nangles = 2\nsamples = 1\n[scene]\nn_disk = 200\n'


def start(study, name: str, *extra: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "runner", "study", str(study), "--name", name, "--workers", "1"]
        + list(extra),
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "IMPACT_RUNS": str(RUNS)},
    )


def wait_for_lock(name: str, pid: int, timeout: float = 120.0) -> None:
    """Return once process ``pid`` holds the study's lock (its pid in it)."""
    lock = RUNS / name / ".lock"
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if lock.is_file() and lock.read_text().split()[:1] == [str(pid)]:
            return
        time.sleep(0.05)
    raise AssertionError(f"pid {pid} never held {lock}")


def test_a_second_run_of_one_folder_is_refused_naming_the_first(tmp_path):
    study = tmp_path / "locked.toml"
    study.write_text(SMALL)
    first = start(study, "h44_lock")
    try:
        wait_for_lock("h44_lock", first.pid)
        second = start(study, "h44_lock")
        _, errors = second.communicate(timeout=120)
        assert second.returncode == 2, errors
        assert errors.strip().splitlines() == [
            f"python -m runner: error: {RUNS / 'h44_lock'}: another run of this study is under "
            f"way (pid {first.pid} on {os.uname().nodename}); let it end, or give --wait to "
            "start when it has"
        ]
        out, errors = first.communicate(timeout=600)
        assert first.returncode == 0, errors
        assert "2 done, 0 failed" in out
    finally:
        first.kill()
    # --wait: the second starts when the first has ended, and has nothing to run
    first = start(study, "h44_lock_wait")
    try:
        wait_for_lock("h44_lock_wait", first.pid)
        waiting = start(study, "h44_lock_wait", "--wait")
        out, errors = waiting.communicate(timeout=600)
        assert waiting.returncode == 0, errors
        assert f"waiting for pid {first.pid}" in errors
        assert "2 already done or failed, 0 to run" in out
        assert first.wait(timeout=600) == 0
    finally:
        first.kill()
