"""The scene's command-line options, shared by the builder, the runner and the study.

Every option is builder.scene.SCENE_OPTIONS's (builder/declared.py): its
type, range, default and help come from there. A number outside its range,
a non-finite one or an unknown choice is refused with one line that names
the option and what it may be, exit status 2, before anything is written.
"""

from __future__ import annotations

import argparse

from ground.errors import InputError, clipped

from .declared import Option
from .scene import MODEL_READINGS, NU, SCENE, SCENE_OPTIONS


class OneLineParser(argparse.ArgumentParser):
    """Errors as a single line and exit status 2 (argparse prints the usage
    too). A parser given ``common`` options (their dests) shows only those
    with --help, and every option with --help-all: a command of many options
    opens on one screen."""

    common: frozenset[str] = frozenset()

    def show_common(self, dests) -> None:
        """--help shows these options (and the positionals) only; --help-all every one."""
        self.common = frozenset(dests)
        self.add_argument(
            "--help-all", action=_HelpAll, help="show every option, grouped, and exit"
        )

    def format_help(self, full: bool = False) -> str:
        if full or not self.common:
            return super().format_help()
        hidden = [
            a
            for a in self._actions
            if a.option_strings
            and a.help != argparse.SUPPRESS
            and a.dest not in self.common | {"help", "help_all"}
        ]
        saved = [a.help for a in hidden]
        for action in hidden:
            action.help = argparse.SUPPRESS
        try:
            text = super().format_help()
        finally:
            for action, help_text in zip(hidden, saved, strict=True):
                action.help = help_text
        return (
            f"{text}\n{len(hidden)} more options (the scene's, the run's): {self.prog} --help-all\n"
        )

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {clipped(message)}\n")


class _HelpAll(argparse.Action):
    """--help-all: the parser's whole help."""

    def __init__(
        self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None
    ):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        print(parser.format_help(full=True), end="")
        parser.exit()


# The readings of the model (docs/model.md section 8), SceneSpec's fields by option.
MODEL_OPTIONS = {name: SCENE[name].option for name in MODEL_READINGS}
# SceneSpec's fields by the options that set them, for messages the user can act on.
OPTIONS = {option.name: option.option for option in SCENE_OPTIONS if option.cli}


def add_option(group, option: Option, study: bool = False) -> None:
    """``option`` on ``group``. A study's take None for "the study's own"; a
    scene's options that apply to one target take None for "not given" (the
    other target refuses them), and so do the square lattice's."""
    given_only = study or option.applies or option.name == "k2_over_k1"
    option.add_argument(group, default=None if given_only else option.default)


def add_model_arguments(group, study: bool = False) -> None:
    """The readings of the model (docs/model.md section 8)."""
    for name in MODEL_READINGS:
        add_option(group, SCENE[name], study)


def add_scene_arguments(parser: argparse.ArgumentParser) -> None:
    """The options that define a scene (docs/model.md sections 1, 2 and 4)."""
    group = parser.add_argument_group("scene")
    square = group.add_mutually_exclusive_group()
    for option in SCENE_OPTIONS:
        if not option.cli or option.name in MODEL_READINGS:
            continue
        add_option(square if option.name == "k2_over_k1" else group, option)
    square.add_argument(
        "--nu",
        type=NU,
        default=None,
        help=f"square lattice only: k2/k1 that gives this Poisson ratio along the axes, "
        f"{NU.describe()}; a scene needs the ratio calibrated (0.1 and 0.3 are; "
        "python -m calibration run --square K2_OVER_K1 adds one)",
    )
    add_model_arguments(
        parser.add_argument_group("the readings of the model (docs/model.md section 8)")
    )


def validate_spec(spec) -> None:
    """SceneSpec.validate, its message naming the option rather than the field."""
    try:
        spec.validate()
    except InputError as error:
        word, _, rest = str(error).partition(" ")
        field, colon = word.rstrip(":"), word[len(word.rstrip(":")) :]
        if field in OPTIONS:
            raise InputError(f"{OPTIONS[field]}{colon} {rest}") from None
        raise


def spec_from_args(args: argparse.Namespace):
    """The SceneSpec of parsed scene options; an option that does not apply to
    the chosen lattice or target is refused, not ignored."""
    from .materials import square_ratio_for_poisson
    from .scene import SceneSpec

    values = {o.name: getattr(args, o.name) for o in SCENE_OPTIONS if o.cli}
    if args.k2_over_k1 is not None or args.nu is not None:
        if args.lattice != "square":
            option = "--nu" if args.nu is not None else "--k2-over-k1"
            raise InputError(f"{option} applies to --lattice square only, got {args.lattice}")
        if args.nu is not None:
            values["k2_over_k1"] = square_ratio_for_poisson(args.nu)
    for option in SCENE_OPTIONS:
        if option.applies and option.applies != args.target and values[option.name] is not None:
            raise InputError(
                f"{option.option} applies to --target wall; a binary scene (--target disk) "
                "has no wall"
                if option.applies == "wall"
                else f"{option.option} applies to --target disk, got --target {args.target}"
            )
    return SceneSpec(
        **{name: SCENE[name].default if value is None else value for name, value in values.items()}
    )
