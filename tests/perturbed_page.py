"""Make a page again from its committed tables as another CPU would read
them: every measured number of every table moved by a few ulps.

Another x86-64 CPU (another vector width in numpy, another OpenBLAS kernel,
another order of summing) computes a page's numbers with other rounding
errors; moving the tables' measured numbers by a few units in their last
place stands in for that, deterministically. Run with the environment of
an older CPU as well (``OLDER_CPU``: numpy's dispatch limited to the
baseline, OpenBLAS forced to Sandybridge's kernels), the committed page,
tables and figures must come out byte for byte.

    python -m tests.perturbed_page NAME [--ulps K]

writes NAME's page in place (docs/studies/NAME/), as ``runner page`` does;
tests/docs/test_pages_reproducible.py restores what it changed.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import sys
from pathlib import Path

from analysis.impact.result import BINARY_FINITE
from analysis.table import BINARY_COLUMNS, COLUMNS

# numpy 2's names of the dispatched x86 features (``numpy.show_runtime()``):
# everything above the baseline X86_V2 (SSE4.2) off, and OpenBLAS's oldest
# AVX kernels instead of the machine's own. Set before numpy is imported.
OLDER_CPU = {
    "NPY_DISABLE_CPU_FEATURES": "X86_V3 X86_V4 AVX512_ICL AVX512_SPR",
    "OPENBLAS_CORETYPE": "Sandybridge",
}
# The columns a machine measures: what a run writes into result.json
# (analysis.impact.result's finite numbers, the two-disk normals of
# analysis.table.BINARY_COLUMNS) but the grid's own numbers, which are the
# same text on every machine (the seed, the angle asked for, the material's
# nu from the committed calibration, the step count).
GRID = ("seed", "gamma_deg", "nu", "steps", "cot_gamma_nominal", "target_held")
MEASURED = tuple(
    dict.fromkeys(
        k
        for k in (*BINARY_FINITE, "side_clearance", *BINARY_COLUMNS[len(COLUMNS) :])
        if k not in GRID and k not in ("target", "partner_lattice")
    )
)
EPS = 2.0**-52
READ_MARK = "tables read: "


def moved(text: str, where: str, ulps: int) -> str:
    """``text``'s number times (1 + k eps), k in [-ulps, ulps] and not 0,
    chosen by a hash of ``where`` (the same on every run); words, empty
    cells and integers as they are."""
    try:
        value = float(text)
    except ValueError:
        return text
    if not any(c in text for c in ".eE") or value == 0.0:
        return text
    k = int(hashlib.sha256(where.encode()).hexdigest()[:8], 16) % (2 * ulps) - ulps
    k = k + 1 if k >= 0 else k  # -ulps..-1, 1..ulps
    return repr(value * (1.0 + k * EPS))


def perturbing_reader(ulps: int):
    """csv.DictReader whose measured cells come out moved (``moved``)."""

    class Perturbed(csv.DictReader):
        count = 0
        read: set[str] = set()

        def __init__(self, handle, *args, **kwargs):
            super().__init__(handle, *args, **kwargs)
            Perturbed.read.add(str(Path(handle.name).resolve()))

        def __next__(self):
            row = super().__next__()
            Perturbed.count += 1
            return {
                k: moved(v, f"{Perturbed.count}/{k}", ulps)
                if k in MEASURED and isinstance(v, str)
                else v
                for k, v in row.items()
            }

    return Perturbed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("name")
    parser.add_argument("--ulps", type=int, default=4)
    args = parser.parse_args(argv)
    reader = csv.DictReader = perturbing_reader(args.ulps)  # every table the page reads
    from runner.__main__ import main as runner

    status = runner(["page", args.name])
    # the tables read, which the page may write back as it read them (moved)
    print(READ_MARK + json.dumps(sorted(reader.read)))
    return status


if __name__ == "__main__":
    sys.exit(main())
