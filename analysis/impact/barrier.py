"""What the barrier against turned-over triangles (``--area-floor``) saw in
a run: barrier.dat, written by decks/impact.lmp from fix area/barrier."""

from __future__ import annotations

from pathlib import Path


def barrier_counts(folder: Path | str) -> dict:
    """``in_barrier_max``, the most triangles inside the barrier at once
    (J < J_c), and ``area_ratio_min``, the smallest J any triangle reached;
    {} for a run without the barrier (no barrier.dat), so that its result
    is as before."""
    path = Path(folder) / "barrier.dat"
    if not path.is_file():
        return {}
    most, smallest = (float(v) for v in path.read_text().splitlines()[-1].split())
    return {"in_barrier_max": int(most), "area_ratio_min": smallest}
