"""The notebook runs: its code cells, in order, on a small disk, under a
Jupyter kernel of this venv's Python (nbclient), as a user runs it."""

from __future__ import annotations

import json
import os
import sys

import nbformat
import numpy as np
import pytest
from nbclient import NotebookClient

from tests.helpers import ROOT, RUNS

pytestmark = pytest.mark.lammps

# A last cell, the test's own: what the notebook computed, for the asserts here.
REPORT = """
import json as _json, sys as _sys
print(_json.dumps({
    "python": _sys.executable,
    "contact_end": float(result["contact_end"]),
    "omega_end": float(result["omega"]),
    "times": [float(t) for t in times],
    "omega": [float(w) for w in omega],
    "table": str(table),
}))
"""


def kernel_of_this_python(folder):
    """A kernel spec in ``folder`` whose kernel is this interpreter (the venv's),
    found before any other spec of the machine or the user (JUPYTER_PATH first)."""
    spec = folder / "kernels" / "impact-venv"
    spec.mkdir(parents=True)
    argv = [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"]
    spec.joinpath("kernel.json").write_text(
        json.dumps({"argv": argv, "display_name": "impact venv", "language": "python"})
    )
    return "impact-venv"


def test_notebook_cells_run(monkeypatch, tmp_path):
    monkeypatch.setenv("IMPACT_ROOT", str(ROOT))
    monkeypatch.setenv("NOTEBOOK_POINTS", "200")
    table = tmp_path / "impacts.csv"
    table.write_text("study_lattice,cot_gamma,beta\nrandom,1.0,-0.5\nrandom,2.0,0.1\n")
    monkeypatch.setenv("STUDY_TABLE", str(table))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    kernel = kernel_of_this_python(tmp_path / "jupyter")
    notebook = nbformat.read(ROOT / "notebooks" / "impact.ipynb", as_version=4)
    notebook.cells.append(nbformat.v4.new_code_cell(REPORT))
    # Jupyter starts a notebook's kernel in the notebook's folder
    client = NotebookClient(
        notebook,
        kernel_name=kernel,
        timeout=600,
        resources={"metadata": {"path": str(ROOT / "notebooks")}},
    )
    client.execute()  # a cell that raises fails the test with its traceback
    (report,) = [o for o in notebook.cells[-1].outputs if o.get("name") == "stdout"]
    seen = json.loads(report["text"])
    assert seen["python"] == sys.executable
    times, omega = np.asarray(seen["times"]), np.asarray(seen["omega"])
    assert len(times) > 10
    # the dump, read by MDAnalysis, gives the rebound's spin that series.dat gave
    after = times > seen["contact_end"]
    assert after.any() and abs(seen["omega_end"]) > 1e-4
    assert abs(omega[after] - seen["omega_end"]).max() < 1e-5 * (1 + abs(seen["omega_end"]))
    assert seen["table"] == str(table)
    assert os.path.exists(RUNS / "notebook" / "dump.lammpstrj")
