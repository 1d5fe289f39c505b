"""The study file (``"format": "roadbrdf-study"``, version 1): reading and validation.

Everything is checked once, before any candidate runs; every error names the study file and the JSON key path
(``study.json: variables[2].range: ...``). The format is documented in docs/studies.md.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re

from .. import _roadbrdf
from ..core import MAX_JSON_DEPTH, check_json_depth, parse_json_text  # noqa: F401 - used here and by store.py

InputError = _roadbrdf.InputError

KINDS = ("mass_percent", "component", "share", "mastic_fraction")
DESIGNS = ("grid", "random", "lhs")
# The mixing methods that need no measured mixture (areal, mastic, hapke).
FAST_METHODS = tuple(m["name"] for m in _roadbrdf.mixing_methods() if not m["needs_data"])
PATHS = ("fast", "physical")

_TOP_KEYS = {"format", "version", "name", "description", "base", "library", "variables", "design", "replicates",
             "predictions"}
_VARIABLE_KEYS = {"name", "kind", "component", "values", "range", "levels", "balance", "balance_range", "choices",
                  "material", "unit", "note"}
_DESIGN_KEYS = {"type", "count", "seed"}
_PREDICTION_KEYS = {"path", "methods", "sun_zenith_deg", "diffuse_fraction", "atmosphere", "spectrum",
                    "illuminant", "physical", "lighting"}
_PHYSICAL_KEYS = {"size_mm", "cell_mm", "samples", "wavelengths", "white_sky_nodes", "acceptance_deg", "rtable",
                  "max_bounces"}
_LIBRARY_KEYS = {"fit", "fit_model", "density_g_cm3", "note"}
_LIGHTING_KEYS = {"installation", "class", "operating_hours"}
M_CLASSES = ("M1", "M2", "M3", "M4", "M5", "M6")

# The lighting figures a study stores per candidate (predictions.lighting), with their units: the names of the
# `roadbrdf lighting` JSON (docs/lighting.md), the least flux's with ``least_``. Kind: "number" or "text"; each
# may be null (no class met, no class asked for, an infeasible class).
LIGHTING_OUTPUTS = (
    ("M_class", "class", "text"), ("L_av", "cd/m^2", "number"), ("U_o", "1", "number"), ("U_l", "1", "number"),
    ("f_TI", "%", "number"), ("R_EI", "1", "number"), ("E_av", "lx", "number"), ("U_o_E", "1", "number"),
    ("D_P", "W lx^-1 m^-2", "number"), ("D_E", "Wh m^-2 per year", "number"), ("power_per_km_w", "W/km", "number"),
    ("least_class", "class", "text"), ("least_dimming_factor", "1", "number"),
    ("least_power_per_km_w", "W/km", "number"),
    ("least_blocking", "criteria", "text"), ("ULOR", "1", "number"), ("direct_upward_lm_per_km", "lm/km", "number"),
    ("reflected_upward_lm_per_km", "lm/km", "number"), ("lighting_reflectance", "1", "number"))

class Study:
    """A validated study: the base formulation (dict, fit paths absolute), the library, the variables, the
    design and the prediction settings, and the fit files' contents keyed by their SHA-256."""

    def __init__(self, path, name, base_path, base, library, variables, design, replicates, predictions, fits):
        self.path = path
        self.name = name
        self.base_path = base_path
        self.base = base
        self.library = library
        self.variables = variables
        self.design = design
        self.replicates = replicates
        self.predictions = predictions
        self.fits = fits  # sha256 -> file text
        self.fit_hash = {}  # absolute path -> sha256


def _fail(where, key, message):
    raise InputError(f"{where}: {key}: {message}")


def _number(where, key, value, low=-math.inf, high=math.inf, open_low=False, open_high=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        _fail(where, key, f"expected a number, got {json.dumps(value)}")
    if value < low or value > high or (open_low and value == low) or (open_high and value == high):
        lo = "(" if open_low else "["
        hi = ")" if open_high else "]"
        _fail(where, key, f"{value:g} is outside {lo}{low:g}, {high:g}{hi}")
    return float(value)


def _integer(where, key, value, low, high=None):
    if isinstance(value, bool) or not isinstance(value, int):
        _fail(where, key, f"expected an integer, got {json.dumps(value)}")
    if value < low or (high is not None and value > high):
        _fail(where, key, f"{value} is outside [{low}, {high if high is not None else 'inf'}]")
    return value


def _string(where, key, value):
    if not isinstance(value, str) or not value:
        _fail(where, key, f"expected a non-empty string, got {json.dumps(value)}")
    return value


def _object(where, key, value, allowed, required=()):
    if not isinstance(value, dict):
        _fail(where, key, f"expected an object, got {json.dumps(value)[:60]}")
    for k in value:
        if k not in allowed:
            _fail(where, f"{key}.{k}" if key else k, f"unknown key (allowed: {', '.join(sorted(allowed))})")
    for k in required:
        if k not in value:
            _fail(where, f"{key}.{k}" if key else k, "required key is missing")
    return value


def _read_json(path, where, key):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        if key is None:
            raise InputError(f"{path}: cannot read: {e.strerror}") from None
        _fail(where, key, f"cannot read {path}: {e.strerror}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: byte {e.start + 1}: not UTF-8 text") from None
    return parse_json_text(text, path), text


def _hash_fit(study, path, where, key):
    """SHA-256 of a fit file's bytes (read once), remembered with its text."""
    path = os.path.abspath(path)
    if path not in study.fit_hash:
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as e:
            _fail(where, key, f"cannot read fit file {path}: {e.strerror}")
        digest = hashlib.sha256(data).hexdigest()
        study.fit_hash[path] = digest
        study.fits[digest] = data.decode("utf-8", errors="strict")
    return study.fit_hash[path]


def _range_or_values(where, key, v, low, high):
    """('values', [..]) or ('range', (lo, hi), levels or None)."""
    if ("values" in v) == ("range" in v):
        _fail(where, key, "give exactly one of 'values' and 'range'")
    if "values" in v:
        values = v["values"]
        if not isinstance(values, list) or not values:
            _fail(where, f"{key}.values", "expected a non-empty array")
        out = [_number(where, f"{key}.values[{i}]", x, low, high) for i, x in enumerate(values)]
        if len(set(out)) != len(out):
            _fail(where, f"{key}.values", "values repeat")
        if "levels" in v:
            _fail(where, f"{key}.levels", "'levels' goes with 'range', not with 'values'")
        return {"values": out}
    r = v["range"]
    if not isinstance(r, list) or len(r) != 2:
        _fail(where, f"{key}.range", "expected [low, high]")
    lo = _number(where, f"{key}.range[0]", r[0], low, high)
    hi = _number(where, f"{key}.range[1]", r[1], low, high)
    if not lo < hi:
        _fail(where, f"{key}.range", f"low {lo:g} must be below high {hi:g}")
    levels = None
    if "levels" in v:
        levels = _integer(where, f"{key}.levels", v["levels"], 2, 10000)
    return {"range": (lo, hi), "levels": levels}


def _component_index(where, key, base, name):
    for i, c in enumerate(base["components"]):
        if c.get("name") == name:
            return i
    names = ", ".join(str(c.get("name")) for c in base["components"])
    _fail(where, key, f"the base formulation has no component '{name}' (components: {names})")


def _variables(study, where, data):
    raw = data.get("variables", [])
    if not isinstance(raw, list):
        _fail(where, "variables", "expected an array")
    names = set()
    out = []
    for i, v in enumerate(raw):
        key = f"variables[{i}]"
        _object(where, key, v, _VARIABLE_KEYS, ("name", "kind"))
        name = _string(where, f"{key}.name", v["name"])
        if name in names or name in ("candidate", "replicate", "method"):
            _fail(where, f"{key}.name", f"'{name}' is used twice or is reserved")
        names.add(name)
        kind = v["kind"]
        if kind not in KINDS:
            _fail(where, f"{key}.kind", f"'{kind}' is not one of {', '.join(KINDS)}")
        allowed = {"name", "kind", "note"} | {
            "mass_percent": {"component", "values", "range", "levels", "balance", "balance_range"},
            "component": {"component", "choices"},
            "share": {"component", "material", "values", "range", "levels"},
            "mastic_fraction": {"values", "range", "levels"}}[kind]
        for k in v:
            if k not in allowed:
                _fail(where, f"{key}.{k}", f"not a key of a '{kind}' variable (allowed: {', '.join(sorted(allowed))})")
        item = {"name": name, "kind": kind}
        if kind != "mastic_fraction":
            if "component" not in v:
                _fail(where, f"{key}.component", "required key is missing")
            if kind == "share" and isinstance(v["component"], list) and v["component"]:
                # One share applied to several components (e.g. both coarse classes of a rock).
                parts = [_string(where, f"{key}.component[{j}]", c) for j, c in enumerate(v["component"])]
                item["indices"] = [_component_index(where, f"{key}.component[{j}]", study.base, c)
                                   for j, c in enumerate(parts)]
                if len(set(item["indices"])) != len(parts):
                    _fail(where, f"{key}.component", "components repeat")
                item["component"] = parts
            else:
                item["component"] = _string(where, f"{key}.component", v["component"])
                item["index"] = _component_index(where, f"{key}.component", study.base, item["component"])
                item["indices"] = [item["index"]]
        if kind == "mass_percent":
            item.update(_range_or_values(where, key, v, 0.0, 100.0))
            if "balance" not in v:
                _fail(where, f"{key}.balance", "required: the component whose mass absorbs the change (so that the "
                                               "fractions still sum to 100 %)")
            item["balance"] = _string(where, f"{key}.balance", v["balance"])
            item["balance_index"] = _component_index(where, f"{key}.balance", study.base, item["balance"])
            if item["balance_index"] == item["index"]:
                _fail(where, f"{key}.balance", "must differ from the varied component")
            br = v.get("balance_range", [0.0, 100.0])
            if not isinstance(br, list) or len(br) != 2:
                _fail(where, f"{key}.balance_range", "expected [low, high] [%]")
            item["balance_range"] = (_number(where, f"{key}.balance_range[0]", br[0], 0, 100),
                                     _number(where, f"{key}.balance_range[1]", br[1], 0, 100))
            item["unit"] = "%"
        elif kind == "component":
            choices = v.get("choices")
            if not isinstance(choices, list) or not choices:
                _fail(where, f"{key}.choices", "expected a non-empty array of library names")
            for j, c in enumerate(choices):
                if c not in study.library:
                    _fail(where, f"{key}.choices[{j}]", f"'{c}' is not in the library "
                                                         f"({', '.join(sorted(study.library)) or 'empty'})")
            if len(set(choices)) != len(choices):
                _fail(where, f"{key}.choices", "choices repeat")
            item["values"] = list(choices)
            item["unit"] = ""
        elif kind == "share":
            if "material" not in v:
                _fail(where, f"{key}.material", "required key is missing (a library name)")
            if v["material"] not in study.library:
                _fail(where, f"{key}.material", f"'{v['material']}' is not in the library")
            item["material"] = v["material"]
            item.update(_range_or_values(where, key, v, 0.0, 1.0))
            item["unit"] = "1"
        else:
            item.update(_range_or_values(where, key, v, 0.0, 1.0))
            for j, x in enumerate(item.get("values", item.get("range", ()))):
                if not 0.0 < x < 1.0:
                    _fail(where, f"{key}.{'values' if 'values' in item else 'range'}[{j}]",
                          f"{x:g}: an exposed mastic fraction is in (0, 1)")
            item["unit"] = "1"
        out.append(item)
    return out


def _library(study, where, data):
    raw = data.get("library", {})
    if not isinstance(raw, dict):
        _fail(where, "library", "expected an object {name: {fit, fit_model, density_g_cm3}}")
    folder = os.path.dirname(os.path.abspath(study.path))
    out = {}
    for name, entry in raw.items():
        key = f"library.{name}"
        _object(where, key, entry, _LIBRARY_KEYS, ("fit",))
        fit = os.path.join(folder, _string(where, f"{key}.fit", entry["fit"]))
        item = {"fit": os.path.abspath(fit), "hash": _hash_fit(study, fit, where, f"{key}.fit")}
        if "fit_model" in entry:
            item["fit_model"] = _string(where, f"{key}.fit_model", entry["fit_model"])
        if "density_g_cm3" in entry:
            item["density_g_cm3"] = _number(where, f"{key}.density_g_cm3", entry["density_g_cm3"], 0, open_low=True)
        out[name] = item
    return out


def _file_sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def _lighting(where, raw, base_folder):
    """``predictions.lighting``: the installation (read once here, so that a bad file fails before any candidate
    runs), the M class for the least power per km, the operating hours for D_E. The files' SHA-256 go into the
    task keys: an edited installation or luminaire file gives new results."""
    k = "predictions.lighting"
    _object(where, k, raw, _LIGHTING_KEYS, ("installation",))
    path = os.path.abspath(os.path.join(base_folder, _string(where, f"{k}.installation", raw["installation"])))
    try:
        prepared = _roadbrdf.read_lighting_installation(path)
    except InputError as e:
        _fail(where, f"{k}.installation", str(e))
    if not prepared.power_w > 0:
        _fail(where, f"{k}.installation", f"{path}: the luminaires' power is unknown (the luminaire file gives none): "
                                          "give luminaires.power_w in the installation, the power per km needs it")
    out = {"installation": path, "installation_sha256": _file_sha256(path),
           "luminaire_sha256": _file_sha256(prepared.luminaire_file), "class": None,
           "operating_hours": _number(where, f"{k}.operating_hours", raw.get("operating_hours", 4000.0), 0, 8784)}
    if "class" in raw:
        if raw["class"] not in M_CLASSES:
            _fail(where, f"{k}.class", f"{json.dumps(raw['class'])} is not an M lighting class "
                                       f"({', '.join(M_CLASSES)}, EN 13201-2)")
        out["class"] = raw["class"]
    return out


def _predictions(where, data, base_folder="."):
    p = data.get("predictions", {})
    _object(where, "predictions", p, _PREDICTION_KEYS)
    path = p.get("path", "fast")
    if path not in PATHS:
        _fail(where, "predictions.path", f"'{path}' is not one of {', '.join(PATHS)}")
    out = {"path": path}
    zen = p.get("sun_zenith_deg", [30.0])
    if not isinstance(zen, list) or not zen:
        _fail(where, "predictions.sun_zenith_deg", "expected a non-empty array [deg]")
    out["sun_zenith_deg"] = [_number(where, f"predictions.sun_zenith_deg[{i}]", z, 0, 90, open_high=True)
                             for i, z in enumerate(zen)]
    if "diffuse_fraction" in p and "atmosphere" in p:
        _fail(where, "predictions.atmosphere", "give 'diffuse_fraction' or 'atmosphere', not both")
    out["diffuse_fraction"] = (None if "diffuse_fraction" not in p else
                               _number(where, "predictions.diffuse_fraction", p["diffuse_fraction"], 0, 1))
    out["atmosphere"] = None if "atmosphere" not in p else _string(where, "predictions.atmosphere", p["atmosphere"])
    out["spectrum"] = p.get("spectrum", "astm-g173-global")
    if out["spectrum"] not in ("astm-g173-global", "astm-g173-direct"):
        _fail(where, "predictions.spectrum", "expected 'astm-g173-global' or 'astm-g173-direct'")
    out["illuminant"] = p.get("illuminant", "A")
    if out["illuminant"] not in ("A", "D65"):
        _fail(where, "predictions.illuminant", "expected 'A' or 'D65'")
    if path == "fast":
        if "physical" in p:
            _fail(where, "predictions.physical", "only with \"path\": \"physical\"")
        methods = p.get("methods", ["areal", "mastic"])
        if not isinstance(methods, list) or not methods:
            _fail(where, "predictions.methods", "expected a non-empty array of mixing methods")
        for i, m in enumerate(methods):
            if m not in FAST_METHODS:
                _fail(where, f"predictions.methods[{i}]", f"'{m}' is not one of {', '.join(FAST_METHODS)} (the "
                                                          "methods that need no measured mixture)")
        if len(set(methods)) != len(methods):
            _fail(where, "predictions.methods", "methods repeat")
        out["methods"] = list(methods)
        if "lighting" in p:
            out["lighting"] = _lighting(where, p["lighting"], base_folder)
        return out
    if "lighting" in p:
        _fail(where, "predictions.lighting", "only with \"path\": \"fast\" (the lighting calculation needs the "
                                             "candidate's BRDF, which the physical path does not make)")
    if "methods" in p:
        _fail(where, "predictions.methods", "only with \"path\": \"fast\"")
    if out["atmosphere"] is not None:
        _fail(where, "predictions.atmosphere", "the physical path takes a constant 'diffuse_fraction' only")
    ph = p.get("physical", {})
    _object(where, "predictions.physical", ph, _PHYSICAL_KEYS)
    k = "predictions.physical"
    q = {"size_mm": _number(where, f"{k}.size_mm", ph.get("size_mm", 30.0), 0, open_low=True),
         "cell_mm": _number(where, f"{k}.cell_mm", ph.get("cell_mm", 0.2), 0, open_low=True),
         "samples": _integer(where, f"{k}.samples", ph.get("samples", 1024), 1, 1 << 24),
         "white_sky_nodes": _integer(where, f"{k}.white_sky_nodes", ph.get("white_sky_nodes", 8), 1, 64),
         "acceptance_deg": _number(where, f"{k}.acceptance_deg", ph.get("acceptance_deg", 1.0), 0, 30),
         "max_bounces": _integer(where, f"{k}.max_bounces", ph.get("max_bounces", 0), 0, 1000),
         "rtable": ph.get("rtable", True)}
    if not isinstance(q["rtable"], bool):
        _fail(where, f"{k}.rtable", "expected true or false")
    wl = ph.get("wavelengths", [450.0, 550.0, 650.0])
    if not isinstance(wl, list) or not wl:
        _fail(where, f"{k}.wavelengths", "expected a non-empty array [nm]")
    q["wavelengths"] = [_number(where, f"{k}.wavelengths[{i}]", w, 280, 4000) for i, w in enumerate(wl)]
    if any(b <= a for a, b in zip(q["wavelengths"], q["wavelengths"][1:])):
        _fail(where, f"{k}.wavelengths", "must increase strictly")
    if q["cell_mm"] * 4 > q["size_mm"]:
        _fail(where, f"{k}.cell_mm", f"{q['cell_mm']:g} mm is too coarse for a {q['size_mm']:g} mm sample")
    out["physical"] = q
    return out


def _design(where, data, variables):
    d = data.get("design", {"type": "grid"})
    _object(where, "design", d, _DESIGN_KEYS, ("type",))
    kind = d["type"]
    if kind not in DESIGNS:
        _fail(where, "design.type", f"'{kind}' is not one of {', '.join(DESIGNS)}")
    out = {"type": kind, "seed": _integer(where, "design.seed", d.get("seed", 1), 0)}
    if kind == "grid":
        if "count" in d:
            _fail(where, "design.count", "a grid has as many candidates as the product of the levels")
        for i, v in enumerate(variables):
            if "range" in v and v["levels"] is None:
                _fail(where, f"variables[{i}].levels", "a grid needs 'levels' for a variable given by a 'range'")
    else:
        if "count" not in d:
            _fail(where, "design.count", "required for a random or Latin-hypercube design")
        out["count"] = _integer(where, "design.count", d["count"], 1, 10_000_000)
        for i, v in enumerate(variables):
            if v.get("levels") is not None:
                _fail(where, f"variables[{i}].levels", f"only for a grid design (this one is '{kind}')")
    return out


def _base(study, where, data):
    base_rel = _string(where, "base", data.get("base"))
    base_path = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(study.path)), base_rel))
    base, _ = _read_json(base_path, where, "base")
    if not isinstance(base, dict) or base.get("format") != "roadbrdf-formulation":
        _fail(where, "base", f"{base_path} is not a roadbrdf formulation (\"format\": \"roadbrdf-formulation\")")
    if not isinstance(base.get("components"), list) or not base["components"]:
        _fail(where, "base", f"{base_path}: the formulation has no components")
    folder = os.path.dirname(base_path)
    # Fit paths become absolute (the candidate formulations are written elsewhere); the mixing code checks the rest.
    for i, c in enumerate(base["components"]):
        if isinstance(c, dict) and isinstance(c.get("fit"), str):
            c["fit"] = os.path.abspath(os.path.join(folder, c["fit"]))
            _hash_fit(study, c["fit"], f"{base_path}", f"components[{i}].fit")
    if isinstance(base.get("mastic"), dict) and isinstance(base["mastic"].get("fit"), str):
        base["mastic"]["fit"] = os.path.abspath(os.path.join(folder, base["mastic"]["fit"]))
        _hash_fit(study, base["mastic"]["fit"], f"{base_path}", "mastic.fit")
    return base_path, base


def _copy_json(source, where):
    """A deep copy of a dict given instead of a file, through JSON (what a file could hold), depth-checked."""
    try:
        text = json.dumps(source)
    except (TypeError, ValueError, RecursionError) as e:
        raise InputError(f"{where}: not JSON data: {type(e).__name__}: {e}") from None
    return parse_json_text(text, where)


def read_study(source) -> Study:
    """A study from a file path or from a dict (paths in a dict are relative to the current folder)."""
    if isinstance(source, dict):
        where, data = "study", _copy_json(source, "study")
        path = os.path.join(os.getcwd(), "study.json")
    else:
        path = os.fspath(source)
        where = path
        data, _ = _read_json(path, path, None)
    if not isinstance(data, dict):
        raise InputError(f"{where}: expected a JSON object")
    _object(where, "", data, _TOP_KEYS, ("format", "version", "base"))
    if data["format"] != "roadbrdf-study":
        _fail(where, "format", f"expected \"roadbrdf-study\", got {json.dumps(data['format'])}")
    if data["version"] != 1:
        _fail(where, "version", f"this roadbrdf reads version 1, got {json.dumps(data['version'])}")
    study = Study(path, data.get("name", os.path.splitext(os.path.basename(path))[0]), None, None, None, None,
                  None, None, None, {})
    study.base_path, study.base = _base(study, where, data)
    study.library = _library(study, where, data)
    study.variables = _variables(study, where, data)
    study.design = _design(where, data, study.variables)
    study.replicates = _integer(where, "replicates", data.get("replicates", 1), 1, 10000)
    study.predictions = _predictions(where, data, os.path.dirname(os.path.abspath(study.path)))
    return study
