"""The one gate every file and folder the tool writes or deletes passes.

``gate(path)`` resolves the real path once (``~``, ``..`` and every symbolic
link, also of the parts that do not exist yet) and refuses the project's
root, its committed record (docs/, studies/) and its code and build
(ground.paths.PROTECTED), but for what a command was granted after its own
checks (``grant``: a study's page in docs/, owned by exactly one committed
study file; the sampler's cache in build/poisson/). ``make_folder``,
``write_text`` and ``remove`` write or delete through it; ``remove`` never
deletes through a link (it removes the link itself). ``environment_paths``
checks every IMPACT_* path of the environment before any work.

Nothing here imports another package of the project.
"""

from __future__ import annotations

import json
import os
import shutil
import stat
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from .digits import rounded
from .errors import InputError
from .paths import BUILD, PROTECTED, ROOT
from .words import portable_problem, word_problem

# What the project itself writes inside its protected folders without being
# asked: the Poisson samples' cache (builder.sample_cache) and the contact's
# tables (builder.contact_table), which make setup starts.
ALWAYS_GRANTED = (BUILD / "poisson", BUILD / "tables")
# The environment's paths the tool writes into (runs, the sampler's cache).
ENVIRONMENT_PATHS = ("IMPACT_RUNS", "IMPACT_POISSON_CACHE")
_granted: set[Path] = set()


def expanded(path: Path | str) -> Path:
    """``path`` with ``~`` expanded: what the check and the write both use."""
    return Path(os.path.expanduser(os.fspath(path)))


def real(path: Path | str) -> Path:
    """Where ``path`` really is: ``~``, ``..`` and every link resolved."""
    return expanded(path).resolve()


def grant(*paths: Path | str) -> None:
    """Let this process write ``paths`` (files or folders, and what is under
    them) although they lie in the project's protected folders; called by a
    command once it has checked that they are its own (a study's page)."""
    _granted.update(real(p) for p in paths)


def granted(where: Path) -> bool:
    return any(where == g or where.is_relative_to(g) for g in (*_granted, *ALWAYS_GRANTED))


def problem(path: Path | str) -> str | None:
    """Why the tool may not write or delete ``path``, or None."""
    where = real(path)
    if granted(where):
        return None
    if where == ROOT:
        return "is the project's root; give a folder of its own (runs/<name>)"
    for name in PROTECTED:
        folder = (ROOT / name).resolve()
        if where == folder or where.is_relative_to(folder):
            shown = "" if where == expanded(path).absolute() else f" (it leads to {where})"
            what = "the committed record" if name in ("docs", "studies") else "the project's own"
            hint = "; only --docs writes a study's own page there" if name == "docs" else ""
            return f"is inside {name}/, {what}{shown}{hint}"
    return None


def gate(path: Path | str, what: str = "") -> Path:
    """``path`` (``~`` expanded) if the tool may write or delete it, else
    InputError naming ``what`` (an option) and the path."""
    if reason := problem(path):
        raise InputError(f"{what + ': ' if what else ''}{path} {reason}")
    return expanded(path)


def make_folder(path: Path | str, what: str = "") -> Path:
    """The folder at ``path``, made with its parents, through the gate."""
    folder = gate(path, what)
    if folder.is_symlink() and not folder.exists():
        raise InputError(
            f"{what + ': ' if what else ''}{folder} is a link to {os.readlink(folder)}, which "
            "does not exist: remove the link, or make the folder it names"
        )
    folder.mkdir(parents=True, exist_ok=True)
    return folder


@contextmanager
def atomic(path: Path | str, what: str = "") -> Iterator[Path]:
    """A temporary file beside ``path`` (through the gate) for the block to
    write; renamed over ``path`` when the block ends, removed if it fails
    or is interrupted. A cut or interrupted write leaves the old file whole,
    and an error of the disk names the file it was writing."""
    gate(path, what)
    # the file the path leads to (a link is written through, as the gate
    # checked it), replaced with the old file's permissions
    target = real(path)
    temporary = target.with_name(f".{target.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    try:
        yield temporary
        if target.exists():
            os.chmod(temporary, stat.S_IMODE(target.stat().st_mode))
        os.replace(temporary, target)
    except BaseException as error:
        temporary.unlink(missing_ok=True)
        if isinstance(error, OSError):  # a full disk's error names no file: this one
            if error.filename in (None, str(temporary)):
                error.filename = str(path)
        raise


def write_text(path: Path | str, text: str, what: str = "") -> Path:
    """``text`` written to ``path`` through the gate (a link's target is
    checked where it leads), whole or not at all (``atomic``)."""
    with atomic(path, what) as temporary:
        temporary.write_text(text)
    return expanded(path)


def write_json(path: Path | str, data, what: str = "", **options) -> Path:
    """``data`` as JSON (indent 1, a newline at the end), every float to
    the tables' digits (ground.digits), through ``write_text``."""
    return write_text(path, json.dumps(rounded(data), indent=1, **options) + "\n", what)


def copy_file(source: Path | str, path: Path | str, what: str = "") -> Path:
    """``source``'s bytes written to ``path`` through ``atomic``."""
    with atomic(path, what) as temporary:
        shutil.copyfile(source, temporary)
    return expanded(path)


def write_figure(figure, path: Path | str, dpi: int, what: str = "") -> Path:
    """A matplotlib figure as PNG at ``path`` through the gate, whole or not
    at all, with no metadata that names the software or the time: the same
    bytes wherever the same numbers are drawn."""
    with atomic(path, what) as temporary:
        figure.savefig(temporary, format="png", dpi=dpi, metadata={"Software": None})
    return expanded(path)


def remove(path: Path | str, what: str = "") -> None:
    """Delete ``path``: a link itself (never what it leads to), a file, or a
    folder with everything in it (links in it removed, not followed)."""
    path = expanded(path)
    if path.is_symlink():
        gate(path.parent, what)  # the link lives in its parent
        path.unlink()
        return
    gate(path, what)
    if path.is_dir():
        shutil.rmtree(path)
    elif path.exists():
        path.unlink()


def environment_paths(environ: os._Environ | dict | None = None) -> None:
    """Refuse, before any work, an IMPACT_* path of the environment that leads
    where the tool may not write (one line naming the variable)."""
    environ = os.environ if environ is None else environ
    for name in ENVIRONMENT_PATHS:
        value = environ.get(name, "")
        if not value or (name == "IMPACT_POISSON_CACHE" and value == "off"):
            continue
        gate(value, name)
        if expanded(value).exists() and not expanded(value).is_dir():  # a folder, or none yet
            raise InputError(f"{name}: {value} is a file, not a folder")
        if name == "IMPACT_RUNS":  # its path goes into every impact's LAMMPS deck
            path = str(expanded(value).absolute())
            if reason := word_problem(path) or portable_problem(path):
                raise InputError(f"IMPACT_RUNS: {value} {reason}")


def protected_problem(path: Path | str) -> str | None:
    """Why a command may not write into ``path``, or None (ground.gate, the
    one gate every write passes: ``~``, ``..`` and links resolved first)."""
    return problem(path)


def runs_folder() -> Path:
    """Where studies and runs go: runs/ in the clone, or $IMPACT_RUNS (a
    cluster's scratch space; the tests' temporary folder).

    Raises
    ------
    ground.errors.InputError
        If $IMPACT_RUNS points into the project's record or code.
    """
    setting = os.environ.get("IMPACT_RUNS")
    return gate(setting, "IMPACT_RUNS") if setting else ROOT / "runs"
