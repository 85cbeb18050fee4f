"""Errors for bad input, worded for the person who typed it."""

from __future__ import annotations

from collections.abc import Iterable


class InputError(ValueError):
    """A parameter outside its allowed values; the message names both."""


class BuildError(RuntimeError):
    """A lattice that cannot be built as asked (a geometric failure)."""


def require_choice(name: str, value: str, choices: Iterable[str]) -> None:
    choices = list(choices)
    if value not in choices:
        raise InputError(f"{name} must be one of {', '.join(choices)}; got {value!r}")
