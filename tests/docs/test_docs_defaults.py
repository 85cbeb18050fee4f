"""The docs quote the code's defaults, not yesterday's.

Three checks, each able to fail on a default changed in the code alone:

- a registry of phrases per hand-written page, each filled in from the code
  (SceneSpec's and RunOptions' dataclass defaults and what they make of the
  default scene: the step of dt "auto", the rows' and checks' steps, the
  wall's points, the contact's decay lengths), must be on its page;
- usage.md's table of defaults is parsed row by row against SceneSpec;
- every "`--option` ... (default X" in a hand-written page, and every "the
  default is (stays) dt = X" anywhere in docs/, must match the code.

docs/benchmarks/time_vs_error.md, written by bench/time_vs_error.py, must be
that script's text for its committed table (time_vs_error.json): a default
changed in the code then fails here until `make bench` remakes the page.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
import tomllib
from fractions import Fraction

import pytest

from analysis.impact.result import MAX_DRIFT
from builder.scene import SceneSpec
from ground.paths import ROOT
from runner.options import AUTO, DEFAULT_DT, RESPA_DT, RESPA_NRESPA, SERIES_INTERVAL, RunOptions

HAND_WRITTEN = (
    "README.md",
    "docs/model.md",
    "docs/usage.md",
    "docs/benchmarks.md",
    "docs/validation.md",
    "docs/cluster.md",
    "docs/contact.md",
    "docs/calibration.md",
    "docs/index.md",
)


def code_defaults() -> dict[str, str]:
    """The defaults as the pages write them, read from the code."""
    scene, run = SceneSpec(), RunOptions()
    fields = {f.name: getattr(scene, f.name) for f in dataclasses.fields(SceneSpec)}
    fields.update({f.name: getattr(run, f.name) for f in dataclasses.fields(RunOptions)})
    text = {k: (f"{v:g}" if isinstance(v, float) else str(v)) for k, v in fields.items()}
    at_default = run.for_scene(scene)  # dt "auto" made a number for the default scene
    fine = SceneSpec(n_disk=12_800)
    text.update(
        dt_word=str(run.dt),
        dt=f"{at_default.dt:g}",
        dt_fine=f"{run.for_scene(fine).dt:g}",
        a_fine=f"{fine.contact_decay * fine.radius:g}",
        every_steps=str(at_default.every_steps),
        check_steps=str(at_default.check_steps),
        series=f"{at_default.every_steps * at_default.dt:g}",
        check_time=f"{at_default.check_steps * at_default.dt:g}",
        wall_over_disk={2: "twice"}.get(scene.n_wall / scene.n_disk, "?"),
        kb=f"{scene.kb_over_ka:.0e}".replace("e-0", "e-"),
        k2=str(Fraction(scene.k2_over_k1).limit_denominator(100)),
        cutoff=f"{scene.wall_spacing:.4f}",
        decays=f"{round(scene.contact_decay * scene.wall_spacing)}",
        max_drift=f"{MAX_DRIFT:g}",
        respa_dt=f"{RESPA_DT:g}",
        respa_inner=f"{RESPA_DT / RESPA_NRESPA:g}",
    )
    for study in ("paper", "demo"):  # the studies the pages describe, as their files say
        grid = tomllib.loads((ROOT / "studies" / f"{study}.toml").read_text())["grid"]
        text.update({f"{study}_{k}": str(v) for k, v in grid.items() if k != "lattices"})
        text[f"{study}_lattices"] = str(len(grid["lattices"]))
    return text


# Each phrase, filled in from code_defaults(), must be on its page.
PHRASES = {
    "README.md": [
        "the disk's motion every {series} R/c",
        "{paper_samples} samples per point",
    ],
    "docs/model.md": [
        "e and beta at {paper_angles} angles",
        "{paper_samples} samples each",
        "normal speed v_n = {paper_vn} c",
        "a = {contact_a} / R",
        "sd delta = {roughness} R",
        "The wall is a rectangle {wall_width}R wide and {wall_height}R high",
        "kb / ka = {kb}",
        "`--n-wall {n_wall} --wall-ka {wall_ka} --wall-fixed {wall_fixed} "
        "--contact-mass {contact_mass}`",
        "(default: {wall_over_disk} the disk's;",
        "`kb = {kb} ka`",
        "`--k2-over-k1`\n  (default {k2})",
        "**`--roughness-length L`** (default {roughness_length}:",
        "**`--contact-scaling spacing|fixed`** (default {contact_scaling}",
        "**`--dt {dt_word}`** (the default): {dt} R/c",
        "{dt_fine} at 12,800 points",
        "(`integrator {integrator}`, the default)",
        "Every {series} R/c (`every`; {every_steps} steps at dt {dt})",
        "every {check_time} R/c (`check`; {check_steps} steps at dt {dt})",
        "up to `tmax` ({tmax} R/c)",
        "`{stop_rule}` (the default,",
        "T = `contact_time_guess`, {contact_time_guess} R/c",
        "`cutoff (1 + {start_gap})`",
        "above `--max-drift` (default {max_drift})",
    ],
    "docs/usage.md": [
        "random lattice, {demo_angles} angles x {demo_samples} samples",
        "{paper_lattices}\nlattices x {paper_angles} angles x {paper_samples} samples",
        "`--dt {dt_word}` ({dt} R/c\nat {n_disk} points",
        "`--integrator {integrator}`",
        "`--stop-rule\n{stop_rule}`",
        "`--springs {springs}`",
        "`--tmax {tmax}`",
        "`--max-drift {max_drift}`",
        "above `--max-drift` (default {max_drift})",
        "| `series.dat` | every {series} R/c:",
    ],
    "docs/benchmarks.md": [
        "velocity Verlet at dt = {dt} R/c at {n_disk} points",
        "the springs at {respa_dt} with the contact at {respa_inner}",
        "below the {max_drift}\n  guard",
    ],
    "docs/validation.md": [
        "(velocity Verlet, dt = {dt}\n  R/c)",
        "under the default {max_drift} the same impact",
    ],
    "docs/cluster.md": [
        "the wall has {wall_over_disk} the disk's points",
        "(`--contact-scaling {contact_scaling}`: a R = {contact_a} at any n_disk)",
        "(`--dt {dt_word}`:\n{dt} sqrt({n_disk} / n_disk))",
    ],
    "docs/contact.md": [
        "a = {contact_a} / R",
        "`a d` = {contact_a} x\n{cutoff} = {decays} decay lengths",
        "(`--contact-scaling {contact_scaling}`, a R = {contact_a} at any n_disk",
    ],
}


def fill(phrase: str, values: dict[str, str]) -> str:
    """The phrase with the code's values."""
    return phrase.format(**values)


def page(name: str) -> str:
    return (ROOT / name).read_text()


def flat(text: str) -> str:
    """Line breaks and runs of spaces as one space: a phrase may be rewrapped."""
    return re.sub(r"\s+", " ", text)


@pytest.mark.parametrize("name", sorted(PHRASES))
def test_each_page_quotes_the_code_defaults(name):
    values = code_defaults()
    text = flat(page(name))
    missing = [fill(p, values) for p in PHRASES[name] if flat(fill(p, values)) not in text]
    assert not missing, f"{name} no longer says the code's defaults: {missing}"


def test_the_registry_reads_the_code():
    """The registry's values are the code's: change a default and a phrase
    changes with it (so a page that kept the old one fails above)."""
    values = code_defaults()
    assert values["dt_word"] == AUTO and values["dt"] == f"{DEFAULT_DT:g}"
    assert int(values["every_steps"]) * DEFAULT_DT == pytest.approx(SERIES_INTERVAL)
    changed = dataclasses.replace(SceneSpec(), wall_ka=3.0)
    assert f"{changed.wall_ka:g}" != values["wall_ka"]
    phrase = "`--n-wall {n_wall} --wall-ka {wall_ka}"
    assert fill(phrase, values) != fill(phrase, {**values, "wall_ka": "3"})


def usage_defaults_table() -> list[tuple[str, str]]:
    """(option, default) of each row of usage.md's table of defaults."""
    rows = []
    for line in page("docs/usage.md").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and re.fullmatch(r"`--[a-z0-9-]+`", cells[0]):
            rows.append((cells[0].strip("`").lstrip("-"), cells[2]))
    return rows


def test_usage_table_of_defaults_is_the_code():
    scene = SceneSpec()
    rows = usage_defaults_table()
    assert len(rows) >= 12, "usage.md's table of defaults is missing"
    for option, default in rows:
        field = option.replace("-", "_")
        assert hasattr(scene, field), f"usage.md lists --{option}, which SceneSpec lacks"
        value = getattr(scene, field)
        if field == "n_wall":  # None in the code: twice the disk's points
            expected = f"twice `--n-disk` ({value} at {scene.n_disk} points)"
        else:
            expected = f"{value:g}" if isinstance(value, float) else str(value)
        assert default == expected, f"usage.md: --{option} default {default!r}, code {expected!r}"


# "`--option` ... (default X" in a hand-written page
OPTION_DEFAULT = re.compile(r"`--([a-z0-9-]+)[^`]*`[^.;()\n]{0,30}\(default:? `?([A-Za-z0-9./+-]+)")


def test_no_option_quotes_another_default():
    scene, run = SceneSpec(), RunOptions()
    checked = 0
    for name in HAND_WRITTEN:
        for option, quoted in OPTION_DEFAULT.findall(flat(page(name))):
            field = option.replace("-", "_")
            owner = scene if hasattr(scene, field) else run if hasattr(run, field) else None
            if owner is None:
                continue
            value, quoted = getattr(owner, field), quoted.rstrip(".:")
            if field == "n_wall":  # None in the code: twice the disk's points
                assert quoted == "twice" and value == 2 * scene.n_disk, (name, option, quoted)
            elif isinstance(value, (int, float)) and not isinstance(value, bool):
                assert float(Fraction(quoted)) == pytest.approx(value), (name, option, quoted)
            else:
                assert quoted == str(value), (name, option, quoted, value)
            checked += 1
    assert checked >= 3


DEFAULT_STEP = re.compile(r"[Dd]efault (?:stays|is|remains) dt = \**([0-9.]+(?:e-?\d+)?)")


def test_no_page_claims_another_default_step():
    """docs/ and the README, generated pages included."""
    step = float(code_defaults()["dt"])
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    claims = [
        (p.relative_to(ROOT), float(m)) for p in pages for m in DEFAULT_STEP.findall(p.read_text())
    ]
    assert claims, "no page states the default step"
    wrong = [(str(p), v) for p, v in claims if not math.isclose(v, step)]
    assert not wrong, f"pages that claim another default step than {step:g}: {wrong}"


def test_time_vs_error_page_is_its_script_text():
    """The committed page is bench/time_vs_error.py's text for its committed
    table; a changed default (its paragraph quotes DEFAULT_DT) fails here until
    `make bench` writes the page again."""
    from bench.time_vs_error import render

    folder = ROOT / "docs" / "benchmarks"
    table = json.loads((folder / "time_vs_error.json").read_text())
    text = (folder / "time_vs_error.md").read_text()
    header, _, body = text.partition("\n\n")  # the title
    _, _, body = body.partition("\n\n")  # "Generated by ..."
    assert body == render(table) + "\n"
