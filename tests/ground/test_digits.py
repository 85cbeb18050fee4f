"""Numbers as written (ground/digits.py): six significant digits, spreads of
equal values exactly 0, and the atomic writes of ground/gate.py."""

from __future__ import annotations

import math

import pytest

from ground.digits import TABLE_DIGITS, half_range, rounded
from ground.gate import write_json, write_text


def test_rounded_keeps_the_table_digits_in_every_container():
    value = {"a": 0.86481234567, "b": [1.387778781e-17, -0.0], "c": (3, "x", math.nan)}
    out = rounded(value)
    assert out["a"] == 0.864812 and f"{out['a']:.{TABLE_DIGITS + 3}g}" == "0.864812"
    assert out["b"] == [1.38778e-17, 0.0] and math.copysign(1.0, out["b"][1]) == 1.0
    assert out["c"][:2] == (3, "x") and math.isnan(out["c"][2])


def test_a_spread_of_values_equal_to_their_digits_is_exactly_zero():
    """Fitting choices that give one beta0 but for its last bits (grazing's
    1.4e-17 on one CPU, 6.9e-18 on another) spread by exactly 0."""
    beta0 = -0.2263718125
    assert half_range([beta0, beta0 * (1 + 2**-52), beta0 * (1 - 2**-51)]) == 0.0
    assert half_range([0.1, 0.3]) == pytest.approx(0.1, abs=0)
    assert math.isnan(half_range([]))


def test_numbers_moved_in_their_last_bits_round_the_same():
    for value in (0.8648123, -0.98512, 23.527514, 2.917433783e-06, 0.5000010652):
        moved = [value * (1 + k * 2**-52) for k in range(-4, 5)]
        assert len({rounded(v) for v in moved}) == 1


def test_a_write_is_whole_or_not_at_all(tmp_path):
    """A write that fails midway leaves the old file and no temporary one."""
    path = tmp_path / "fits.json"
    write_json(path, {"mu": 0.1234567891})
    assert path.read_text() == '{\n "mu": 0.123457\n}\n'

    class Unwritable:
        def __str__(self):
            raise RuntimeError("cut")

    with pytest.raises(TypeError):
        write_json(path, {"mu": Unwritable()})
    assert path.read_text() == '{\n "mu": 0.123457\n}\n'
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fits.json"]
    write_text(path, "new\n")
    assert path.read_text() == "new\n"


def test_a_write_goes_through_a_link_and_keeps_the_file_s_permissions(tmp_path):
    """The gate checks where a link leads; the write lands there too (not
    on the link, which stays a link), and the file keeps its mode."""
    target = tmp_path / "page.md"
    target.write_text("old\n")
    target.chmod(0o640)
    link = tmp_path / "link.md"
    link.symlink_to(target)
    write_text(link, "new\n")
    assert link.is_symlink() and target.read_text() == "new\n"
    assert target.stat().st_mode & 0o777 == 0o640
