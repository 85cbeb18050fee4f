"""Options declared once: a table of ``Option`` from which a dataclass's
fields, its checks, the command line's arguments, a study file's keys and
the "made by" command line are all derived.

    SCENE_OPTIONS = (Option("n_disk", 800, "points in the disk", N_DISK), ...)

    @with_options(SCENE_OPTIONS)
    class SceneSpec: ...          # a dataclass with a field per option

An option is a number in a ``Range``, one of some words, or either
(``Value``); ``section`` says where a study file gives it ([scene], [run],
[grid]); ``study`` whether a study takes it (runner study's option and its
file's key); ``cli`` whether the one-scene commands take it (python -m
builder scene, python -m runner impact/run).
"""

from __future__ import annotations

import argparse
import dataclasses
from dataclasses import dataclass
from typing import Any

from ground.checks import Range
from ground.errors import InputError, require_choice

# ``Option.before``'s "the default's" (None is a value).
UNSET = object()


@dataclass(frozen=True)
class Value:
    """A number in ``numbers``, or one of ``words`` (the same type and value:
    0 is a word of ``every``, 0.0 and false are not); ``many``: a list of
    distinct such values."""

    numbers: Range | None = None
    words: tuple = ()
    many: bool = False

    def describe(self) -> str:
        """The allowed values in words, as the command line says them."""
        if self.numbers is None:
            text = "one of " + ", ".join(map(str, self.words))
        else:
            text = " or ".join([self.numbers.describe(), *map(repr, self.words)])
        return f"a list of distinct values, each {text}" if self.many else text

    def allows(self, value) -> bool:
        if any(type(value) is type(word) and value == word for word in self.words):
            return True
        return self.numbers is not None and self.numbers.contains(value)

    def check(self, name: str, value):
        """``value`` if allowed, else InputError naming ``name`` and what it may be."""
        if self.many:
            if not isinstance(value, (list, tuple)) or not value:
                raise InputError(f"{name} must be {self.describe()}, got {value!r}")
            for each in value:
                if not self.allows(each):
                    raise InputError(f"{name} must be {self.describe()}, got {each!r} in {value!r}")
            if len({repr(v) for v in value}) != len(value):
                raise InputError(f"{name} names a value twice, got {value!r}")
            return value
        if not self.allows(value):
            raise InputError(f"{name} must be {self.describe()}, got {value!r}")
        return value

    def __call__(self, text: str):
        """argparse's type: a word, or the text as a number in ``numbers``."""
        for word in self.words:
            if str(word) == text:
                return word
        if self.numbers is None:
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text!r}")
        try:
            return self.numbers(text)
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(f"must be {self.describe()}, got {text}") from None

    @property
    def __name__(self) -> str:  # argparse names a type by it in some messages
        return "value"


@dataclass(frozen=True)
class Option:
    """One option, declared once.

    Parameters
    ----------
    name : str
        The field's name, a study file's key; the command line's is
        ``flag`` (default ``--name-with-dashes``).
    default : object
        The field's default (None: see ``help``).
    help : str
        What it is, for --help; the range and the default are added.
    numbers : ground.checks.Range, optional
        The numbers it takes from the command line and a study file.
    words : tuple
        The words it takes (alone, or besides ``numbers``).
    section : str
        "scene", "run" or "grid": a study file's table for it.
    study : bool
        Whether a study takes it (runner study's option, its file's key,
        study.json's record).
    cli : bool
        Whether the one-scene commands take it (builder scene, runner impact/run).
    study_cli : bool
        Whether runner study takes it (a study file's [run] takes every run option).
    kind : type
        Its type, as a dataclass field's annotation says it.
    scene_numbers : ground.checks.Range, optional
        What the object itself accepts where wider than what a user may
        give (the code's 0 angle, a benchmark's faster scenes); default ``numbers``.
    hide_words : bool
        Its refusal names the range alone (the range's unit says the words).
    applies : str
        "wall" or "disk": the target it applies to ("" both); the "made by"
        command line leaves it out for the other.
    made_by : str
        How the "made by" command line gives it: "always", "changed" (where
        not its default), or "" (never).
    before : object
        What a record from before the option existed means (``made_by``);
        default ``default``.
    flag : str
        The command line's option; default ``--`` + name with dashes.
    by_target : tuple
        The default by target, (target, value) pairs, where it is the body's
        (``default`` None: the scene takes the value of its target).
    """

    name: str
    default: Any
    help: str
    numbers: Range | None = None
    words: tuple = ()
    section: str = "scene"
    study: bool = True
    cli: bool = True
    study_cli: bool = True
    kind: Any = None
    scene_numbers: Range | None = None
    hide_words: bool = False
    applies: str = ""
    made_by: str = ""
    before: Any = UNSET
    flag: str = ""
    by_target: tuple = ()

    @property
    def option(self) -> str:
        """The command line's option: --n-disk."""
        return self.flag or "--" + self.name.replace("_", "-")

    @property
    def value(self) -> Value:
        """What the command line and a study file take (runner/values.py)."""
        return Value(self.numbers, self.words)

    @property
    def annotation(self) -> Any:
        kind = self.kind or type(self.default)
        return kind

    def default_for(self, target: str) -> Any:
        """The default of a scene whose target is ``target`` (``by_target``'s
        value, else ``default``)."""
        return dict(self.by_target).get(target, self.default)

    @property
    def recorded_before(self) -> Any:
        """What a record that lacks the option means."""
        return self.default if self.before is UNSET else self.before

    def check(self, value, name: str | None = None) -> None:
        """Refuse ``value`` in one line naming the option (``name``, default
        the field's) and what it may be: the object's own check."""
        name = name or self.name
        if value is None and self.default is None:  # None: what the option says it means
            return
        if any(type(value) is type(w) and value == w for w in self.words):
            return
        numbers = self.scene_numbers or self.numbers
        if numbers is None:
            require_choice(name, value, self.words)
        elif self.words and not self.hide_words:
            Value(numbers, self.words).check(name, value)
        else:
            numbers.check(name, value)

    def add_argument(self, group, default: Any = dataclasses.MISSING, **extra) -> None:
        """This option on an argparse ``group``: its type or choices, its help
        with the range and the default."""
        default = self.default if default is dataclasses.MISSING else default
        if self.numbers is None:
            typed = {"choices": self.words}
            said = ""
        elif self.hide_words:  # the range's unit says the words
            typed = {"type": self.parse_hidden}
            said = f", {self.numbers.describe()}"
        else:
            typed = {"type": self.value if self.words else self.numbers}
            said = f", {self.value.describe()}"
        shown = self.default
        tail = f" (default: {shown:g})" if isinstance(shown, float) else f" (default: {shown})"
        if shown is None:
            tail = ""
        if self.by_target:
            words = [f"{v:g}" if isinstance(v, float) else str(v) for _, v in self.by_target]
            pairs = (f"{v} with --target {t}" for v, (t, _) in zip(words, self.by_target))
            tail = f" (default: {', '.join(pairs)})"
        help_text = f"{self.help}{said}{tail}".replace("%", "%%")
        group.add_argument(
            self.option, dest=self.name, default=default, help=help_text, **typed, **extra
        )

    @property
    def parse_hidden(self):
        """argparse's type for an option whose words its range's unit names:
        a word, or a number in the range (refused naming the range alone)."""
        value, numbers = self.value, self.numbers

        def parse(text: str):
            for word in value.words:
                if str(word) == text:
                    return word
            return numbers(text)

        parse.__name__ = "value"
        low = numbers.low if numbers.low is not None else 0.0
        parse.bad_values = ("nan", "abc", "-1", "1e300", f"{low / 2:g}" if low > 0 else "-0.1")
        return parse

    def made_by_words(self, record: dict) -> str:
        """This option as the "made by" command line of a study ``record``
        (study.json's dict) gives it, or "" where it leaves it out."""
        if not self.made_by:
            return ""
        target = record.get("target", "wall")
        if self.applies and self.applies != target:
            return ""
        value = record.get(self.name, self.recorded_before)
        if self.made_by == "changed" and value in (self.default_for(target), None):
            return ""
        if value is None:
            return ""
        shown = f"{value:g}" if isinstance(value, float) else str(value)
        return f"{self.option} {shown}"


def with_options(options: tuple[Option, ...], after: str | None = None):
    """A class decorator: the class as a dataclass with a field per option
    (its default, its type), placed after the field ``after`` of the class's
    own (default: before them all)."""

    def make(cls):
        own = dict(cls.__dict__.get("__annotations__", {}))
        names = list(own)
        at = names.index(after) + 1 if after else 0
        notes = {n: own[n] for n in names[:at]}
        for option in options:
            notes[option.name] = option.annotation
            setattr(cls, option.name, option.default)
        notes.update({n: own[n] for n in names[at:]})
        cls.__annotations__ = notes
        return dataclass(cls)

    return make


def by_name(options: tuple[Option, ...]) -> dict[str, Option]:
    return {option.name: option for option in options}
