"""The study's figures (MODEL.md section 7), from the means and the fits."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .table import near_the_ends
from .theory import Compliant, compliant_beta, walton_beta

LABELS = {
    "random": "random",
    "triangular": "triangular",
    "square_nu0.1": "square, nu = 0.1",
    "square_nu0.3": "square, nu = 0.3",
}
STYLE = {
    "random": ("C0", "o"),
    "triangular": ("C1", "s"),
    "square_nu0.1": ("C2", "^"),
    "square_nu0.3": ("C3", "v"),
}


def _axes(ylabel: str):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.set_xscale("log")
    ax.set_xlabel("cot gamma")
    ax.set_ylabel(ylabel)
    return fig, ax


def _points(ax, means: list[dict], lattice: str, key: str) -> bool:
    """Means with standard errors; open symbols where the contacts felt the wall's ends."""
    rows = [m for m in means if m["study_lattice"] == lattice]
    if not rows:
        return False
    color, marker = STYLE[lattice]
    for near, label in ((False, LABELS[lattice]), (True, "_nolegend_")):
        part = [m for m in rows if near_the_ends(m) == near]
        if part:
            ax.errorbar(
                [m["cot_gamma"] for m in part],
                [m[key] for m in part],
                yerr=[m[f"{key}_se"] for m in part],
                fmt=marker,
                color=color,
                ms=4,
                capsize=2,
                label=label,
                mfc="none" if near else color,
            )
            ax.open_symbols = getattr(ax, "open_symbols", False) or near
    return True


def _curve_grid(means: list[dict], lattice: str):
    """A fine grid of cot gamma and e interpolated on it (log cot gamma)."""
    rows = sorted((m for m in means if m["study_lattice"] == lattice), key=lambda m: m["cot_gamma"])
    psi = np.array([m["cot_gamma"] for m in rows])
    e = np.array([m["e"] for m in rows])
    grid = np.geomspace(psi.min(), psi.max(), 200)
    return grid, np.interp(np.log(grid), np.log(psi), e)


def _walton(ax, means, fits, lattice, fits_clear=None):
    """Walton's fit over all angles, and dashed over the angles clear of the wall's ends."""
    grid, e = _curve_grid(means, lattice)
    for source, style, note in ((fits, "-", ""), (fits_clear or {}, "--", " (clear of the ends)")):
        fit = source.get(lattice, {}).get("walton")
        if fit:
            ax.plot(
                grid,
                walton_beta(grid, e, fit["mu"], fit["beta0"], fit["K"]),
                color=STYLE[lattice][0],
                lw=1,
                ls=style,
                label=f"Walton{note}, mu = {fit['mu']:.3f}, beta0 = {fit['beta0']:.3f}",
            )


def _finish(fig, ax, path: Path, empty: str) -> Path:
    if ax.has_data():
        note = (
            "open symbols: contacts near the wall's ends"
            if getattr(ax, "open_symbols", False)
            else None
        )
        ax.legend(fontsize=7, title=note, title_fontsize=7)
    else:
        ax.text(0.5, 0.5, empty, transform=ax.transAxes, ha="center")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return path


def draw(means: list[dict], fits: dict, folder: Path, fits_clear: dict | None = None) -> list[Path]:
    """The four figures of a study, as PNG files in ``folder``.

    Parameters
    ----------
    means : list of dict
        Means per lattice and angle (``analysis.table.mean_rows``).
    fits : dict
        Fits per lattice (``analysis.report.fit_all``).
    folder : pathlib.Path
        Where the figures go; created if missing.
    fits_clear : dict, optional
        Walton's fits over the angles whose contacts stayed clear of the wall's
        ends, drawn dashed beside the all-angle fits.

    Returns
    -------
    list of pathlib.Path
        beta_random_triangular.png, e.png, beta_compliant.png, beta_square.png.
    """
    folder.mkdir(parents=True, exist_ok=True)
    paths = []

    fig, ax = _axes("beta")
    for lattice in ("random", "triangular"):
        if _points(ax, means, lattice, "beta"):
            _walton(ax, means, fits, lattice, fits_clear)
    paths.append(
        _finish(fig, ax, folder / "beta_random_triangular.png", "no random or triangular data")
    )

    fig, ax = _axes("e")
    for lattice in LABELS:
        _points(ax, means, lattice, "e")
    paths.append(_finish(fig, ax, folder / "e.png", "no data"))

    fig, ax = _axes("beta")
    if _points(ax, means, "random", "beta"):
        _walton(ax, means, fits, "random", fits_clear)
        fit = fits.get("random", {}).get("compliant")
        if fit:
            grid, e = _curve_grid(means, "random")
            curve = [
                compliant_beta(p, Compliant(e=ei, mu=fit["mu"], nu=fit["nu"], alpha=fit["alpha"]))
                for p, ei in zip(grid, e)
            ]
            ax.plot(
                grid,
                curve,
                color="k",
                lw=1.2,
                label=f"compliant model, mu = {fit['mu']:.3f} (nu = {fit['nu']:.3f})",
            )
    paths.append(_finish(fig, ax, folder / "beta_compliant.png", "no random-lattice data"))

    fig, ax = _axes("beta")
    for lattice in ("square_nu0.1", "square_nu0.3"):
        if _points(ax, means, lattice, "beta"):
            _walton(ax, means, fits, lattice, fits_clear)
    paths.append(
        _finish(fig, ax, folder / "beta_square.png", "no square-lattice data in this study")
    )
    return paths
