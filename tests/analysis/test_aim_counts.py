"""How the binary pages count the aim (analysis.binary_comparison.first_touch_incidence)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.binary_comparison import first_touch_incidence


def row(gamma: float, read: float, aimed: float, turn: float) -> dict:
    """An impact at nominal ``gamma`` whose rows give the incidence ``read``
    at the first touch, aimed at ``aimed`` after a turn of ``turn`` degrees."""
    return {
        "study_lattice": "random",
        "gamma_deg": gamma,
        "cot_gamma_first_touch": 1.0 / np.tan(np.radians(read)),
        "aim_incidence_deg": aimed,
        "aim_turn_deg": turn,
    }


def test_turned_pairs_and_lines_past_a_jump_are_counted_apart():
    rows = [
        row(80.0, 80.05, 80.0000001, 0.0),
        row(80.0, 79.99, 80.0000002, -0.96),  # turned, and hits
        row(80.0, 80.40, 80.4, 1.93),  # turned, and still past a jump
        row(45.0, 45.00, 45.0, 0.0),
    ]
    touch = first_touch_incidence(rows)["random"]
    assert touch["gamma_deg"] == [45.0, 80.0]
    assert touch["turned"] == [0, 2]
    assert touch["no_line"] == [0, 1]
    assert touch["impacts"] == [1, 3]
    assert touch["largest_deg"] == pytest.approx([0.0, 0.40], abs=1e-9)
    assert touch["relative"][1] == pytest.approx((80.05 + 79.99 + 80.40) / 3 / 80.0 - 1.0)


def test_tables_from_before_the_normals_have_no_count():
    rows = [row(80.0, 80.0, 80.0, 0.0)]
    rows[0]["cot_gamma_first_touch"] = ""
    assert first_touch_incidence(rows) is None
