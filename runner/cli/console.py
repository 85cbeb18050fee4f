"""`oblique-impact`, the project's one command: a subcommand for each entry
point, the same as its `python -m` form.

    oblique-impact scene --lattice random --gamma 30 --out runs/example
    oblique-impact impact --gamma 30 --out runs/example
    oblique-impact study paper --docs
    oblique-impact page scene_readings
    oblique-impact calibrate
    oblique-impact validate
    oblique-impact bench loop_floor --docs
"""

from __future__ import annotations

import ast
import importlib
import sys

from ground.paths import ROOT

BENCH = ROOT / "bench"
# subcommand -> (module with main(argv), the words it puts first, what it does)
COMMANDS = {
    "scene": ("builder.__main__", ["scene"], "build a scene folder (python -m builder scene)"),
    "impact": ("runner.__main__", ["impact"], "build and run one impact, print its result"),
    "run": ("runner.__main__", ["run"], "run an existing scene folder"),
    "study": ("runner.__main__", ["study"], "a study file's study: runs, tables, page"),
    "page": ("runner.__main__", ["page"], "a study's page again from its committed tables"),
    "tilt": ("runner.__main__", ["tilt"], "the wall's tilt under the disk, from dumps"),
    "calibrate": ("calibration.__main__", ["run"], "measure E, nu and c of every lattice"),
    "validate": ("bench.validation", [], "LAMMPS against the reference integrator"),
    "bench": ("bench", [], "a benchmark of the tool: oblique-impact bench NAME [options]"),
}
PROG = "oblique-impact"


def benchmarks() -> list[str]:
    """The benchmarks' names (bench/*.py but the package's own modules)."""
    return sorted(p.stem for p in BENCH.glob("*.py") if p.stem not in ("common", "__init__"))


def bench_usage() -> str:
    """oblique-impact bench's usage: each benchmark with its docstring's first line."""
    width = max(map(len, benchmarks()))
    lines = [f"usage: {PROG} bench NAME [options]   ({PROG} bench NAME -h for its options)", ""]
    for name in benchmarks():
        doc = ast.get_docstring(ast.parse((BENCH / f"{name}.py").read_text())) or ""
        paragraph = " ".join(doc.split("\n\n")[0].split())
        lines.append(f"  {name:<{width}}  {paragraph.split('. ')[0].rstrip('.')}")
    return "\n".join(lines)


def usage() -> str:
    width = max(map(len, COMMANDS))
    lines = [f"usage: {PROG} COMMAND [options]   ({PROG} COMMAND -h for its options)", ""]
    lines += [f"  {name:<{width}}  {what}" for name, (_, _, what) in COMMANDS.items()]
    lines += ["", "benchmarks: " + " ".join(benchmarks())]
    return "\n".join(lines)


def refuse(message: str) -> int:
    print(f"{PROG}: error: {message}", file=sys.stderr)
    return 2


def main(argv: list[str] | None = None) -> int:
    """Run the subcommand ``argv[0]`` with the rest of ``argv``; its exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(usage())
        return 0 if argv else 2
    command, rest = argv[0], argv[1:]
    if command not in COMMANDS:
        return refuse(f"COMMAND must be one of {', '.join(COMMANDS)}, got {command!r}")
    module, words, _ = COMMANDS[command]
    if command == "bench":
        if not rest or rest[0] in ("-h", "--help"):
            print(bench_usage())
            return 0 if rest else 2
        if rest[0] not in benchmarks():
            return refuse(f"bench NAME must be one of {', '.join(benchmarks())}, got {rest[0]!r}")
        module, rest = f"bench.{rest[0]}", rest[1:]
    return importlib.import_module(module).main(words + rest)


if __name__ == "__main__":
    sys.exit(main())
