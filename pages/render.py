"""The one renderer of the pages' prose: Jinja2 templates in pages/templates/.

A page kind keeps its numbers in analysis/ and its sentences in a template,
which gets them as variables; an undefined variable is an error
(StrictUndefined), not an empty string, so a template and its caller that
drift apart stop the page instead of printing a hole in it. Block tags take
their own line whole (trim_blocks, lstrip_blocks); ``+%}`` keeps the line's end.

Filters: ``x | f("0.3f")`` is Python's ``format(x, "0.3f")``; ``pm`` is
pages.text.pm (a value +- its error, or '-'); ``n | word`` a small count
in words; ``n | plural("impact")`` the word for that count. Globals: the
helpers the templates call (``finite``, ``atan_degrees``, ...).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import jinja2
import numpy as np

from analysis.grazing import significant

from .text import NUMBER_WORDS, plural, pm, reading_differences

TEMPLATES = Path(__file__).resolve().parent / "templates"


@cache
def environment() -> jinja2.Environment:
    # Markdown, not HTML: nothing to escape; a template's last newline is the page's.
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,
    )
    env.filters["f"] = format
    env.filters["pm"] = pm
    env.filters["plural"] = plural
    env.filters["word"] = NUMBER_WORDS.__getitem__
    env.globals.update(
        zip=zip,
        finite=lambda x: bool(np.isfinite(x)),
        atan_degrees=lambda t: np.degrees(np.arctan(t)),
        significant=significant,
        reading_differences=reading_differences,
    )
    return env


def render(template: str, **context) -> str:
    """The text of ``template`` (a file of pages/templates/) with ``context``."""
    return environment().get_template(template).render(**context)


def macro(template: str, name: str, *args) -> str:
    """The text of the macro ``name`` of ``template`` called with ``args``."""
    return str(getattr(environment().get_template(template).module, name)(*args))
