"""Numbers written as what they mean: the significant digits every table,
JSON record and figure of a page carries (``TABLE_DIGITS``), and spreads
taken of those numbers, so that a spread of equal values is exactly 0.

A page made again from the same tables on another CPU (another vector
width, another BLAS kernel, another order of summing) computes its numbers
with other rounding errors in their last bits. Rounded to TABLE_DIGITS, a
number computed to its last bits (the fits are closed forms, or roots found
to the last bits: analysis/statistics/fits.py) comes out the same unless it
lies within a few ulps of a rounding edge, about one chance in 1e9 a number.
Six digits are two more than any page prints (0.8648 +- 0.0040, chi2/dof
96, p 0.058), so that a difference or a ratio a page forms from the written
numbers is still right in every digit it shows; the errors of those numbers
are 1e-4 of them and larger.
"""

from __future__ import annotations

import math

TABLE_DIGITS = 6


def rounded(value, digits: int = TABLE_DIGITS):
    """``value`` with every float in it (in dicts, lists, tuples) to ``digits``
    significant digits; other values as they are. -0.0 becomes 0.0."""
    if isinstance(value, float):
        if not math.isfinite(value):
            return value
        return float(f"{value:.{digits}g}") + 0.0
    if isinstance(value, dict):
        return {k: rounded(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(rounded(v, digits) for v in value)
    return value


def half_range(values) -> float:
    """Half the range of ``values`` as written (``rounded``): exactly 0 where
    they agree to TABLE_DIGITS, NaN for none."""
    written = [rounded(float(v)) for v in values]
    if not written:
        return math.nan
    return rounded(0.5 * (max(written) - min(written)))
