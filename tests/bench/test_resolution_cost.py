"""bench/resolution_cost.py builds, in its own process, the scene its page
describes: every option that carries the body to finer disks as spec_at
gives it, not the command line's defaults (the refined body)."""

from __future__ import annotations

import json

from bench.resolution_cost import build, spec_at
from builder.scene import BODY


def test_the_built_scene_is_the_page_scene(tmp_path):
    spec = spec_at(200, 30.0, 1)
    build(spec, tmp_path / "scene", tmp_path / "cache")
    built = json.loads((tmp_path / "scene" / "scene.json").read_text())["spec"]
    for name in BODY:
        assert built[name] == getattr(spec, name), name
    assert built["area_floor"] == 0.0 and built["contact_scaling"] == "spacing"
