"""A disk cache of Poisson-disk samples, which are most of a scene's build time.

scipy's sampler is pure Python: about 2 s for the default wall and 0.4 s for
a random disk, against about 0.5 s for the whole LAMMPS run of an impact. A
study builds every seed's bodies once, but the next study on the same seeds
(another reading, another speed, the same study from scratch) draws the same
samples again. A draw depends only on the generator's state, the sampler's
arguments and the versions of scipy and numpy, so that is the key; a hit
returns the same points and leaves the generator in the state the draw would
have left, so the scene's later draws (and its data file, byte for byte) do
not change.

The cache lives in build/poisson/, or in $IMPACT_POISSON_CACHE; "off" turns
it off. A file that cannot be read is drawn again and replaced.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np
import scipy

from ground.gate import gate
from ground.paths import BUILD

DEFAULT_FOLDER = BUILD / "poisson"


def cache_folder() -> Path | None:
    """Where samples are kept, or None if the cache is off."""
    setting = os.environ.get("IMPACT_POISSON_CACHE", "")
    if setting == "off":
        return None
    # through the one gate of every write (ground.gate): ~ expanded, and
    # never into the project's record or code
    return gate(setting, "IMPACT_POISSON_CACHE") if setting else DEFAULT_FOLDER


def sample_key(rng: np.random.Generator, arguments: dict) -> str:
    """The hash of everything a draw from ``rng`` with ``arguments`` depends on."""
    what = {
        "state": rng.bit_generator.state,
        "arguments": arguments,
        "scipy": scipy.__version__,
        "numpy": np.__version__,
    }
    return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()


def cached_draw(
    rng: np.random.Generator, arguments: dict, draw: Callable[[], np.ndarray]
) -> np.ndarray:
    """``draw()``'s points, from the cache if it holds them for this state of
    ``rng`` and these ``arguments`` (JSON numbers and lists)."""
    folder = cache_folder()
    if folder is None:
        return draw()
    path = folder / f"{sample_key(rng, arguments)}.npz"
    try:
        with np.load(path) as stored:
            points = stored["points"]
            state = json.loads(str(stored["state"]))
        rng.bit_generator.state = state
        return points
    except (OSError, KeyError, ValueError):  # missing or unreadable: draw it
        pass
    points = draw()
    temporary = None
    try:
        folder.mkdir(parents=True, exist_ok=True)
        # written whole under another name, then renamed: two workers drawing
        # the same sample never leave half a file
        with tempfile.NamedTemporaryFile(dir=folder, suffix=".npz", delete=False) as handle:
            temporary = Path(handle.name)
            np.savez(handle, points=points, state=json.dumps(rng.bit_generator.state))
        temporary.replace(path)
    except OSError:  # a read-only clone still builds, only slower
        if temporary is not None:
            temporary.unlink(missing_ok=True)
    return points
