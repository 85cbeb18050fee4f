"""What every page's text is made of: a number with its error, a count in
words, a Markdown table, the options a reading changes."""

from __future__ import annotations

import math

from analysis.study_tables import PROVENANCE


def pm(value, sd=None, digits: int = 3) -> str:
    """value +- sd, or '-' without a value."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if sd is None or not math.isfinite(sd):
        return f"{value:.{digits}f}"
    return f"{value:.{digits}f} +- {sd:.{digits}f}"


NUMBER_WORDS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine")


def plural(count: int, word: str, many: str | None = None) -> str:
    """``word`` for one, ``many`` (default: ``word`` + 's') for any other count."""
    return word if count == 1 else (many if many is not None else word + "s")


def markdown_table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


# What a reading's study.json may differ in from the study's and still be a
# reading of it: everything but its name and the records of its run (how
# long it took, what its study file said).
NOT_A_READING = ("name", "common_wall", "source", *PROVENANCE)


def reading_differences(study: dict, reading: dict) -> str:
    """The options a reading's study.json sets otherwise than the study's
    (the grazing page's readings, pages/templates/grazing.md.j2)."""
    words = []
    for key in sorted(set(study) | set(reading)):
        if key in NOT_A_READING or study.get(key) == reading.get(key):
            continue
        if isinstance(reading.get(key), dict):  # the run's options
            inner = reading[key]
            words += [
                f"{k} {inner[k]}"
                for k in sorted(inner)
                if inner.get(k) != study.get(key, {}).get(k)
            ]
        else:
            words.append(f"{key} {reading.get(key)}")
    return ", ".join(words) or "none"
