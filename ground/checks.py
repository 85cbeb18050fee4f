"""What a value may be: one definition for the command line and the code.

Every number an entry point takes is a ``Range``: argparse calls it on the
text (an error names the option, argparse adds it), and the dataclasses that
hold the value call ``Range.check`` with the field's name. Both refuse
non-finite numbers and say the allowed range in the same words. Folders that
a command writes into are ``OutFolder``s, checked before any work; files and
folders it reads are ``InPath``s. tests/runner/cli/test_bad_input.py feeds every option
of every entry point the values these refuse.
"""

from __future__ import annotations

import argparse
import math
import tempfile
from dataclasses import dataclass
from numbers import Integral, Real
from pathlib import Path

from .errors import InputError
from .gate import expanded, protected_problem
from .words import LAMMPS_UNSAFE, portable_problem, word_problem  # noqa: F401 (checks' own)


def _number_text(value: float) -> str:
    # integers in full (a seed's bound is 4294967295, not 4.29497e+09)
    if float(value).is_integer() and abs(value) < 1e16:
        return str(int(value))
    return f"{value:g}"


@dataclass(frozen=True)
class Range:
    """A finite number (or integer) between optional bounds.

    ``low_open`` / ``high_open`` exclude the bound itself; ``unit`` is said
    after the range ("units of c"). Call it on a command-line text (an
    argparse ``type``) or use ``check`` on a value.
    """

    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    integer: bool = False
    unit: str = ""

    def describe(self) -> str:
        """The allowed values in words: 'a number in (0, 1) (units of c)'."""
        kind = "an integer" if self.integer else "a number"
        if self.low is not None and self.high is not None:
            left, right = "(" if self.low_open else "[", ")" if self.high_open else "]"
            text = f"{kind} in {left}{_number_text(self.low)}, {_number_text(self.high)}{right}"
        elif self.low is not None:
            text = f"{kind} {'>' if self.low_open else '>='} {_number_text(self.low)}"
        elif self.high is not None:
            text = f"{kind} {'<' if self.high_open else '<='} {_number_text(self.high)}"
        else:
            text = f"a finite {kind.split()[-1]}"
        return f"{text} ({self.unit})" if self.unit else text

    def contains(self, value) -> bool:
        if isinstance(value, bool) or not isinstance(value, Real):
            return False
        # an integer's value must be one, as the command line reads it: 2.0
        # from a file would reach LAMMPS as "2.0", where it wants 2
        if self.integer and not isinstance(value, Integral):
            return False
        if not math.isfinite(value):
            return False
        if self.low is not None and (value <= self.low if self.low_open else value < self.low):
            return False
        if self.high is not None and (value >= self.high if self.high_open else value > self.high):
            return False
        return True

    def check(self, name: str, value):
        """``value`` if allowed, else InputError naming ``name`` and the range."""
        if not self.contains(value):
            raise InputError(f"{name} must be {self.describe()}, got {value!r}")
        return int(value) if self.integer else plain_zero(float(value))

    def __call__(self, text: str):
        """argparse's type: the text as a number, or an error with the range."""
        try:
            value = int(text) if self.integer else float(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text!r}") from None
        if not self.contains(value):
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text}")
        return plain_zero(value)

    @property
    def __name__(self) -> str:  # argparse names a type by it in some messages
        return "integer" if self.integer else "number"


def plain_zero(value):
    """-0.0 as 0.0, anything else as it is: one rule for the command line and
    the study files (a -0 folder name beside a 0 one would be two impacts)."""
    if isinstance(value, float) and value == 0.0:
        return 0.0
    if isinstance(value, list):
        return [plain_zero(v) for v in value]
    if isinstance(value, dict):
        return {k: plain_zero(v) for k, v in value.items()}
    return value


def folder_problem(path: Path | str) -> str | None:
    """Why a folder cannot be created and written at ``path``, or None.

    Looks for the nearest existing ancestor: it must be a folder in which a
    file can be made (tried with a temporary folder, removed at once, since
    permission bits do not stop root but a read-only or virtual file system
    such as /proc or /sys does). Nothing is left behind.
    """
    path = Path(path).absolute()
    if path.exists() and not path.is_dir():
        return "is a file, not a folder"
    ancestor = path
    while not ancestor.exists():
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        return f"is under {ancestor}, which is a file"
    try:
        tempfile.TemporaryDirectory(dir=ancestor, prefix=".write-check-").cleanup()
    except OSError as error:
        return f"cannot be made: no folder can be created in {ancestor} ({error.strerror or error})"
    return None


def require_out_folder(name: str, path: Path | str) -> Path:
    """``path`` as a Path if a run can write there (not inside the project's
    record or code: ground.paths) and LAMMPS can name it, else InputError
    naming the option."""
    path = expanded(path)
    problem = protected_problem(path) or word_problem(str(path.absolute())) or folder_problem(path)
    if problem:
        raise InputError(f"{name}: {path} {problem}")
    return path


@dataclass(frozen=True)
class OutFolder:
    """argparse's type for a folder a command writes into (created if missing)."""

    lammps: bool = True  # whether LAMMPS must be able to take its path

    def __call__(self, text: str) -> Path:
        if not text:
            raise argparse.ArgumentTypeError("must be a folder's path, got ''")
        path = expanded(text)  # the check and the write: the same folder
        problem = (
            protected_problem(path)
            or (word_problem(str(path.absolute())) if self.lammps else None)
            or folder_problem(path)
        )
        if problem:
            raise argparse.ArgumentTypeError(f"{text} {problem}")
        return path

    __name__ = "folder"


@dataclass(frozen=True)
class InPath:
    """argparse's type for a file or folder a command reads; it must exist and,
    if ``needs`` names files, hold them."""

    kind: str = "folder"  # folder or file
    needs: tuple[str, ...] = ()

    def __call__(self, text: str) -> Path:
        path = expanded(text)
        if self.kind == "file" and not path.is_file():
            raise argparse.ArgumentTypeError(f"must be an existing file, got {text!r}")
        if self.kind == "folder":
            if not path.is_dir():
                raise argparse.ArgumentTypeError(f"must be an existing folder, got {text!r}")
            missing = [name for name in self.needs if not (path / name).is_file()]
            if missing:
                raise argparse.ArgumentTypeError(f"{text} has no {', '.join(missing)}")
        return path

    __name__ = "path"
