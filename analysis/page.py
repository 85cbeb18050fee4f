"""The results page's sections on the fits, the model-free measures, the
paper's claims and the Poisson-ratio question, from ``study_estimates``'s
fits (fits.json)."""

from __future__ import annotations

import math

import numpy as np

from .claims import RULE_NEAR, RULE_SAME, claims
from .measures import BETA_NORMAL_PSI, E_NORMAL_PSI, GRAZING_ANGLES
from .table import NEAR_SIDE, NEAR_SIDE_SHARE

THEORIES = {"walton": "Walton", "compliant": "compliant"}
WAYS = {"paper": "the paper's way", "measured": "the measured way"}


def pm(value, sd=None, digits: int = 3) -> str:
    """value +- sd, or '-' without a value."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if sd is None or not math.isfinite(sd):
        return f"{value:.{digits}f}"
    return f"{value:.{digits}f} +- {sd:.{digits}f}"


def statistics_section(fits: dict) -> list[str]:
    """What every error on the page is."""
    errors = fits["errors"]
    return [
        "## What the errors are",
        "",
        f"Every +- on this page, in `means.csv` (columns `*_seed_sd`) and in `fits.json` "
        f"(`*_sd`) is an {errors['kind']} (the standard deviation over the resamples): a "
        "resample draws the study's seeds with replacement and takes each "
        "drawn seed's impacts at every angle of every lattice together, since one seed's "
        "disk and wall serve all its angles and, on a common wall, every lattice's wall "
        f"(beta correlates {_correlations(fits)} on average over the seeds between "
        "neighbouring angles). Every number (a mean, a fitted "
        "parameter, a difference, a measure) is recomputed on every resample; the "
        f"resamples' generator is `numpy.random.default_rng({errors['rng_seed']})`, so the "
        "page is made again with the same errors. For a mean at one angle this is the "
        "standard error of the mean (the impacts of one angle come from distinct seeds); "
        "for anything that combines angles or lattices it is larger than treating them as "
        "independent would give. Where a fit's reduced chi^2 is above "
        f"{fits['chi2_limit']:g}, the model does not describe the data, and its parameters "
        "also get a systematic error: half their range over eight fitting choices (below).",
        "",
    ]


def _correlations(fits: dict) -> str:
    values = {
        k: v["beta_neighbour_correlation"]
        for k, v in fits["lattices"].items()
        if v.get("beta_neighbour_correlation") is not None
    }
    return ", ".join(f"{v:.2f} ({k})" for k, v in values.items()) if values else "-"


def claims_section(fits: dict) -> list[str]:
    """The paper's facts beside the study's numbers, with computed verdicts."""
    lines = [
        "## The paper's claims",
        "",
        "Each fact of docs/model.md section 8 and the paper's conclusions, the project's number "
        "measured by the paper's procedure and model-free (+- the error: the seed "
        "bootstrap's, combined in quadrature with the systematic error where the fit does "
        "not describe the data), and verdicts computed by these rules: "
        f"{RULE_NEAR}; {RULE_SAME}. What counts as near is docs/model.md section 8's unit of each "
        "fact (e 0.1, mu 0.05, beta0 0.2, contacts near a side 10 %; for the share of "
        "angles with beta > 0, which has none there, a tenth).",
        "",
        "| fact | the paper | near | paper's procedure | verdict | model-free | verdict |",
        "|---|---|---|---|---|---|---|",
    ]
    for claim in fits.get("claims") or claims(fits):
        procedure, model_free = claim["procedure"], claim["model_free"]
        near = "the same" if claim["near"] is None else f"{claim['near']:g}"
        lines.append(
            f"| {claim['fact']} | {claim['paper']:g} | {near} "
            f"| {_claim_number(procedure, claim['procedure_is'])} | {claim['procedure_verdict']} "
            f"| {_claim_number(model_free, claim['model_free_is'])} "
            f"| {claim['model_free_verdict']} |"
        )
    return lines + [
        "",
        "These verdicts are this study's reading of the model. Which reading of the model "
        "and the wall reproduces which fact, by how much, and what moves the facts no reading "
        'reproduces: docs/model.md, section 8, "The verdict, fact by fact" '
        "(from `python -m runner page model_readings` and this page).",
        "",
    ]


def _claim_number(number: dict | None, what: str) -> str:
    if number is None:
        # no number by design ("-", "fixed at 0.8"), or the lattice is not in the study
        return what if what == "-" or what.startswith("fixed") else "- (not in this study)"
    return f"{pm(number['value'], number['error'])} ({what})"


NO_FITS = "No lattice of this study has three angles of two impacts or more: nothing to fit."


def fits_section(fits: dict) -> list[str]:
    """Both fits of both theories for every lattice, with errors and reduced chi^2."""
    if not fits["lattices"]:
        return ["## Fits", "", NO_FITS, ""]
    lines = [
        "## Fits",
        "",
        "Two fits of each theory (docs/model.md section 6). **The paper's way**: Walton with e "
        "fixed at 0.8 and K = 3; the compliant model with eta = 1.015 (nu = "
        f"{fits['paper']['nu_of_eta']:.3f} in eta^2 = (2 - nu) / (2 (1 - nu))), alpha = 3.02 "
        "and e = 0.8, mu free; both unweighted least squares on the per-angle means. **The "
        "measured way**: e the measured mean at each angle, K = 1 + MR^2/I from the measured "
        "inertia and nu from the calibration (docs/materials.md); each angle weighted by "
        "the standard error of its mean of beta (sd / sqrt(n) of its impacts, which gives "
        "the grazing angles, whose beta scatters least, most of the weight). chi2/dof: the "
        "squared residuals of the fit to all the data over the seed-bootstrap errors of the "
        "per-angle means of beta, per degree of freedom, whatever weights the fit used: "
        "about 1 if the model describes the means within their errors (the angles are "
        "treated as independent here, which they are not quite).",
        "",
        f"mu and beta0: the value +- its seed error, then +- its systematic error where the "
        f"fit's chi2/dof is above {fits['chi2_limit']:g} (below).",
        "",
        "| lattice | nu | I/(MR^2) | theory | way | e | K or alpha | weights | mu | beta0 "
        "| chi2/dof |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for lattice, entry in fits["lattices"].items():
        for theory, label in THEORIES.items():
            for name in ("paper", "measured"):
                fit = entry.get(theory, {}).get(name)
                if not fit:
                    continue
                failed = fit["chi2"] > fits["chi2_limit"]
                systematic = entry[theory]["systematic"]
                constant = fit.get("K", fit.get("alpha"))
                e = fit["e"] if isinstance(fit["e"], str) else f"{fit['e']:g}"
                cells = []
                for p in ("mu", "beta0"):
                    cell = pm(fit.get(p), fit.get(f"{p}_sd"))
                    if failed and p in fit and systematic.get(p) is not None:
                        cell += f" +- {systematic[p]:.3f}"
                    cells.append(cell)
                lines.append(
                    f"| {lattice} | {entry['nu']:.3f} | {entry['inertia_ratio']:.4f} | {label} "
                    f"| {WAYS[name]} | {e} | {constant:.3f} | {fit['weights']} "
                    f"| {cells[0]} | {cells[1]} | {fit['chi2']:.1f} |"
                )
    lines += ["", *model_verdicts(fits), ""]
    return lines + systematic_section(fits)


def model_verdicts(fits: dict) -> list[str]:
    """Which fits describe which lattice's beta(psi), by chi2/dof against the limit."""
    limit = fits["chi2_limit"]
    lines = []
    for lattice, entry in fits["lattices"].items():
        fitted = [
            (f"{THEORIES[theory]} {WAYS[name]}", entry[theory][name]["chi2"])
            for theory in THEORIES
            if theory in entry
            for name in ("paper", "measured")
        ]
        good = [f"{label} (chi2/dof {chi2:.1f})" for label, chi2 in fitted if chi2 <= limit]
        worst = [chi2 for _, chi2 in fitted if chi2 > limit]
        if good:
            lines.append(f"- {lattice}: described by " + ", ".join(good) + ".")
        if worst:
            lines.append(
                f"- {lattice}: {'none' if not good else 'the other'} of the {len(fitted)} fits "
                f"describes its beta within the errors of its means (chi2/dof {min(worst):.0f} "
                f"to {max(worst):.0f}): the model does not describe the data."
            )
    return lines


def systematic_section(fits: dict) -> list[str]:
    """The fits over the fitting choices, for the fits that do not describe the data."""
    limit = fits["chi2_limit"]
    failing = [
        (lattice, theory)
        for lattice, entry in fits["lattices"].items()
        for theory in THEORIES
        if theory in entry and max(entry[theory][w]["chi2"] for w in ("paper", "measured")) > limit
    ]
    if not failing:
        return []
    lines = [
        "### How far the parameters move with the fitting choices",
        "",
        f"Where a fit's chi2/dof is above {limit:g} the model does not describe the data, and "
        "its parameters depend on how it is fitted more than on the samples. Each such fit "
        "again over eight choices: e 0.8 with the paper's K (or eta and alpha) or the "
        "measured e, K and nu; weights by standard error or none; all angles or only the "
        "angles where at most "
        f"{NEAR_SIDE_SHARE:.0%} of the contacts came within {NEAR_SIDE:g} R of a fixed side of "
        "the wall (clear of the wall's ends). The systematic error is half the range of each "
        "parameter over the eight, quoted beside the seed error where the verdicts use it.",
        "",
        "| lattice | theory | mu: range | beta0: range | systematic mu | systematic beta0 "
        "| chi2/dof: range |",
        "|---|---|---|---|---|---|---|",
    ]
    for lattice, theory in failing:
        fit = fits["lattices"][lattice][theory]
        variants = fit["variants"]
        mus = [v["mu"] for v in variants]
        chi2 = [v["chi2"] for v in variants]
        beta0 = [v["beta0"] for v in variants if "beta0" in v]
        beta0_range = f"{min(beta0):.3f} to {max(beta0):.3f}" if beta0 else "-"
        lines.append(
            f"| {lattice} | {THEORIES[theory]} | {min(mus):.3f} to {max(mus):.3f} "
            f"| {beta0_range} | {fit['systematic']['mu']:.3f} "
            f"| {pm(fit['systematic'].get('beta0'))} | {min(chi2):.1f} to {max(chi2):.1f} |"
        )
    lines += [
        "",
        "Each choice for the random lattice (the others are in `fits.json`, `variants`):",
        "",
        "| theory | e, constants | weights | angles | mu | beta0 | chi2/dof |",
        "|---|---|---|---|---|---|---|",
    ]
    entry = fits["lattices"].get("random", {})
    for theory in THEORIES:
        for v in entry.get(theory, {}).get("variants", []):
            lines.append(
                f"| {THEORIES[theory]} | {v['e']}, {v['constants']} | {v['weights']} "
                f"| {v['angles']} ({v['n_angles']}) | {v['mu']:.3f} | {pm(v.get('beta0'))} "
                f"| {v['chi2']:.1f} |"
            )
    return lines + [""]


def measures_section(fits: dict, figure_dir: str) -> list[str]:
    """The model-free measures per lattice, and mu_eff on the sliding branch."""
    if not fits["lattices"]:
        return ["## Model-free measures", "", NO_FITS, ""]
    lines = [
        "## Model-free measures",
        "",
        "From the per-angle means, every angle counted alike (analysis/measures.py): e near "
        f"normal incidence (mean over cot gamma >= {E_NORMAL_PSI:g}), e at grazing incidence "
        f"(mean over the {GRAZING_ANGLES} smallest cot gamma), beta near normal incidence "
        f"(mean over cot gamma >= {BETA_NORMAL_PSI:g}), mu_eff = (1 + beta) / ((1 + e) K "
        "cot gamma) at the top of the sliding branch (below), the share of angles whose mean "
        f"beta is above 0, and the share of all contacts within {NEAR_SIDE:g} R of a fixed "
        "side of the wall.",
        "",
        f"| lattice | e, cot >= {E_NORMAL_PSI:g} | e, {GRAZING_ANGLES} smallest cot "
        f"| beta, cot >= {BETA_NORMAL_PSI:g} | mu_eff, branch's top | share beta > 0 "
        "| share near a side |",
        "|---|---|---|---|---|---|---|",
    ]
    for lattice, entry in fits["lattices"].items():
        m = entry["measures"]
        lines.append(
            f"| {lattice} | {pm(**m['e_normal'])} | {pm(**m['e_grazing'])} "
            f"| {pm(**m['beta_normal'])} | {pm(**m['mu_eff_top'])} "
            f"| {pm(**m['share_beta_positive'], digits=2)} "
            f"| {pm(**m['share_near_side'], digits=3)} |"
        )
    lines += [
        "",
        "### mu_eff on the sliding branch",
        "",
        "Walton's sliding branch, beta = -1 + mu (1 + e) K cot gamma, holds mu_eff constant at "
        "mu. **The sliding branch** is here the angles whose cot gamma is below the kink of "
        "the lattice's paper's-way Walton fit, psi_c = (1 + beta0) / (mu (1 + 0.8) 3), where "
        "that fit leaves the sliding line for the plateau (the branch on which the paper read "
        "its mu); it is fixed from all the data, and mu_eff is computed at each of its angles "
        "with the measured e and K. A constant mu_eff would be Coulomb friction; a mu_eff "
        "that rises toward grazing incidence is not.",
        "",
    ]
    gammas = sorted(
        {
            g
            for entry in fits["lattices"].values()
            for g, on in zip(
                entry["measures"]["mu_eff"]["gamma_deg"], entry["measures"]["mu_eff"]["sliding"]
            )
            if on
        }
    )
    if gammas:
        names = list(fits["lattices"])
        lines += [
            "| gamma (deg) | cot gamma | " + " | ".join(names) + " |",
            "|---|---|" + "---|" * len(names),
        ]
        for gamma in gammas:
            cells, psi = [], None
            for lattice in names:
                mu = fits["lattices"][lattice]["measures"]["mu_eff"]
                if gamma in mu["gamma_deg"]:
                    j = mu["gamma_deg"].index(gamma)
                    psi = mu["cot_gamma"][j]
                    cells.append(pm(mu["value"][j], mu["sd"][j]) if mu["sliding"][j] else "-")
                else:
                    cells.append("-")
            lines.append(f"| {gamma:g} | {psi:.3f} | " + " | ".join(cells) + " |")
        branches = "; ".join(
            f"{lattice} {entry['sliding_branch']['psi_c']:.2f}"
            for lattice, entry in fits["lattices"].items()
        )
        lines += [
            "",
            f"The kinks psi_c: {branches}.",
            "",
            f"![mu_eff against cot gamma on the sliding branch]({figure_dir}/mu_eff.png)",
            "",
            "*mu_eff against cot gamma on the sliding branch, every lattice*",
            "",
        ]
    return lines


def shear_anisotropy(nu: float) -> float:
    """c44 / ((c11 - c12) / 2) of a square lattice's interior from its Poisson
    ratio along the axes: c11 = k1 + k2, c12 = c44 = k2 (per unit area), so
    nu = k2 / (k1 + k2) and the ratio is 2 k2 / k1 = 2 nu / (1 - nu); 1 for
    an isotropic solid, and the shear modulus over an isotropic solid's of the
    same c11 and nu."""
    return 2.0 * nu / (1.0 - nu)


def _shear_ratio(nu_a: float, nu_b: float) -> float:
    """c44 of a square lattice of Poisson ratio nu_a over one of nu_b, at the
    same c11: c44 / c11 = k2 / (k1 + k2) = nu."""
    return nu_a / nu_b


def wall_reading(
    study: dict, rows: list[dict], lattices: tuple[str, ...]
) -> tuple[bool | None, str]:
    """Whether the lattices met one wall (the same points, springs and spring
    constant), from study.json's ``common_wall`` where it is recorded, else
    from impacts.csv: the wall's spring constant over each disk's, and the
    wall's number of points for each seed."""
    if study.get("common_wall") is not None:
        common = bool(study["common_wall"])
        return common, (
            "study.json records one wall for every lattice"
            if common
            else "study.json records a wall for each lattice"
        )
    mine = [r for r in rows if r["study_lattice"] in lattices]
    ratios = {
        lattice: sorted(
            {float(r["ka_wall_over_disk"]) for r in mine if r["study_lattice"] == lattice}
        )
        for lattice in lattices
    }
    points: dict = {}
    for r in mine:
        points.setdefault(r["seed"], set()).add(str(r["n_wall_points"]))
    same_points = all(len(v) == 1 for v in points.values())
    ratio_text = ", ".join(f"{k} {'/'.join(f'{x:.4g}' for x in v)}" for k, v in ratios.items())
    if len({tuple(v) for v in ratios.values()}) == 1:
        return False, (
            f"the wall's spring constant was the same multiple of each disk's ({ratio_text}), "
            "so each disk met a wall of its own stiffness"
            + (" (with the same points for a seed)" if same_points else "")
        )
    return same_points, (
        f"the wall's spring constant was set in the wall's own terms (over each disk's: "
        f"{ratio_text})"
        + (
            " and its points were the same for a seed: one wall"
            if same_points
            else ", but the number of wall points differs for a seed"
        )
    )


def nu_section(fits: dict, study: dict, rows: list[dict], means: list[dict]) -> list[str]:
    """Does beta depend on the Poisson ratio? The two square disks compared,
    with what else differs between them (study.json, impacts.csv's rows and
    means.csv's rows with their seed errors)."""
    pair = fits.get("pair")
    lines = ["## Does beta depend on the Poisson ratio?", ""]
    if not pair:
        return lines + ["This study has not two square lattices; the question needs them.", ""]
    low, high = pair["lower_nu"], pair["higher_nu"]
    a, b = fits["lattices"][low], fits["lattices"][high]
    limit = fits["chi2_limit"]
    common, wall_text = wall_reading(study, rows, (low, high))
    differences = pair["beta_difference"]
    values, sds = np.array(differences["value"], float), np.array(differences["sd"], float)
    beyond = {k: (int(np.sum(values > k * sds)), int(np.sum(values < -k * sds))) for k in (2, 3)}
    lines += [
        f"The square disks {low} (nu = {a['nu']:.3f}) and {high} (nu = {b['nu']:.3f}), compared "
        "at the same seeds (the bootstrap resamples their seeds together, so each "
        "difference's error counts what the two share). beta of the second minus the first, "
        "angle by angle:",
        "",
        "| gamma (deg) | beta, " + low + " | beta, " + high + " | difference |",
        "|---|---|---|---|",
    ]
    means_a, means_b = _by_angle(means, low), _by_angle(means, high)
    for gamma, d, s in zip(pair["gamma_deg"], values, sds):
        lines.append(
            f"| {gamma:g} | {_beta(means_a, gamma)} | {_beta(means_b, gamma)} | {pm(d, s)} |"
        )
    rows_beta0 = []
    for name in ("paper", "measured"):
        d = pair[f"beta0_difference_{name}"]
        failed = max(a["walton"][name]["chi2"], b["walton"][name]["chi2"]) > limit
        error = math.hypot(d["sd"], d["systematic"] if failed else 0.0)
        rows_beta0.append((name, d, failed, error))
    normal = pair["beta_normal_difference"]
    paper_name, paper_d, paper_failed, paper_error = rows_beta0[0]
    z = abs(paper_d["value"]) / paper_error if paper_error > 0 else math.inf
    z_normal = abs(normal["value"]) / normal["sd"] if normal["sd"] else math.inf
    verdict = (
        "differ"
        if min(z, z_normal) > 3
        else "do not differ within the errors"
        if max(z, z_normal) <= 2
        else "may differ: a hint, not a finding"
    )
    lines += [
        "",
        f"Angle by angle, the second disk's beta is above the first's by more than 3 errors "
        f"at {beyond[3][0]} of {len(values)} angles (by more than 2 at {beyond[2][0]}) and "
        f"below it by more than 3 at {beyond[3][1]} (2: {beyond[2][1]}).",
        "",
        f"Near normal incidence (the paper's question, beta0): Walton's beta0 fitted the "
        f"paper's way is {pm(a['walton']['paper']['beta0'], a['walton']['paper']['beta0_sd'])} "
        f"and {pm(b['walton']['paper']['beta0'], b['walton']['paper']['beta0_sd'])}, a "
        f"difference of {pm(paper_d['value'], paper_d['sd'])}"
        + (
            f" +- {paper_d['systematic']:.3f} over the fitting choices (the fits do not "
            "describe the data)"
            if paper_failed
            else ""
        )
        + "; fitted the measured way, a difference of "
        f"{pm(rows_beta0[1][1]['value'], rows_beta0[1][1]['sd'])}. Model-free, beta at cot "
        f"gamma >= {BETA_NORMAL_PSI:g} is {pm(**a['measures']['beta_normal'])} and "
        f"{pm(**b['measures']['beta_normal'])}, a difference of "
        f"{pm(normal['value'], normal['sd'])}. The rule: beta0 differs if the paper's-way "
        "difference (over its seed and systematic errors combined) and the model-free one "
        "are both above 3 errors, is the same if both are within 2, and is a hint otherwise. "
        f"Here they are {z:.1f} and {z_normal:.1f} errors: beta0 of the two disks "
        f"**{verdict}**.",
        "",
        "**The two disks differ in more than nu**, so this is not the effect of nu alone:",
        "",
        f"- their shear stiffness: in a square lattice (springs k1 along the axes, k2 on the "
        f"diagonals: c11 = k1 + k2, c12 = c44 = k2, nu = k2 / (k1 + k2) along the axes) the "
        f"shear modulus over an isotropic solid's of the same c11 and nu, 2 c44 / (c11 - c12) "
        f"= 2 nu / (1 - nu), is {shear_anisotropy(a['nu']):.2f} for the first and "
        f"{shear_anisotropy(b['nu']):.2f} for the second (1: isotropic); the first's shear "
        f"modulus is {_shear_ratio(a['nu'], b['nu']):.2f} of the second's at the same c11 "
        "(docs/materials.md);",
        f"- the energy they take into vibrations: the disk's share of the initial kinetic "
        f"energy is {_range(means, low, 'vibration_disk')} for the first and "
        f"{_range(means, high, 'vibration_disk')} for the second (over the angles; the "
        f"wall's {_range(means, low, 'vibration_wall')} and "
        f"{_range(means, high, 'vibration_wall')}), and e near normal incidence is "
        f"{pm(**a['measures']['e_normal'])} and {pm(**b['measures']['e_normal'])};",
        f"- the wall: {wall_text}"
        + (
            "."
            if common
            else "; a difference of beta may come from the wall as well as from the disk."
        ),
        "",
    ]
    return lines


def _by_angle(means: list[dict], lattice: str) -> dict:
    return {float(m["gamma_deg"]): m for m in means if m["study_lattice"] == lattice}


def _beta(means: dict, gamma: float) -> str:
    m = means.get(float(gamma))
    return pm(m["beta"], m.get("beta_seed_sd")) if m else "-"


def _range(means: list[dict], lattice: str, quantity: str) -> str:
    values = [m[quantity] for m in means if m["study_lattice"] == lattice]
    return f"{min(values):.2f} to {max(values):.2f}"
