"""Every number of a study with its error from whole seeds: the means per
angle, both fits of both theories, the fits' spread over fitting choices, the
model-free measures and the comparison of the two square lattices.

docs/model.md section 6 asks for two fits of each theory:

- **the paper's way**: Walton with e fixed at 0.8 and K = 3, the compliant
  model with eta = 1.015, alpha = 3.02 and e = 0.8 (mu free), both by
  unweighted least squares on the per-angle means;
- **the measured way**: e the measured mean at each angle, K = 1 + MR^2/I and
  nu of the lattice as measured, each angle weighted by the standard error
  of its mean of beta (sd / sqrt(n) of its impacts).

Errors: the standard deviation over resamples of whole seeds
(``analysis.statistics.seeds``), every number recomputed on every resample, the
sliding branch and the angle sets fixed from all the data. Reduced chi^2:
the residuals of the fit to all the data over the seed-bootstrap errors of
the per-angle means. Systematic error of a fit: half the range of its
parameters over eight fitting choices (e 0.8 and the paper's K, eta, alpha
or the measured e, K, nu; weights by standard error or none; all angles or
only those whose contacts stayed clear of the wall's ends).
"""

from __future__ import annotations

import itertools

import numpy as np

from builder.study_names import FIT_ANGLES, FIT_SEEDS
from ground.digits import half_range

from ..table import NEAR_SIDE, NEAR_SIDE_SHARE, held
from ..theory.tangential import nu_for_eta, walton_beta
from .fits import Means, compliant_curve, fit_compliant, fit_walton, means, reduced_chi2
from .measures import measures
from .seeds import QUANTITIES, RNG_SEED, SeedTable, seed_bootstrap, seed_errors, seed_tables
from .sliding import BRANCH_P, sliding_branch

# The paper's fits (docs/model.md sections 6 and 8).
PAPER = {"e": 0.8, "K": 3.0, "eta": 1.015, "alpha": 3.02}
# A fit whose reduced chi^2 is above this does not describe the data.
CHI2_LIMIT = 2.0
# Where the reduced chi^2 is above CHI2_LIMIT, the page adds the systematic error.
PARAMETERS = {"walton": ("mu", "beta0"), "compliant": ("mu",)}


def way(theory: str, name: str, K: float, nu: float) -> dict:
    """The fixed inputs and the weighting of one way of fitting one theory."""
    if name == "paper":
        if theory == "walton":
            return {"e": PAPER["e"], "K": PAPER["K"], "weighted": False}
        return {
            "e": PAPER["e"],
            "nu": nu_for_eta(PAPER["eta"]),
            "alpha": PAPER["alpha"],
            "weighted": False,
        }
    if theory == "walton":
        return {"e": None, "K": K, "weighted": True}
    return {"e": None, "nu": nu, "alpha": K, "weighted": True}


def fit(theory: str, data: Means, inputs: dict, start=None) -> np.ndarray:
    """One fit of ``theory`` with the inputs of ``way``."""
    if theory == "walton":
        return fit_walton(data, inputs["K"], inputs["e"], inputs["weighted"])
    return fit_compliant(
        data, inputs["nu"], inputs["alpha"], inputs["e"], inputs["weighted"], start=start
    )


def curve(theory: str, data: Means, parameters, inputs: dict) -> np.ndarray:
    """The fitted model's beta at the angles of ``data``."""
    if theory == "walton":
        e = data.e if inputs["e"] is None else inputs["e"]
        return walton_beta(data.psi, e, parameters[0], parameters[1], inputs["K"])
    return compliant_curve(data, parameters[0], inputs["nu"], inputs["alpha"], inputs["e"])


def two_body_k(row: dict) -> float:
    """Walton's K of a binary impact (docs/model.md, section 6), from both
    disks' masses M (their points) and I = (I / M R^2) M R^2:
    K = (1/M_A + 1/M_B + R^2/I_A + R^2/I_B) / (1/M_A + 1/M_B)."""
    m_a, m_b = float(row["n_disk_points"]), float(row["n_target_points"])
    if held(row):  # infinite mass and inertia
        return 1.0 + 1.0 / float(row["disk_inertia_ratio"])
    r_a, r_b = float(row["disk_inertia_ratio"]), float(row["target_inertia_ratio"])
    return 1.0 + (1.0 / (r_a * m_a) + 1.0 / (r_b * m_b)) / (1.0 / m_a + 1.0 / m_b)


def lattice_constants(rows: list[dict], lattice: str) -> tuple[float, float, float]:
    """(nu, I/(MR^2), K) of a lattice: the calibration's nu, the mean measured
    inertia, and K = 1 + MR^2/I on the wall or, between two disks, the mean
    of each pair's two-body K."""
    mine = [r for r in rows if r["study_lattice"] == lattice]
    inertia = float(np.mean([float(r["disk_inertia_ratio"]) for r in mine]))
    if all(r.get("target") == "disk" for r in mine):
        return float(mine[0]["nu"]), inertia, float(np.mean([two_body_k(r) for r in mine]))
    return float(mine[0]["nu"]), inertia, 1.0 + 1.0 / inertia


def clear_angles(table: SeedTable) -> np.ndarray:
    """The angles where at most NEAR_SIDE_SHARE of the contacts came within
    NEAR_SIDE of a fixed side of the wall (``table.near_the_ends``)."""
    clearance = table.values["side_clearance"]
    near = np.sum(np.isfinite(clearance) & (clearance < NEAR_SIDE), axis=0)
    return near <= NEAR_SIDE_SHARE * table.counts()


def square_pair(lattices: dict) -> tuple[str, str] | None:
    """The study's two square lattices, lower nu first, if it has exactly two."""
    squares = sorted((v["nu"], k) for k, v in lattices.items() if k.startswith("square"))
    return (squares[0][1], squares[1][1]) if len(squares) == 2 else None


class Study:
    """The fixed inputs of a study's estimates: per lattice its constants,
    the theories to fit, and (after the fit to all the data) the sliding
    branch and the fits that the resamples start from."""

    def __init__(self, rows: list[dict], compliant: bool = True):
        self.tables = seed_tables(rows)
        self.lattices = {}
        for lattice, table in self.tables.items():
            if np.sum(table.counts() >= FIT_SEEDS) < FIT_ANGLES:
                continue  # too few angles to fit
            nu, inertia, K = lattice_constants(rows, lattice)
            self.lattices[lattice] = {
                "nu": nu,
                "inertia_ratio": inertia,
                "K": K,
                "theories": ("walton", "compliant") if compliant else ("walton",),
            }
        self.pair = square_pair(self.lattices)
        self.starts: dict = {}
        self.branches: dict = {}

    def statistic(self, tables: dict[str, SeedTable]) -> dict:
        """Every number of the study from (resampled) tables, by key."""
        out = {}
        for lattice, table in tables.items():
            for q in QUANTITIES:
                out[(lattice, "mean", q)] = table.mean(q)
        for lattice, info in self.lattices.items():
            table = tables[lattice]
            data = means(table)
            for theory in info["theories"]:
                for name in ("paper", "measured"):
                    inputs = way(theory, name, info["K"], info["nu"])
                    start = self.starts.get((lattice, theory, name))
                    out[(lattice, theory, name)] = fit(theory, data, inputs, start)
            for key, value in measures(table, info["K"], self.branches[lattice][0]).items():
                out[(lattice, "measure", key)] = value
        if self.pair:
            low, high = self.pair
            common = np.intersect1d(tables[low].gamma_deg, tables[high].gamma_deg)
            a = np.isin(tables[low].gamma_deg, common)
            b = np.isin(tables[high].gamma_deg, common)
            out[("pair", "beta")] = out[(high, "mean", "beta")][b] - out[(low, "mean", "beta")][a]
            for name in ("paper", "measured"):
                out[("pair", "beta0", name)] = (
                    out[(high, "walton", name)][1] - out[(low, "walton", name)][1]
                )
            out[("pair", "beta_normal")] = (
                out[(high, "measure", "beta_normal")] - out[(low, "measure", "beta_normal")]
            )
        return out

    def prepare(self) -> None:
        """The sliding branches, read from all the data (``sliding``)."""
        for lattice, info in self.lattices.items():
            self.branches[lattice] = sliding_branch(self.tables[lattice], info["K"])


def variants(
    theory: str, table: SeedTable, info: dict, sd_beta: np.ndarray, headline: dict
) -> list[dict]:
    """The fit over the eight fitting choices, each with its reduced chi^2;
    ``headline``: the two ways' fits to all the data (way name -> parameters),
    which are two of the eight."""
    keep = table.counts() > 1
    clear = clear_angles(table)[keep]
    data = means(table)
    out = []
    for name, weighted, angles in itertools.product(
        ("paper", "measured"), (False, True), ("all", "clear")
    ):
        inputs = dict(way(theory, name, info["K"], info["nu"]), weighted=weighted)
        chosen = np.ones_like(clear) if angles == "all" else clear
        if chosen.sum() < len(PARAMETERS[theory]) + 1:
            continue
        subset = data.select(chosen)
        if angles == "all" and weighted == way(theory, name, 1.0, 0.0)["weighted"]:
            parameters = headline[name]
        else:
            parameters = fit(theory, subset, inputs)
        model = curve(theory, subset, parameters, inputs)
        out.append(
            {
                "e": "0.8" if name == "paper" else "per angle",
                "constants": "the paper's" if name == "paper" else "measured",
                "weights": "se" if weighted else "none",
                "angles": angles,
                "n_angles": int(chosen.sum()),
                **dict(zip(PARAMETERS[theory], map(float, parameters))),
                "chi2": reduced_chi2(subset, model, len(PARAMETERS[theory]), sd_beta[keep][chosen]),
            }
        )
    return out


def neighbour_correlation(table: SeedTable) -> float:
    """The mean over pairs of neighbouring angles of the correlation of beta
    between them over the seeds that have both: why whole seeds are resampled."""
    beta = table.values["beta"]
    values = []
    for j in range(beta.shape[1] - 1):
        both = np.isfinite(beta[:, j]) & np.isfinite(beta[:, j + 1])
        if both.sum() > 2 and np.std(beta[both, j]) > 0 and np.std(beta[both, j + 1]) > 0:
            values.append(np.corrcoef(beta[both, j], beta[both, j + 1])[0, 1])
    return float(np.mean(values)) if values else np.nan


def systematic(fits: list[dict], parameters) -> dict:
    """Half the range of each parameter over the fitting choices, of the
    numbers as written (exactly 0 where the choices agree)."""
    return {p: half_range(f[p] for f in fits) for p in parameters}


def study_estimates(
    rows: list[dict], resamples: int = 200, compliant: bool = True, by_seed_count: bool = False
):
    """Every number of a study with its seed-bootstrap error.

    Parameters
    ----------
    rows : list of dict
        One row per impact (impacts.csv; numbers may be strings).
    resamples : int
        Seed-bootstrap resamples.
    compliant : bool
        Fit the compliant model too (slower: a few seconds per lattice and way
        for the fit to all the data, and a tenth of a second per resample).
    by_seed_count : bool
        The errors by the method the seed count calls for
        (``analysis.statistics.seeds.seed_errors``: the jackknife below 16 seeds)
        instead of the bootstrap at any count.

    Returns
    -------
    fits : dict
        What fits.json holds (plain floats, lists and strings): ``errors``,
        ``paper`` (the paper's fixed inputs), ``lattices`` (per lattice: nu,
        inertia, K, both fits of each theory with their errors and reduced
        chi^2, the variants and the systematic error, the model-free measures
        and the sliding branch) and, with two square lattices, ``pair``.
    mean_sd : dict
        (lattice, gamma_deg) -> {quantity + "_seed_sd": the seed-bootstrap
        error of its mean} for means.csv.
    """
    study = Study(rows, compliant)
    study.prepare()
    best = study.statistic(study.tables)
    for lattice, info in study.lattices.items():
        for theory in info["theories"]:
            for name in ("paper", "measured"):
                if theory == "compliant":
                    study.starts[(lattice, theory, name)] = float(best[(lattice, theory, name)][0])
    errors = {
        "kind": f"sd over {resamples} seed-bootstrap resamples",
        "resamples": resamples,
        "rng_seed": RNG_SEED,
        "unit": "whole seeds: a resample draws the study's seeds with replacement and takes "
        "each drawn seed's impacts at every angle of every lattice together",
    }
    if by_seed_count and study.tables:
        sd, chosen = seed_errors(study.tables, study.statistic, resamples)
        errors.update(chosen)
    else:
        sd = seed_bootstrap(study.tables, study.statistic, resamples) if study.tables else {}
    fits = {
        "errors": errors,
        "paper": dict(PAPER, nu_of_eta=nu_for_eta(PAPER["eta"])),
        "chi2_limit": CHI2_LIMIT,
        "lattices": {},
    }
    mean_sd = {
        (lattice, float(gamma)): {
            f"{q}_seed_sd": float(sd[(lattice, "mean", q)][j]) for q in QUANTITIES
        }
        for lattice, table in study.tables.items()
        for j, gamma in enumerate(table.gamma_deg)
    }
    for lattice, info in study.lattices.items():
        table = study.tables[lattice]
        keep = table.counts() > 1
        data = means(table)
        sd_beta = sd[(lattice, "mean", "beta")]
        entry = {
            "nu": info["nu"],
            "inertia_ratio": info["inertia_ratio"],
            "K": info["K"],
            "angles": int(keep.sum()),
            "seeds": int(np.max(table.counts())),
            "clear_angles": [float(g) for g in table.gamma_deg[clear_angles(table)]],
            "beta_neighbour_correlation": neighbour_correlation(table),
        }
        for theory in info["theories"]:
            entry[theory] = {}
            for name in ("paper", "measured"):
                inputs = way(theory, name, info["K"], info["nu"])
                parameters = best[(lattice, theory, name)]
                model = curve(theory, data, parameters, inputs)
                entry[theory][name] = {
                    **{k: v for k, v in inputs.items() if k != "weighted"},
                    "e": "per angle" if inputs["e"] is None else inputs["e"],
                    "weights": "se" if inputs["weighted"] else "none",
                    **{p: float(parameters[i]) for i, p in enumerate(PARAMETERS[theory])},
                    **{
                        f"{p}_sd": float(sd[(lattice, theory, name)][i])
                        for i, p in enumerate(PARAMETERS[theory])
                    },
                    "chi2": reduced_chi2(data, model, len(PARAMETERS[theory]), sd_beta[keep]),
                }
            entry[theory]["variants"] = variants(
                theory,
                table,
                info,
                sd_beta,
                {name: best[(lattice, theory, name)] for name in ("paper", "measured")},
            )
            entry[theory]["systematic"] = systematic(entry[theory]["variants"], PARAMETERS[theory])
        branch, p_branch = study.branches[lattice]
        entry["sliding_branch"] = {
            "rule": "the longest run of the most grazing angles whose mu_eff one constant "
            f"describes (p >= {BRANCH_P}, Hotelling's T^2 on each seed's differences)",
            "p": p_branch,
            "gamma_deg": [float(g) for g in table.gamma_deg[branch]],
        }
        entry["measures"] = {}
        for key in ("e_normal", "e_grazing", "beta_normal", "mu_branch"):
            entry["measures"][key] = _pair(best, sd, (lattice, "measure", key))
        entry["measures"]["share_beta_positive"] = _pair(
            best, sd, (lattice, "measure", "share_beta_positive")
        )
        entry["measures"]["share_near_side"] = _pair(
            best, sd, (lattice, "measure", "share_near_side")
        )
        entry["measures"]["mu_eff"] = {
            "gamma_deg": table.gamma_deg.tolist(),
            "cot_gamma": best[(lattice, "mean", "cot_gamma")].tolist(),
            "value": best[(lattice, "measure", "mu_eff")].tolist(),
            "sd": sd[(lattice, "measure", "mu_eff")].tolist(),
            "sliding": branch.tolist(),
        }
        fits["lattices"][lattice] = entry
    if study.pair:
        fits["pair"] = pair_entry(study, best, sd, fits["lattices"])
    return _plain(fits), mean_sd


def pair_entry(study: Study, best: dict, sd: dict, lattices: dict) -> dict:
    """The two square lattices compared: beta angle by angle, beta0 and beta near normal."""
    low, high = study.pair
    common = np.intersect1d(study.tables[low].gamma_deg, study.tables[high].gamma_deg)
    entry = {
        "lower_nu": low,
        "higher_nu": high,
        "gamma_deg": common.tolist(),
        "beta_difference": _pair(best, sd, ("pair", "beta")),
        "beta_normal_difference": _pair(best, sd, ("pair", "beta_normal")),
    }
    for name in ("paper", "measured"):
        difference = _pair(best, sd, ("pair", "beta0", name))
        # the spread of the difference over the fitting choices (the same choices on both)
        shifts = [
            b["beta0"] - a["beta0"]
            for a, b in zip(
                lattices[low]["walton"]["variants"], lattices[high]["walton"]["variants"]
            )
            if (a["e"], a["weights"], a["angles"]) == (b["e"], b["weights"], b["angles"])
        ]
        difference["systematic"] = half_range(shifts)
        entry[f"beta0_difference_{name}"] = difference
    return entry


def _pair(best: dict, sd: dict, key) -> dict:
    return {"value": best[key], "sd": sd.get(key, np.nan)}


def _plain(value):
    """numpy numbers and arrays as JSON's floats and lists (NaN as None)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if np.isfinite(value) else None
    return value
