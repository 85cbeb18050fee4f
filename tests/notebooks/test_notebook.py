"""The notebook runs: its code cells, in order, on a small disk."""

from __future__ import annotations

import json
import os

import matplotlib
import numpy as np

from tests.helpers import ROOT, RUNS


def test_notebook_cells_run(monkeypatch, tmp_path):
    matplotlib.use("Agg")
    monkeypatch.setenv("IMPACT_ROOT", str(ROOT))
    monkeypatch.setenv("NOTEBOOK_POINTS", "200")
    table = tmp_path / "impacts.csv"
    table.write_text("study_lattice,cot_gamma,beta\nrandom,1.0,-0.5\nrandom,2.0,0.1\n")
    monkeypatch.setenv("STUDY_TABLE", str(table))
    notebook = json.loads((ROOT / "notebooks" / "impact.ipynb").read_text())
    namespace: dict = {}
    for cell in notebook["cells"]:
        if cell["cell_type"] == "code":
            exec(compile("".join(cell["source"]), "notebook", "exec"), namespace)
    result, times, omega = namespace["result"], namespace["times"], np.asarray(namespace["omega"])
    assert len(times) > 10
    # the dump, read by MDAnalysis, gives the rebound's spin that series.dat gave
    after = times > result["contact_end"]
    assert after.any() and abs(result["omega"]) > 1e-4
    assert abs(omega[after] - result["omega"]).max() < 1e-5 * (1 + abs(result["omega"]))
    assert namespace["table"] == table
    assert os.path.exists(RUNS / "notebook" / "dump.lammpstrj")
