"""Errors for bad input, worded for the person who typed it."""

from __future__ import annotations

from collections.abc import Iterable
from numbers import Real


class InputError(ValueError):
    """A parameter outside its allowed values; the message names both."""


class BuildError(RuntimeError):
    """A lattice that cannot be built as asked (a geometric failure)."""


def require_positive(name: str, value: Real) -> None:
    if not value > 0:
        raise InputError(f"{name} must be > 0, got {value}")


def require_nonnegative(name: str, value: Real) -> None:
    if not value >= 0:
        raise InputError(f"{name} must be >= 0, got {value}")


def require_open_interval(name: str, value: Real, low: Real, high: Real) -> None:
    if not low < value < high:
        raise InputError(f"{name} must be in ({low}, {high}), got {value}")


def require_choice(name: str, value: str, choices: Iterable[str]) -> None:
    choices = list(choices)
    if value not in choices:
        raise InputError(f"{name} must be one of {', '.join(choices)}; got {value!r}")
