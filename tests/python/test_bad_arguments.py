"""Every public function of the package, every argument, a set of bad values: the only errors that come out
are roadbrdf.InputError (a ValueError), ValueError or TypeError, naming the argument where the wrapper converts
it; never AttributeError, OverflowError, MemoryError, KeyError or a crash.

Each function has a small valid call (``BASE``); one argument at a time is replaced by each bad value. The sweep
runs in a child process with its address space bounded, so that a value the library fails to refuse ends in
a MemoryError (reported) rather than in swapping."""

import inspect
import json
import math
import os
import subprocess
import sys
import textwrap

import pytest

import roadbrdf

BAD_VALUES = {"None": None, "'x'": "x", "inf": math.inf, "nan": math.nan, "-1": -1, "10**9": 10 ** 9, "[]": [],
              "{}": {}, "object()": object(), "2.5": 2.5, "b'x'": b"x", "-inf": -math.inf}


def _files(folder):
    """A small dataset, its Lambertian fit file and a formulation of two rocks of that fit (test files of ours)."""
    data = os.path.join(folder, "tile.csv")
    with open(data, "w", encoding="utf-8") as f:
        f.write("# sample: tile\ntheta_i,phi_i,theta_r,phi_r,500,600\n")
        for ti in (0, 30, 60):
            for tr in (0, 20, 40, 60):
                f.write(f"{ti},0,{tr},180,0.09,0.1\n")
    fit = os.path.join(folder, "grey.fit.json")
    roadbrdf.fit(data, "lambert", output=fit)
    formulation = os.path.join(folder, "mix.json")
    with open(formulation, "w", encoding="utf-8") as f:
        json.dump({"format": "roadbrdf-formulation", "version": 1, "name": "rocks", "components": [
            {"name": "A 2/6", "kind": "aggregate", "mass_percent": 50, "density_g_cm3": 2.65, "d_min_mm": 2,
             "d_max_mm": 6, "fit": "grey.fit.json"},
            {"name": "B 6/10", "kind": "aggregate", "mass_percent": 50, "density_g_cm3": 2.65, "d_min_mm": 6,
             "d_max_mm": 10, "fit": "grey.fit.json"}]}, f)
    return data, fit, formulation


LIGHTING = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "lighting")
GRID = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "grid",
                    "cerema-like-grid.csv")


def base_calls(folder):
    """{function name: (function, keyword arguments of a valid, quick call)}."""
    data, fit, formulation = _files(folder)
    flat = roadbrdf.flat_surface("lambert", {"albedo": 0.3}, cells=8, cell_mm=0.5)
    surface_file = os.path.join(folder, "flat.surface")
    flat.write(surface_file)
    lambert = roadbrdf.Model("lambert")
    dataset = roadbrdf.read_dataset(data)
    small = dict(max_samples=4096, samples=512, seed=1, threads=1)
    table = os.path.join(folder, "lambert.rtable.csv")
    roadbrdf.rtable(lambert, {"albedo": 0.3}).write(table)
    fitted = roadbrdf.fit(data, "lambert")
    from study_support import physical_study
    virtual = os.path.join(folder, "virtual")
    os.makedirs(virtual, exist_ok=True)
    import pathlib
    physical_study(pathlib.Path(virtual))
    return {
        "Model": (roadbrdf.Model, dict(name="lambert", options=None)),
        "Model.evaluate": (lambert.evaluate, dict(theta_i=30, phi_i=0, theta_r=30, phi_r=180, params=None)),
        "Dataset": (roadbrdf.Dataset, dict(angles=[[0, 0, 30, 180]], wavelengths=[500.0], brdf=[[0.1]])),
        "read_dataset": (roadbrdf.read_dataset, dict(path=data)),
        "write_dataset": (roadbrdf.write_dataset, dict(dataset=dataset, path=os.path.join(folder, "out.csv"))),
        "check": (roadbrdf.check, dict(path=data)),
        "read_fit": (roadbrdf.read_fit, dict(path=fit, model=None)),
        "params": (roadbrdf.params, dict(fit_file=fit)),
        "fit": (roadbrdf.fit, dict(data=data, models="lambert", multistart=1, threads=1)),
        "rtable": (roadbrdf.rtable, dict(model=lambert, params={"albedo": 0.3})),
        "albedo": (roadbrdf.albedo, dict(model=lambert, params={"albedo": 0.3}, sun_zenith=30)),
        "mix": (roadbrdf.mix, dict(formulation=formulation, method="areal")),
        "flat_surface": (roadbrdf.flat_surface, dict(model_or_fit="lambert", params={"albedo": 0.3}, cells=8,
                                                     cell_mm=0.5)),
        "gaussian_slope_surface": (roadbrdf.gaussian_slope_surface,
                                   dict(model_or_fit="lambert", sigma_rad=0.2, params={"albedo": 0.3}, cells=32,
                                        cell_mm=0.5, seed=1)),
        "read_surface": (roadbrdf.read_surface, dict(path=surface_file)),
        "render": (roadbrdf.render, dict(surface=flat, theta_i=30, phi_i=0, theta_r=30, phi_r=180, **small)),
        "render_albedo": (roadbrdf.render_albedo, dict(surface=flat, sun_zenith=30, white_sky_nodes=2, **small)),
        "road_to_zenith_azimuth": (roadbrdf.road_to_zenith_azimuth, dict(gamma=30, alpha=1, beta=0, delta=0)),
        "read_rtable": (roadbrdf.read_rtable, dict(path=table)),
        "spectral_model_from_fit": (roadbrdf.spectral_model_from_fit, dict(fit_result=fitted, model=None)),
        "surface": (roadbrdf.surface, dict(formulation_path=os.path.join(virtual, "base.json"), size_mm=12.0,
                                           cell_mm=0.4, seed=1)),
        # Request-contract functions (f(*args, **kwargs), fields from the library's table): every keyword of
        # the base call is swept.
        "luminaire": (roadbrdf.luminaire, dict(file=os.path.join(LIGHTING, "road.ldt"))),
        "lighting": (roadbrdf.lighting, dict(installation=os.path.join(LIGHTING, "installation.json"),
                                             target_class="M4", operating_hours=4000.0)),
        "marking": (roadbrdf.marking, dict(source="lambert", parameters=["albedo=0.6"], illumination_angle=1.24)),
        "export": (roadbrdf.export, dict(source="lambert", parameters=["albedo=0.3"], format="csv",
                                         wavelengths="550", theta_i="0:60:30", theta_r="0:60:30", phi="0:180:90",
                                         output=os.path.join(folder, "grid.csv"))),
        "evaluate": (roadbrdf.evaluate, dict(model="lambert", parameters=["albedo=0.3"], theta_i=30, phi_i=0,
                                             theta_r=30, phi_r=180)),
        "simulate": (roadbrdf.simulate, dict(model="lambert", parameters=["albedo=0.3"],
                                             grid=GRID,
                                             wavelengths="500", output=os.path.join(folder, "sim.csv"))),
        "resample": (roadbrdf.resample, dict(data=data, wavelengths="500:600:100",
                                             output=os.path.join(folder, "resampled.csv"))),
    }


def swept_parameters(function, base):
    """(name, inspect.Parameter) of the arguments to sweep: a function's signature or, for a request-contract
    function (a pybind11 function of *args and **kwargs, whose keywords are its request's fields), the keywords
    of its base call and an unknown keyword."""
    try:
        parameters = list(inspect.signature(function).parameters.items())
    except ValueError:  # a builtin without a signature line
        parameters = [("args", inspect.Parameter("args", inspect.Parameter.VAR_POSITIONAL)),
                      ("kwargs", inspect.Parameter("kwargs", inspect.Parameter.VAR_KEYWORD))]
    if [p.kind for _, p in parameters] == [inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD]:
        parameters = [(k, inspect.Parameter(k, inspect.Parameter.KEYWORD_ONLY)) for k in base]
        parameters.append(("kwargs", inspect.Parameter("kwargs", inspect.Parameter.VAR_KEYWORD)))
    return parameters


# Counts that only the library's requests bound (their limits and tests are those of the C++ requests: fit
# multistart, render samples); the sweep leaves 10**9 out for them so that it never starts such work.
LIBRARY_COUNT_LIMITS = {("fit", "multistart"), ("fit", "max_iterations"), ("render", "samples"),
                        ("render", "max_samples"), ("render_albedo", "samples"), ("render_albedo", "max_samples"),
                        ("mix", "folds"), ("albedo", "nodes"), ("surface", "size_mm")}

def sweep(calls, skipped=lambda name, argument, label: False):
    """Every base call with one argument at a time replaced by each bad value: the calls that raised anything
    but TypeError or ValueError (InputError is a ValueError), as "name(argument=label): error" lines."""
    wrong = []
    for name, (function, base) in calls.items():
        function(**base)  # the valid call works
        for argument, parameter in swept_parameters(function, base):
            if parameter.kind in (parameter.VAR_POSITIONAL,):
                continue
            for label, value in BAD_VALUES.items():
                if skipped(name, argument, label):
                    continue
                kwargs = dict(base)
                if parameter.kind == parameter.VAR_KEYWORD:
                    kwargs["unknown_option"] = value
                else:
                    kwargs[argument] = value
                try:
                    function(**kwargs)
                except (TypeError, ValueError):
                    pass
                except BaseException as e:  # noqa: BLE001 - what the test looks for
                    wrong.append(f"{name}({argument}={label}): {type(e).__name__}: {str(e)[:120]}")
    return wrong


def run_sweep(module, *arguments):
    """``module``.base_calls(*arguments) swept (``module``.skipped, if any, leaves values out) in a child
    process whose address space is bounded; returns the wrong calls."""
    here = os.path.dirname(os.path.abspath(__file__))
    script = textwrap.dedent(f"""
        import resource, sys, json, warnings
        resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
        sys.path.insert(0, {here!r})
        warnings.simplefilter("ignore")
        import test_bad_arguments as t
        import {module} as m
        calls = m.base_calls(*sys.argv[1:])
        print(json.dumps(t.sweep(calls, getattr(m, "skipped", lambda *a: False))))
    """)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.dirname(os.path.dirname(roadbrdf.__file__)),
                                                       os.environ.get("PYTHONPATH", "")]))
    result = subprocess.run([sys.executable, "-c", script, *map(str, arguments)], capture_output=True, text=True,
                            cwd=arguments[0], env=env, timeout=1200)
    assert result.returncode == 0, result.stderr[-3000:]
    return json.loads(result.stdout.strip().splitlines()[-1])


def skipped(name, argument, label):
    return label == "10**9" and (name, argument) in LIBRARY_COUNT_LIMITS


def test_bad_values_of_every_argument_raise_input_or_type_errors(tmp_path):
    wrong = run_sweep("test_bad_arguments", tmp_path)
    assert wrong == [], "\n".join(wrong)


@pytest.mark.parametrize("call, argument", [
    (lambda: roadbrdf.Model("lambert", options="x"), "options"),
    (lambda: roadbrdf.albedo(model=None), "model"),
    (lambda: roadbrdf.rtable(model=None), "model"),
    (lambda: roadbrdf.write_dataset(None, "out.csv"), "dataset"),
    (lambda: roadbrdf.flat_surface("lambert", params="x"), "params"),
    (lambda: roadbrdf.flat_surface("lambert", {"albedo": 0.3}, cells=math.inf), "cells"),
    (lambda: roadbrdf.gaussian_slope_surface("lambert", 0.2, {"albedo": 0.3}, cells=8, seed=math.inf), "seed"),
])
def test_the_audited_calls_name_their_argument(call, argument):
    with pytest.raises((roadbrdf.InputError, TypeError)) as error:
        call()
    assert argument in str(error.value)


def test_render_samples_inf_is_an_input_error():
    flat = roadbrdf.flat_surface("lambert", {"albedo": 0.3}, cells=8, cell_mm=0.5)
    with pytest.raises(roadbrdf.InputError, match="samples"):
        roadbrdf.render(flat, 30, 0, 30, 180, samples=math.inf)


def test_the_sweep_covers_every_public_function():
    # A public function added later must get a base call here (classes with their own tests excepted).
    covered = {"Model", "Dataset", "read_dataset", "write_dataset", "check", "read_fit", "params", "fit", "rtable",
               "albedo", "mix", "flat_surface", "gaussian_slope_surface", "read_surface", "render", "render_albedo",
               "road_to_zenith_azimuth", "read_rtable", "spectral_model_from_fit", "surface", "luminaire", "lighting",
               "marking", "export", "evaluate", "simulate"}
    covered |= {"resample"}
    # Types, functions without arguments, study (test_study_robustness.py), and the readers of third-party and
    # instrument files, mix_calibrate and Surface's methods (swept by test_bad_arguments_readers.py).
    elsewhere = {"InputError", "SpectralModel", "RTable", "FitResult", "ModelFit", "AlbedoResult", "Surface",
                 "InstrumentSpectrum", "models", "model_names", "model_aliases", "data_directory", "study",
                 "read_curet", "read_alta", "mix_calibrate", "read_instrument", "instrument_dataset", "read_manifest",
                 "calibrate_manifest", "read_usgs", "usgs_dataset", "Result", "Diagnostic", "RoadbrdfWarning",
                 "calibrate", "convert"}
    public = {n for n in roadbrdf.__all__ if callable(getattr(roadbrdf, n))}
    assert public - covered - elsewhere == set()
    assert all(swept_parameters(getattr(roadbrdf, n), {}) for n in covered)
