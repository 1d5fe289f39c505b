"""Campaign fitting: fit every measured sample of a folder or a list with the same models and settings, and
collect their parameter tables (``"format": "roadbrdf-campaign"``, docs/studies.md "Campaign fitting").

It runs on the machinery of the design studies (run.py, store.py, worker.py): one task per sample, keyed by the
SHA-256 of (the dataset's bytes, the fit settings, the roadbrdf version and build fingerprint), its result appended
to the store as it finishes (an interrupted campaign resumes, a finished one re-runs for free), local processes or
a Dask cluster, progress on standard error, a sample that fails (bad data, or a bug) recorded with its error
without stopping the others. Each task's result is its rows of ``roadbrdf params`` and its fit file, byte for
byte what ``roadbrdf fit -o`` writes.
"""

from __future__ import annotations

import glob
import hashlib
import json
import math
import os
import shutil
import tempfile

from ..core import build_fingerprint
from .spec import InputError, _copy_json, _fail, _object, _read_json, _string

_TOP_KEYS = {"format", "version", "name", "description", "samples", "fit", "fits_folder"}
_SAMPLE_KEYS = {"data", "name", "attributes"}
# roadbrdf.fit's own arguments that a campaign sets itself.
# The fit's fields a campaign sets itself (its samples, one thread per task) or that write files per sample.
_NOT_SETTINGS = {"data", "output", "residuals", "threads", "delimiter", "decimal", "average_duplicates"}


class Campaign:
    """A validated campaign: its samples (name, absolute path, SHA-256 of the bytes, attributes), the keyword
    arguments of roadbrdf.fit, and the folder for the fit files (or None)."""

    def __init__(self, path, name, samples, settings, fits_folder):
        self.path, self.name, self.samples, self.settings, self.fits_folder = path, name, samples, settings, fits_folder

    def attribute_names(self):
        names = []
        for s in self.samples:
            names += [k for k in s["attributes"] if k not in names]
        return names


def is_campaign(data):
    return isinstance(data, dict) and data.get("format") == "roadbrdf-campaign"


def _sha256(path, where, key):
    try:
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError as e:
        _fail(where, key, f"cannot read {path}: {e.strerror}")


def _samples(where, folder, value):
    """The samples: a folder name (every *.csv in it, by name) or a list of paths or objects."""
    if isinstance(value, str):
        directory = os.path.join(folder, value)
        if not os.path.isdir(directory):
            _fail(where, "samples", f"{directory} is not a folder")
        items = sorted(glob.glob(os.path.join(glob.escape(directory), "*.csv")))
        if not items:
            _fail(where, "samples", f"no *.csv dataset in {directory}")
        keys = [f"samples ({os.path.basename(p)})" for p in items]
    elif isinstance(value, list) and value:
        items, keys = value, [f"samples[{i}]" for i in range(len(value))]
    else:
        _fail(where, "samples", "expected a folder name or a non-empty array of datasets")
    samples, names = [], {}
    for item, key in zip(items, keys):
        entry = {"data": item} if isinstance(item, str) else _object(where, key, item, _SAMPLE_KEYS, ("data",))
        data_key = key if isinstance(item, str) else f"{key}.data"
        path = os.path.abspath(os.path.join(folder, _string(where, data_key, entry["data"])))
        name = entry.get("name", os.path.splitext(os.path.basename(path))[0])
        _string(where, f"{key}.name", name)
        if name in names:
            _fail(where, key, f"sample name '{name}' is also that of {names[name]}")
        names[name] = key
        attributes = _object(where, f"{key}.attributes", entry.get("attributes", {}), set(entry.get("attributes", {})))
        for k, v in attributes.items():
            if isinstance(v, bool) or not isinstance(v, (str, int, float)):
                _fail(where, f"{key}.attributes.{k}", f"expected a string or a number, got {json.dumps(v)}")
        samples.append({"name": name, "path": path, "sha256": _sha256(path, where, data_key),
                        "attributes": attributes})
    return samples


def _settings(where, value):
    """The keyword arguments of roadbrdf.fit (checked by name here, by value by the fit itself)."""
    from .. import _roadbrdf
    allowed = ({row["name"] for row in _roadbrdf.request_fields("fit")} | {"fix"}) - _NOT_SETTINGS
    settings = dict(_object(where, "fit", value, allowed, ("models",)))
    models = settings["models"]
    if isinstance(models, str):
        models = [models]
    if not isinstance(models, list) or not models or not all(isinstance(m, str) and m for m in models):
        _fail(where, "fit.models", "expected a model name or a non-empty array of them")
    settings["models"] = models
    return settings


def read_campaign(source) -> Campaign:
    """A campaign from a file path or from a dict (paths in a dict are relative to the current folder)."""
    if isinstance(source, dict):
        where, data, path = "campaign", _copy_json(source, "campaign"), os.path.join(os.getcwd(), "campaign.json")
    else:
        path = os.path.abspath(os.fspath(source))
        where = os.fspath(source)
        data, _ = _read_json(path, where, None)
    if not isinstance(data, dict):
        raise InputError(f"{where}: expected a JSON object")
    _object(where, "", data, _TOP_KEYS, ("format", "version", "samples", "fit"))
    if data["version"] != 1:
        _fail(where, "version", f"this roadbrdf reads version 1, got {json.dumps(data['version'])}")
    folder = os.path.dirname(path)
    fits_folder = None
    if "fits_folder" in data:
        fits_folder = os.path.abspath(os.path.join(folder, _string(where, "fits_folder", data["fits_folder"])))
        if not os.path.isdir(fits_folder):
            _fail(where, "fits_folder", f"{fits_folder} is not a folder")
    name = data.get("name", os.path.splitext(os.path.basename(path))[0])
    return Campaign(path, name, _samples(where, folder, data["samples"]), _settings(where, data["fit"]), fits_folder)


def make_tasks(campaign, version, build=None):
    """(index, sample, key, task) for every sample; ``build``: the build fingerprint in the keys (default: this
    process's, roadbrdf.core.build_fingerprint)."""
    build = build or build_fingerprint()
    out = []
    for index, sample in enumerate(campaign.samples):
        entry = {"data": "sha256:" + sample["sha256"], "fit": campaign.settings, "roadbrdf": version, "build": build}
        key = hashlib.sha256(json.dumps(entry, sort_keys=True, separators=(",", ":")).encode()).hexdigest()
        task = {"key": key, "name": sample["name"], "path": sample["path"], "sha256": sample["sha256"],
                "fit": campaign.settings, "build": build}
        out.append((index, sample, key, task))
    return out


def _plain(value):
    """A DataFrame cell as JSON: NaN becomes null, numpy scalars Python numbers."""
    if hasattr(value, "item"):
        value = value.item()
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def fit_sample(task, texts):
    """One sample's fit: {"rows": params rows, "fit_file": text, "error": None} or {"rows": [], "error": ...},
    with its CPU time and build (worker.guarded: a task of another build is refused; an unexpected exception is
    the sample's recorded ``internal error: ...``).

    The dataset is read from its path when its bytes still have the campaign's SHA-256; else (a Dask worker on
    another machine) from ``texts`` (SHA-256 -> bytes), written to a temporary file of the same name. A changed
    dataset is the sample's error."""
    from .worker import guarded
    return guarded(_fit, task, texts)


def _fit(task, texts):
    from .. import fitting
    work = tempfile.mkdtemp(prefix="roadbrdf-campaign-task-")
    try:
        path = task["path"]
        try:
            with open(path, "rb") as f:
                same = hashlib.sha256(f.read()).hexdigest() == task["sha256"]
        except OSError:
            same = False
        if not same:
            if not texts or task["sha256"] not in texts:
                return {"rows": [], "error": f"{path}: changed or unreadable since the campaign started"}
            local = os.path.join(work, os.path.basename(path))
            with open(local, "wb") as f:
                f.write(texts[task["sha256"]])
            path = local
        fit_path = os.path.join(work, task["name"] + ".fit.json")
        try:
            result = fitting.fit(path, threads=1, **task["fit"])
            result.write(fit_path)
            table = fitting.params(fit_path)
        except InputError as e:
            return {"rows": [], "error": str(e).replace(path, task["path"])}
        rows = [{k: _plain(v) for k, v in r.items()} for r in table.to_dict("records")]
        with open(fit_path, encoding="utf-8") as f:
            fit_file = f.read()
        return {"rows": rows, "units": dict(table.attrs.get("units", {})), "fit_file": fit_file, "error": None}
    finally:
        shutil.rmtree(work, ignore_errors=True)


def table(campaign, tasks, store):
    """Header and rows of the parameters CSV: one row per sample, model (and group) and wavelength; the
    parameters' units in their headers, a parameter a row's model lacks left empty."""
    attributes = campaign.attribute_names()
    columns, units = [], {}
    for *_, key, _ in tasks:
        record = store.results[key]
        units.update(record.get("units") or {})
        for r in record["rows"]:
            columns += [c for c in r if c not in columns]

    def heading(c):
        base = c[:-len("_stderr")] if c.endswith("_stderr") else c
        return f"{c} [{units[base]}]" if base in units else c
    header = ["sample", "key", "status", "error"] + attributes + [heading(c) for c in columns]
    rows = []
    for _, sample, key, _ in tasks:
        record = store.results[key]
        ident = [sample["name"], key]
        values = [sample["attributes"].get(a) for a in attributes]
        if record["error"] is not None:
            rows.append(ident + ["failed", record["error"]] + values + [None] * len(columns))
            continue
        for r in record["rows"]:
            rows.append(ident + ["ok", ""] + values + [r.get(c) for c in columns])
    return header, rows


def write_fit_files(campaign, tasks, store):
    """NAME.fit.json of every fitted sample in the campaign's fits_folder, each written atomically."""
    from ..core import write_text_atomic
    if campaign.fits_folder is None:
        return
    for _, sample, key, _ in tasks:
        text = store.results[key].get("fit_file")
        if text is not None:
            path = os.path.join(campaign.fits_folder, sample["name"] + ".fit.json")
            try:
                write_text_atomic(path, text, ".json")
            except OSError as e:
                raise InputError(f"{path}: cannot write the fit file: {e.strerror or e} (the results store keeps "
                                 "every fit: run again to write it)") from None


def texts_of(campaign):
    """SHA-256 -> bytes of every sample, for Dask workers that may not see the campaign's files."""
    out = {}
    for s in campaign.samples:
        with open(s["path"], "rb") as f:
            out[s["sha256"]] = f.read()
    return out
