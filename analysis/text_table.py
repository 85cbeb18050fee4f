"""Results as a plain-text table (what python -m runner impact and python -m
reference run print)."""

from __future__ import annotations

COLUMNS = (
    ("lattice", "{}"),
    ("seed", "{}"),
    ("gamma_deg", "{:.1f}"),
    ("cot_gamma", "{:.3f}"),
    ("e", "{:.4f}"),
    ("beta", "{:+.4f}"),
    ("omega", "{:+.4f}"),
    ("contact_time", "{:.2f}"),
    ("dt", "{:g}"),
    ("steps", "{}"),
    ("wall_seconds", "{:.1f}"),
)


def format_table(results: list[dict]) -> str:
    rows = [[name for name, _ in COLUMNS]]
    for result in results:
        rows.append(
            ["-" if result.get(name) is None else fmt.format(result[name]) for name, fmt in COLUMNS]
        )
    widths = [max(len(row[i]) for row in rows) for i in range(len(COLUMNS))]
    return "\n".join("  ".join(cell.rjust(w) for cell, w in zip(row, widths)) for row in rows)
