"""Designs (grid, random, Latin hypercube) and the candidate formulations they make.

Random numbers come from SHA-256 of text (seed, purpose, indices), never from a library generator, so a design
is the same on every machine, Python and numpy version. A candidate is a dict {variable name: value}; its
formulation is the base formulation with the variables applied (:func:`apply`).
"""

from __future__ import annotations

import copy
import hashlib
import itertools

from .spec import InputError


def uniform(*parts) -> float:
    """A number in [0, 1) from SHA-256 of the parts (53 bits, as a double holds)."""
    digest = hashlib.sha256(":".join(str(p) for p in parts).encode()).digest()
    return (int.from_bytes(digest[:8], "big") >> 11) / float(1 << 53)


def _levels(v):
    """The values a grid takes for a variable."""
    if "values" in v:
        return list(v["values"])
    lo, hi = v["range"]
    n = v["levels"]
    return [lo + (hi - lo) * i / (n - 1) for i in range(n)]


def _pick(v, u):
    """The value of a variable at a unit coordinate u in [0, 1): uniform in a range, or one of the values."""
    if "values" in v:
        return v["values"][min(int(u * len(v["values"])), len(v["values"]) - 1)]
    lo, hi = v["range"]
    return lo + (hi - lo) * u


def point_count(study):
    """How many points the design has (without making them)."""
    if not study.variables:
        return 1
    if study.design["type"] == "grid":
        n = 1
        for v in study.variables:
            n *= len(_levels(v))
        return n
    return study.design["count"]


def candidate_count(study):
    """How many candidates the study has: design points x replicates."""
    return point_count(study) * study.replicates


def design_points(study):
    """The design's points, in order, one at a time: {variable name: value}."""
    variables = study.variables
    d = study.design
    if not variables:
        yield {}
        return
    if d["type"] == "grid":
        for combo in itertools.product(*(_levels(v) for v in variables)):
            yield dict(zip((v["name"] for v in variables), combo))
        return
    n = d["count"]
    seed = d["seed"]
    if d["type"] == "random":
        for i in range(n):
            yield {v["name"]: _pick(v, uniform(seed, "random", j, i)) for j, v in enumerate(variables)}
        return
    # Latin hypercube: for each variable a permutation of the n strata (sorted by hash), a uniform point inside.
    # The permutations are made once (n integers per variable); the points one at a time.
    orders = []
    for j, _ in enumerate(variables):
        orders.append(sorted(range(n), key=lambda i, j=j: uniform(seed, "lhs-permutation", j, i)))
    for i in range(n):
        yield {v["name"]: _pick(v, (orders[j][i] + uniform(seed, "lhs-offset", j, i)) / n)
               for j, v in enumerate(variables)}


def candidates(study):
    """Every candidate, one at a time: (index, point, replicate) for each design point and replicate 1..R."""
    index = 0
    for point in design_points(study):
        for r in range(1, study.replicates + 1):
            yield index, point, r
            index += 1


def apply(study, point):
    """The formulation of a design point (dict; fit paths absolute) and its mastic exposure (or None).

    Raises InputError when the point is outside what the formulation allows (a balance component leaving its
    envelope); the study records that candidate as failed.
    """
    f = copy.deepcopy(study.base)
    comps = f["components"]
    mastic_fraction = None
    # Component swaps first, then shares (they split a component), then mass changes.
    for v in study.variables:
        if v["kind"] == "component":
            lib = study.library[point[v["name"]]]
            c = comps[v["index"]]
            c["fit"] = lib["fit"]
            c.pop("fit_model", None)
            if "fit_model" in lib:
                c["fit_model"] = lib["fit_model"]
            if "density_g_cm3" in lib:
                c["density_g_cm3"] = lib["density_g_cm3"]
    for v in study.variables:
        if v["kind"] == "mass_percent":
            c = comps[v["index"]]
            b = comps[v["balance_index"]]
            new = float(point[v["name"]])
            balance = b["mass_percent"] + c["mass_percent"] - new
            lo, hi = v["balance_range"]
            if not lo <= balance <= hi or balance <= 0.0:
                raise InputError(f"variable '{v['name']}' = {new:g} % leaves '{v['balance']}' at {balance:g} %, "
                                 f"outside its envelope [{lo:g}, {hi:g}] % (and it must stay above 0)")
            c["mass_percent"] = new
            b["mass_percent"] = balance
        elif v["kind"] == "mastic_fraction":
            mastic_fraction = float(point[v["name"]])
            f["mastic_area_fraction"] = mastic_fraction
    additions = []
    for v in study.variables:
        if v["kind"] == "share":
            for index in v["indices"]:
                additions.append(_split(comps[index], study.library[v["material"]], v["material"],
                                        float(point[v["name"]])))
    comps.extend(additions)
    # A component whose mass went to zero (mass 0, share 0 or 1) is left out: formulations hold positive masses.
    f["components"] = [c for c in comps if c["mass_percent"] > 0.0]
    if not any(c.get("kind") != "binder" for c in f["components"]):
        raise InputError("the candidate has no aggregate left")
    return f, mastic_fraction


def _split(c, lib, material, s):
    """Move the share s of component c's mass to a new component of the same size class made of ``material``."""
    part = dict(c)
    part["name"] = f"{c['name']} ({material})"
    part["fit"] = lib["fit"]
    part.pop("fit_model", None)
    part.pop("note", None)
    if "fit_model" in lib:
        part["fit_model"] = lib["fit_model"]
    if "density_g_cm3" in lib:
        part["density_g_cm3"] = lib["density_g_cm3"]
    part["mass_percent"] = c["mass_percent"] * s
    c["mass_percent"] = c["mass_percent"] * (1.0 - s)
    return part
