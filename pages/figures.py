"""The study's figures (docs/model.md section 7), from the means and the fits."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.table import near_the_ends
from analysis.theory.tangential import Compliant, compliant_beta, walton_beta
from ground.gate import write_figure

LABELS = {
    "random": "random",
    "triangular": "triangular",
    "square_nu0.1": "square, nu = 0.1",
    "square_nu0.3": "square, nu = 0.3",
}
WAYS = {"measured": "measured way", "paper": "paper's way"}
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
                yerr=[m.get(f"{key}_seed_sd", np.nan) for m in part],
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


def _walton(ax, means, fits, lattice):
    """Walton's fits: the measured way (e interpolated between the angles, the
    lattice's K) solid, the paper's way (e 0.8, K 3) dashed."""
    grid, e = _curve_grid(means, lattice)
    fit = fits["lattices"].get(lattice, {}).get("walton")
    if not fit:
        return
    for name, style in (("measured", "-"), ("paper", "--")):
        f = fit[name]
        ax.plot(
            grid,
            walton_beta(grid, e if f["e"] == "per angle" else f["e"], f["mu"], f["beta0"], f["K"]),
            color=STYLE[lattice][0],
            lw=1,
            ls=style,
            label=f"Walton, {WAYS[name]}: mu = {f['mu']:.3f}, beta0 = {f['beta0']:.3f}",
        )


def _compliant(ax, means, fits, lattice):
    """The compliant model's fits, measured way solid, paper's way dashed."""
    fit = fits["lattices"].get(lattice, {}).get("compliant")
    if not fit:
        return
    grid, e = _curve_grid(means, lattice)
    for name, style in (("measured", "-"), ("paper", "--")):
        f = fit[name]
        es = e if f["e"] == "per angle" else np.full_like(grid, f["e"])
        curve = [
            compliant_beta(p, Compliant(e=ei, mu=f["mu"], nu=f["nu"], alpha=f["alpha"]))
            for p, ei in zip(grid, es)
        ]
        ax.plot(
            grid,
            curve,
            color="k",
            lw=1.2,
            ls=style,
            label=f"compliant, {WAYS[name]}: mu = {f['mu']:.3f} (nu = {f['nu']:.3f}, "
            f"alpha = {f['alpha']:.2f})",
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
    write_figure(fig, path, 110)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return path


def draw(means: list[dict], fits: dict, folder: Path) -> list[Path]:
    """The figures of a study, as PNG files in ``folder``.

    Parameters
    ----------
    means : list of dict
        Means per lattice and angle with their errors (means.csv's rows).
    fits : dict
        The study's estimates (fits.json, ``analysis.statistics.estimates.study_estimates``).
    folder : pathlib.Path
        Where the figures go; created if missing.

    Returns
    -------
    list of pathlib.Path
        beta_random_triangular.png, e.png, beta_compliant.png, beta_square.png,
        mu_eff.png.
    """
    folder.mkdir(parents=True, exist_ok=True)
    paths = []

    fig, ax = _axes("beta")
    for lattice in ("random", "triangular"):
        if _points(ax, means, lattice, "beta"):
            _walton(ax, means, fits, lattice)
    paths.append(
        _finish(fig, ax, folder / "beta_random_triangular.png", "no random or triangular data")
    )

    fig, ax = _axes("e")
    for lattice in LABELS:
        _points(ax, means, lattice, "e")
    paths.append(_finish(fig, ax, folder / "e.png", "no data"))

    fig, ax = _axes("beta")
    if _points(ax, means, "random", "beta"):
        _compliant(ax, means, fits, "random")
    paths.append(_finish(fig, ax, folder / "beta_compliant.png", "no random-lattice data"))

    fig, ax = _axes("beta")
    for lattice in LABELS:
        if lattice.startswith("square") and _points(ax, means, lattice, "beta"):
            _walton(ax, means, fits, lattice)
    paths.append(
        _finish(fig, ax, folder / "beta_square.png", "no square-lattice data in this study")
    )

    fig, ax = _axes("mu_eff = (1 + beta) / ((1 + e) K cot gamma)")
    for lattice, entry in fits["lattices"].items():
        mu = entry["measures"]["mu_eff"]
        color, marker = STYLE.get(lattice, ("k", "o"))
        sd = [s if s is not None else np.nan for s in mu["sd"]]
        ax.errorbar(
            mu["cot_gamma"],
            mu["value"],
            yerr=sd,
            fmt=marker + "-",
            color=color,
            mfc="none",
            ms=4,
            lw=0.8,
            capsize=2,
            label=LABELS.get(lattice, lattice),
        )
        on = [j for j, sliding in enumerate(mu["sliding"]) if sliding]
        ax.plot(
            [mu["cot_gamma"][j] for j in on],
            [mu["value"][j] for j in on],
            marker,
            color=color,
            ms=4,
        )  # filled: on the sliding branch
    if ax.has_data():
        ax.axhline(0.18, color="0.5", lw=0.8, ls=":", label="the paper's mu, 0.18")
    paths.append(_finish(fig, ax, folder / "mu_eff.png", "no lattice to fit in this study"))
    return paths
