"""bench/resolution_error.py on a small table: it writes its page, and one
level's error is sqrt(bias^2 + stat^2) against the limit of every level."""

import csv
import math

from analysis.kinds import resolution
from bench import resolution_error
from ground.paths import ROOT

LEVELS = (800, 1600, 3200)
SEEDS = ("1", "2", "3", "4")


def small_tables(tmp_path):
    """The committed profile rows at three levels and four seeds, each impact
    timed at its disk's points in seconds (a made-up timing)."""
    source = ROOT / "docs" / "studies" / "resolution_profile" / "rows.csv"
    with open(source) as f:
        reader = csv.DictReader(f)
        columns = reader.fieldnames
        rows = [
            r
            for r in reader
            if r["limit"] == "profile" and int(r["n_disk"]) in LEVELS and r["seed"] in SEEDS
        ]
    rows_csv, timings_csv = tmp_path / "rows.csv", tmp_path / "timings.csv"
    with open(rows_csv, "w", newline="") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        writer.writerows(rows)
    with open(timings_csv, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["reading", "study_lattice", "seed", "gamma_deg", "wall_seconds"])
        for r in rows:
            key = [r["reading"], r["study_lattice"], r["seed"], r["gamma_deg"]]
            writer.writerow([*key, r["n_disk"]])
    return rows_csv, timings_csv


def test_one_level_error_and_seconds(tmp_path):
    rows_csv, timings_csv = small_tables(tmp_path)
    out = tmp_path / "out"
    argv = ["--study", "resolution_profile", "--rows", str(rows_csv), "--timings",
            str(timings_csv), "--out", str(out)]  # fmt: skip
    assert resolution_error.main(argv) == 0
    assert (out / "resolution_error.md").read_text().count("| one level |") >= len(LEVELS)

    rows = resolution_error.read(rows_csv, timings_csv, "profile")
    summary = resolution.summaries(rows)
    found = resolution_error.estimates(rows)
    checked = 0
    for q in resolution_error.QUANTITIES:
        limit = resolution.limits(summary, (q,), rows)[("profile", "random", q)]
        if limit["status"] != "limit":
            continue
        value, stat = summary[("profile", "random", LEVELS[-1])]["values"][q]
        (finest,) = [
            r for r in found[q]["rows"] if r["method"] == "one level" and r["n"] == LEVELS[-1]
        ]
        bias = value - limit["value"]
        assert math.isclose(finest["error"], math.sqrt(bias**2 + stat**2))
        impacts = sum(int(r["n_disk"]) == LEVELS[-1] for r in rows)
        assert math.isclose(finest["seconds"], LEVELS[-1] * impacts)
        checked += 1
    assert checked
