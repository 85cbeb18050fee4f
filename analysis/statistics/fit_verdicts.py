"""Which fits describe which lattice's beta(psi) (chi2/dof against the
limit), and how far the parameters of those that do not move over the
fitting choices (fits.json's ``variants``): the numbers of a results page's
fits section (pages/templates/results/fits.md.j2)."""

from __future__ import annotations

THEORIES = ("walton", "compliant")
WAYS = ("paper", "measured")


def described(fits: dict) -> dict[str, dict]:
    """Per lattice: its fits (theory, way, chi2/dof) that describe its beta
    within the errors (chi2/dof at most the limit), the chi2/dof of those
    that do not, and how many fits it has."""
    limit = fits["chi2_limit"]
    out = {}
    for lattice, entry in fits["lattices"].items():
        fitted = [
            {"theory": theory, "way": way, "chi2": entry[theory][way]["chi2"]}
            for theory in THEORIES
            if theory in entry
            for way in WAYS
        ]
        out[lattice] = {
            "good": [f for f in fitted if f["chi2"] <= limit],
            "bad": [f["chi2"] for f in fitted if f["chi2"] > limit],
            "fits": len(fitted),
        }
    return out


def failing(fits: dict) -> list[dict]:
    """The (lattice, theory) whose fit either way does not describe the data,
    with the ranges of mu, beta0 and chi2/dof over the fitting choices."""
    limit = fits["chi2_limit"]
    out = []
    for lattice, entry in fits["lattices"].items():
        for theory in THEORIES:
            if theory not in entry or max(entry[theory][w]["chi2"] for w in WAYS) <= limit:
                continue
            variants = entry[theory]["variants"]
            beta0 = [v["beta0"] for v in variants if "beta0" in v]
            out.append(
                {
                    "lattice": lattice,
                    "theory": theory,
                    "mu": (min(v["mu"] for v in variants), max(v["mu"] for v in variants)),
                    "beta0": (min(beta0), max(beta0)) if beta0 else None,
                    "chi2": (min(v["chi2"] for v in variants), max(v["chi2"] for v in variants)),
                    "systematic": entry[theory]["systematic"],
                }
            )
    return out


def mu_eff_table(fits: dict) -> list[dict]:
    """mu_eff at every angle, a row per angle any lattice has, the most
    grazing first: the angle, its cot gamma (the last lattice's that has
    the angle), and per lattice (mu_eff, its seed error, on the lattice's
    sliding branch) or None where the lattice lacks the angle."""
    lattices = fits["lattices"]
    gammas = sorted(
        {g for entry in lattices.values() for g in entry["measures"]["mu_eff"]["gamma_deg"]},
        reverse=True,
    )
    rows = []
    for gamma in gammas:
        cells, psi = {}, None
        for lattice, entry in lattices.items():
            mu = entry["measures"]["mu_eff"]
            cells[lattice] = None
            if gamma in mu["gamma_deg"]:
                j = mu["gamma_deg"].index(gamma)
                psi = mu["cot_gamma"][j]
                cells[lattice] = (mu["value"][j], mu["sd"][j], mu["sliding"][j])
        rows.append({"gamma": gamma, "psi": psi, "cells": cells})
    return rows
