"""The bad-value sweep of test_bad_arguments.py over the readers of third-party and instrument files, the
mixture calibration and the methods of Surface: the only errors are roadbrdf.InputError (a ValueError),
ValueError or TypeError; never AttributeError, OverflowError, MemoryError, KeyError or a crash."""
import json
import math
import os

import roadbrdf
from test_bad_arguments import run_sweep

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CURET = os.path.join(ROOT, "data", "third-party", "curet")
RETRO = os.path.join(ROOT, "data", "third-party", "retroreflective", "retro-gray-tape.dat")


def _usgs(folder):
    """A two-channel splib07a spectrum and its wavelength file (our own numbers, the format's layout)."""
    wavelengths = os.path.join(folder, "w.txt")
    spectrum = os.path.join(folder, "s.txt")
    with open(wavelengths, "w", encoding="ascii") as f:
        f.write(" splib07a Record=1: wavelengths in micrometres\n 0.5\n 0.6\n")
    with open(spectrum, "w", encoding="ascii") as f:
        f.write(" splib07a Record=2: a grey test spectrum\n 0.25\n 0.30\n")
    return spectrum, wavelengths


def _calibration_pairs(folder):
    """Three measured two-component mixtures of Lambertian end-members (as test_mix_calibrate.py)."""
    wavelengths = [400, 500]
    spectra = {"calcite": [0.80, 0.85], "chlorite": [0.10, 0.20], "epidote": [0.30, 0.25]}
    os.makedirs(os.path.join(folder, "fits"), exist_ok=True)
    for name, albedo in spectra.items():
        with open(os.path.join(folder, "fits", f"{name}.fit.json"), "w", encoding="utf-8") as f:
            json.dump({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                       "fits": [{"model": "lambert", "options": {}, "wavelengths": wavelengths,
                                 "parameters": {"albedo": albedo}}]}, f)
    pairs = []
    for name, parts in (("A", {"calcite": 60, "chlorite": 40}), ("B", {"calcite": 30, "epidote": 70}),
                        ("C", {"chlorite": 50, "epidote": 50})):
        formulation = os.path.join(folder, f"{name}.json")
        with open(formulation, "w", encoding="utf-8") as f:
            json.dump({"format": "roadbrdf-formulation", "version": 1, "name": name, "components": [
                {"name": n, "kind": "aggregate", "mass_percent": wt, "density_g_cm3": 2.7, "d_min_mm": 0.075,
                 "d_max_mm": 0.15, "fit": f"fits/{n}.fit.json"} for n, wt in parts.items()]}, f)
        data = os.path.join(folder, f"{name}.csv")
        with open(data, "w", encoding="utf-8") as f:
            f.write("theta_i,phi_i,theta_r,phi_r,400,500\n")
            for ti in (0, 30, 60):
                rho = [sum(wt / 100 * spectra[n][m] for n, wt in parts.items()) for m in range(2)]
                f.write(f"{ti},0,10,0," + ",".join(repr(r / math.pi) for r in rho) + "\n")
        pairs.append((formulation, data))
    return pairs


def base_calls(folder, instruments):
    """{name: (function, keyword arguments of a valid, quick call)}."""
    spectrum, wavelengths = _usgs(folder)
    geometry = dict(theta_i=30.0, phi_i=0.0, theta_r=0.0, phi_r=0.0)
    flat = roadbrdf.flat_surface("lambert", {"albedo": 0.3}, cells=8, cell_mm=0.5)
    small = dict(max_samples=4096, samples=512, seed=1, threads=1)
    return {
        "read_curet": (roadbrdf.read_curet, dict(abrdf_path=os.path.join(CURET, "abrdf.dat"),
                                                  table_path=os.path.join(CURET, "table.txt"), sample=45)),
        "read_alta": (roadbrdf.read_alta, dict(path=RETRO, wavelength=550.0, assumed_output="INV_STERADIAN",
                                                exclude_grazing=False)),
        "read_usgs": (roadbrdf.read_usgs, dict(path=spectrum, wavelengths=wavelengths)),
        "usgs_dataset": (roadbrdf.usgs_dataset, dict(path=spectrum, wavelengths=wavelengths, **geometry)),
        "read_instrument": (roadbrdf.read_instrument, dict(path=os.path.join(instruments, "run_001.asd"),
                                                            overlap="upper")),
        "instrument_dataset": (roadbrdf.instrument_dataset,
                               dict(path=os.path.join(instruments, "sig_overlap.sig"), quantity="target",
                                    overlap="upper", **geometry)),
        "read_manifest": (roadbrdf.read_manifest, dict(path=os.path.join(instruments, "run.csv"),
                                                        quantity="target", overlap="upper")),
        "calibrate_manifest": (roadbrdf.calibrate_manifest,
                               dict(manifest=os.path.join(instruments, "run.csv"),
                                    panel_reflectance=os.path.join(instruments, "rho.txt"))),
        "calibrate": (roadbrdf.calibrate, dict(manifest=os.path.join(instruments, "run.csv"),
                                               panel_reflectance=os.path.join(instruments, "rho.txt"),
                                               overlap="upper", panel_brf_start=None, format="long")),
        "convert": (roadbrdf.convert, dict(inputs=os.path.join(instruments, "run.csv"), source="manifest",
                                           quantity="reflectance", overlap="upper", to="long", convention="road")),
        "mix_calibrate": (roadbrdf.mix_calibrate, dict(mixtures=_calibration_pairs(folder), reference="calcite")),
        "Surface.write": (flat.write, dict(path=os.path.join(folder, "flat.surface"))),
        "Surface.render": (flat.render, dict(theta_i=30, phi_i=0, theta_r=30, phi_r=180, **small)),
        "Surface.render_albedo": (flat.render_albedo, dict(sun_zenith=30, white_sky_nodes=2, **small)),
    }


def skipped(name, argument, label):
    return label == "10**9" and argument in ("samples", "max_samples")  # bounded by the render request (its tests)


def test_bad_values_of_every_reader_argument_raise_input_or_type_errors(tmp_path, instruments):
    wrong = run_sweep("test_bad_arguments_readers", tmp_path, instruments)
    assert wrong == [], "\n".join(wrong)
