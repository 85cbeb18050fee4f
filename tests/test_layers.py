"""The project's layers, read from the import statements of its source (ast,
nothing imported): ground/ imports no other package of the project; builder,
analysis, reference and calibration never import runner; no module of the
project imports itself back through others (an import circle).

Every import counts, also one inside a function: a lazy import is a
dependency all the same. The packages are pyproject.toml's, so a new one is
checked as soon as it is installed.
"""

from __future__ import annotations

import ast
import tomllib
from functools import cache
from pathlib import Path

import pytest

from ground.paths import ROOT

# The packages that must not import runner (the study runner sits above them).
BELOW_RUNNER = ("builder", "analysis", "pages", "reference", "calibration")


def packages() -> list[str]:
    """The project's top-level packages, as pyproject.toml installs them."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    return [name for name in config["tool"]["setuptools"]["packages"] if "." not in name]


def subpackages() -> list[str]:
    """The packages pyproject.toml installs inside the top-level ones."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    return [name for name in config["tool"]["setuptools"]["packages"] if "." in name]


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@cache
def modules() -> dict[str, Path]:
    """Every module of the project's packages, by its dotted name."""
    return {
        module_name(path): path
        for package in packages()
        for path in sorted((ROOT / package).rglob("*.py"))
    }


def imported(name: str, path: Path) -> set[str]:
    """The project's modules that the module ``name`` at ``path`` imports.

    ``from a.b import c`` imports the module a.b.c if there is one, else a.b;
    relative imports are resolved against the module's package.
    """
    known = modules()
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module
            targets = [f"{source}.{alias.name}" for alias in node.names]
            targets = [t if t in known else source for t in targets]
        else:
            continue
        for target in targets:
            # the longest prefix that is a module of the project, if any
            parts = target.split(".")
            while parts and ".".join(parts) not in known:
                parts.pop()
            if parts and ".".join(parts) != name:
                found.add(".".join(parts))
    return found


@cache
def graph() -> dict[str, frozenset[str]]:
    return {name: frozenset(imported(name, path)) for name, path in modules().items()}


def cycles(edges: dict[str, frozenset[str]]) -> list[list[str]]:
    """The import circles of the graph ``edges``: strongly connected groups
    of two or more modules (Tarjan's algorithm, iterative)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    for root in edges:
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.append(member)
                    if member == node:
                        break
                if len(group) > 1:
                    found.append(sorted(group))
    return found


def imports_of(package: str, forbidden: str) -> list[str]:
    return [
        f"{name} imports {target}"
        for name, targets in sorted(graph().items())
        if name.split(".")[0] == package
        for target in sorted(targets)
        if target.split(".")[0] == forbidden
    ]


def test_the_graph_sees_the_packages_imports():
    """The parser finds imports of every form (so that the tests below can fail)."""
    edges = graph()
    assert "builder.scene" in edges["builder.lammps_data"]  # from .scene import ...
    assert "builder.bodies" in edges["builder.scene"]  # from . import bodies
    assert "ground.errors" in edges["ground.gate"]  # from .errors import ...
    assert "runner.options" in edges["runner.impact"]
    assert "ground.launch" in edges["runner.impact"]  # from ground.launch import ...
    assert {"runner.impact", "runner.options"} <= edges["bench.validation"]


def test_cycles_are_found():
    """A circle planted in the graph is found (the algorithm can fail)."""
    edges = graph()
    assert "ground.paths" in edges["ground.provenance"]
    planted = {**edges, "ground.paths": edges["ground.paths"] | {"ground.provenance"}}
    assert ["ground.paths", "ground.provenance"] in cycles(planted)


@pytest.mark.parametrize("package", BELOW_RUNNER)
def test_no_import_of_runner_from_below(package):
    assert imports_of(package, "runner") == []


def test_no_import_of_pages_from_analysis():
    """Measurement apart from pages: analysis/ computes numbers, pages/ writes them."""
    assert imports_of("analysis", "pages") == []


@pytest.mark.parametrize("other", sorted(set(packages()) - {"ground"}))
def test_ground_imports_no_other_package(other):
    assert imports_of("ground", other) == []


@pytest.mark.parametrize("package", packages())
def test_no_import_circle(package):
    """No circle through a module of ``package`` (one through two packages
    fails for both)."""
    assert [c for c in cycles(graph()) if any(m.split(".")[0] == package for m in c)] == []


def test_every_subpackage_is_installed():
    """A folder with an __init__.py inside a package is listed in pyproject.toml
    (setuptools installs only the packages it names)."""
    found = {
        module_name(path.parent)
        for package in packages()
        for path in (ROOT / package).rglob("__init__.py")
        if path.parent != ROOT / package
    }
    assert found == set(subpackages())


# The most modules a folder of runner/ or analysis/ holds directly: more, and a
# reader no longer sees from the names how an impact becomes a page (issue 47).
ROOM = 15


@pytest.mark.parametrize("package", ["runner", "analysis"])
def test_rooms_are_small(package):
    rooms = {path.parent for path in (ROOT / package).rglob("*.py")}
    crowded = {
        str(room.relative_to(ROOT)): n
        for room in rooms
        if (n := len(list(room.glob("*.py")))) > ROOM
    }
    assert crowded == {}
