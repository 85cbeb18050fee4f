"""The one renderer of the pages' prose: Jinja2 templates in analysis/templates/.

A page kind keeps its numbers and tables in Python and its sentences in a
template, which gets them as variables; an undefined variable is an error
(StrictUndefined), not an empty string, so a template and its caller that
drift apart stop the page instead of printing a hole in it.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import jinja2

TEMPLATES = Path(__file__).resolve().parent / "templates"


@cache
def environment() -> jinja2.Environment:
    # Markdown, not HTML: nothing to escape; a template's last newline is the page's.
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        autoescape=False,
    )


def render(template: str, **context) -> str:
    """The text of ``template`` (a file of analysis/templates/) with ``context``."""
    return environment().get_template(template).render(**context)
