// Python bindings of measurement I/O: datasets as numpy arrays plus metadata.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/calibrate_request.h"
#include "roadbrdf/io/check_request.h"
#include "roadbrdf/io/convert_request.h"
#include "roadbrdf/io/curet.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_runs.h"
#include "roadbrdf/io/eval_request.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/io/resample_request.h"
#include "roadbrdf/io/simulate_request.h"
#include "roadbrdf/io/usgs.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

using Array = DoubleArray;

Array matrix(const std::vector<double>& values, std::size_t rows, std::size_t columns) {
  Array out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::dict dataset_to_dict(const SpectralDataset& d) {
  const std::size_t n = d.geometry_count();
  Array angles({static_cast<py::ssize_t>(n), py::ssize_t{4}});
  double* a = angles.mutable_data();
  for (std::size_t k = 0; k < n; ++k) {
    const Geometry& g = d.geometries[k];
    a[4 * k + 0] = rad_to_deg(g.theta_i);
    a[4 * k + 1] = rad_to_deg(g.phi_i);
    a[4 * k + 2] = rad_to_deg(g.theta_r);
    a[4 * k + 3] = rad_to_deg(g.phi_r);
  }
  py::dict out;
  out["angles"] = angles;  // theta_i, phi_i, theta_r, phi_r [deg]
  out["wavelengths"] = Array(static_cast<py::ssize_t>(d.wavelengths.size()), d.wavelengths.data());
  out["brdf"] = matrix(d.brdf, n, d.wavelength_count());
  out["sigma"] = d.has_sigma() ? py::object(matrix(d.sigma, n, d.wavelength_count())) : py::object(py::none());
  out["metadata"] = d.metadata;
  out["convention"] = name_of(d.convention);
  out["comments"] = d.comments;
  return out;
}

// The report of `check --json` as a dict, with the command's text under "text".
py::object check_report(const CheckResult& result) {
  nlohmann::json j = result.to_json();
  j["text"] = result.summary_text();
  return json_to_python(j);
}

std::function<void(const std::string&)> python_warning() {
  return [](const std::string& message) { py::module_::import("roadbrdf.core").attr("warn_at_caller")(message); };
}

ManifestOptions manifest_options(const std::string& overlap) {
  ManifestOptions o;
  o.read.overlap = parse_name<OverlapRule>(overlap, "overlap");
  o.warn = python_warning();
  return o;
}

// The instrument readers and manifests (io/instrument.h, io/manifest.h), as `convert` and
// `calibrate --manifest` use them.
void bind_instruments(py::module_& m) {
  m.def(
      "read_instrument",
      [](const std::string& path, const std::string& overlap) {
        const ManifestOptions o = manifest_options(overlap);
        const InstrumentSpectrum s = read_instrument_file(path, o.read);
        for (const auto& note : s.notes) o.warn(note);
        return json_to_python(s.to_json());
      },
      py::arg("path"), py::arg("overlap") = "upper");
  m.def(
      "read_usgs",
      [](const std::string& path, const std::string& wavelengths) {
        return json_to_python(read_usgs_spectrum(path, wavelengths).to_json());
      },
      py::arg("path"), py::arg("wavelengths"));
  // The request of `roadbrdf calibrate` (its field table: io/calibrate_request.cpp), from radiance
  // datasets or a run manifest; roadbrdf.calibrate_manifest is the same request with `manifest` given.
  m.def(
      "calibrate",
      [](const py::args& args, const py::kwargs& kwargs) {
        return dataset_to_dict(calibrate(request_from_arguments<CalibrateRequest>(args, kwargs)));
      },
      request_docstring<CalibrateRequest>(
          "The calibrated BRDF [sr^-1] against a reference panel, as `roadbrdf calibrate` computes it.",
          "Returns the dataset (a dict of roadbrdf.Dataset), also written to `output` when given.")
          .c_str());
}

}  // namespace

SpectralDataset dataset_from_arrays(const DoubleArray& angles, const DoubleArray& wavelengths, const DoubleArray& brdf,
                                    const py::object& sigma, const std::map<std::string, std::string>& metadata,
                                    const std::string& convention) {
  SpectralDataset d;
  if (angles.ndim() != 2 || angles.shape(1) != 4) throw InputError("angles must be an N x 4 array (deg)");
  const auto n = static_cast<std::size_t>(angles.shape(0));
  const auto m = static_cast<std::size_t>(wavelengths.size());
  if (brdf.ndim() != 2 || static_cast<std::size_t>(brdf.shape(0)) != n ||
      static_cast<std::size_t>(brdf.shape(1)) != m) {
    throw InputError("brdf must be an N x M array (N geometries, M wavelengths)");
  }
  const double* a = angles.data();
  for (std::size_t k = 0; k < n; ++k) {
    d.geometries.push_back(geometry_from_degrees(a[4 * k], a[4 * k + 1], a[4 * k + 2], a[4 * k + 3]));
  }
  d.wavelengths.assign(wavelengths.data(), wavelengths.data() + m);
  d.brdf.assign(brdf.data(), brdf.data() + n * m);
  if (!sigma.is_none()) {
    const DoubleArray s = sigma.cast<DoubleArray>();
    if (static_cast<std::size_t>(s.size()) != n * m) throw InputError("sigma must have the shape of brdf");
    d.sigma.assign(s.data(), s.data() + n * m);
  }
  d.metadata = metadata;
  d.convention = parse_name<AngleConvention>(convention, "convention");
  validate_dataset(d);
  return d;
}

void bind_io(py::module_& m) {
  // Every dataset-reading field of the command line (io/dataset_runs.h DatasetReadFields), for one file
  // or several runs of one sample (combined as `convert A.csv B.csv` does).
  m.def(
      "read_dataset",
      [](const std::vector<std::string>& paths, bool allow_missing, const py::kwargs& kwargs) {
        const auto fields = request_from_arguments<DatasetReadFields>(py::args(), kwargs);
        return dataset_to_dict(read_dataset_runs(paths, fields, python_warning(), allow_missing));
      },
      py::arg("paths"), py::arg("allow_missing") = true,
      request_docstring<DatasetReadFields>("A dataset read from one file or several runs of one sample.",
                                           "Returns the dataset as a dict.")
          .c_str());
  // A dataset made in Python under the readers' duplicate policy: repeated geometries are an error, or
  // averaged as duplicate rows of a file are.
  m.def("dataset_duplicate_policy",
        [](const Array& angles, const Array& wavelengths, const Array& brdf, const py::object& sigma,
           const std::map<std::string, std::string>& metadata, const std::string& convention, bool average_duplicates) {
          const SpectralDataset d = dataset_from_arrays(angles, wavelengths, brdf, sigma, metadata, convention);
          return dataset_to_dict(combine_runs({{"dataset", d}}, average_duplicates, python_warning()));
        });
  // The request of `roadbrdf check` (its field table, io/check_request.cpp): the JSON of `check --json`
  // as a dict, plus its text under "text".
  m.def(
      "check_dataset",
      [](const py::args& args, const py::kwargs& kwargs) {
        return check_report(quality_check(request_from_arguments<CheckRequest>(args, kwargs), python_warning()));
      },
      request_docstring<CheckRequest>("The quality report of `roadbrdf check` of a dataset file.",
                                      "Returns the report of `check --json` as a dict, its text under \"text\".")
          .c_str());
  // The same report of a dataset in memory (no reading statistics: the repeatability of averaged
  // duplicates is that of a file's reading); the options are the check's own rows.
  m.def(
      "check_dataset_object",
      [](const Array& angles, const Array& wavelengths, const Array& brdf, const py::object& sigma,
         const std::map<std::string, std::string>& metadata, const std::string& convention, const py::kwargs& kwargs) {
        const auto options = request_from_arguments<CheckOptions>(py::args(), kwargs);
        const SpectralDataset d = dataset_from_arrays(angles, wavelengths, brdf, sigma, metadata, convention);
        return check_report(quality_check(d, options));
      },
      request_docstring<CheckOptions>("The quality report of `roadbrdf check` of a dataset in memory.",
                                      "Returns the report as a dict (file None), its text under \"text\".")
          .c_str());
  // The request of `roadbrdf resample` (its field table, io/resample_request.cpp): the resampled dataset,
  // also written to `output` when given.
  m.def(
      "resample",
      [](const py::args& args, const py::kwargs& kwargs) {
        return dataset_to_dict(resample(request_from_arguments<ResampleRequest>(args, kwargs), python_warning()));
      },
      request_docstring<ResampleRequest>(
          "A dataset band-averaged onto new wavelength intervals, as `roadbrdf resample` makes it.",
          "Returns the dataset (a dict of roadbrdf.Dataset), also written to `output` when given.")
          .c_str());
  m.def("write_dataset",
        [](const Array& angles, const Array& wavelengths, const Array& brdf, const py::object& sigma,
           const std::map<std::string, std::string>& metadata, const std::string& convention,
           const std::vector<std::string>& comments, const std::string& path, const std::string& format) {
          SpectralDataset d = dataset_from_arrays(angles, wavelengths, brdf, sigma, metadata, convention);
          d.comments = comments;
          write_dataset(d, path, parse_name<DatasetFormat>(format, "format"));
        });
  // The requests of `roadbrdf eval` and `roadbrdf simulate` (their field tables: io/eval_request.cpp,
  // io/simulate_request.cpp), positional model first.
  m.def(
      "eval",
      [](const py::args& args, const py::kwargs& kwargs) -> py::object {
        const EvalResult result = evaluate(request_from_arguments<EvalRequest>(args, kwargs));
        if (!result.table) return py::float_(result.brdf.front());
        return py::cast(result.brdf);
      },
      request_docstring<EvalRequest>("A model's BRDF [sr^-1], as `roadbrdf eval` computes it.",
                                     "Returns the BRDF at the four angles (a float), or one per row of the "
                                     "`geometry` file (a list), which is also written to `output` when given.")
          .c_str());
  m.def(
      "simulate",
      [](const py::args& args, const py::kwargs& kwargs) {
        return dataset_to_dict(simulate(request_from_arguments<SimulateRequest>(args, kwargs)));
      },
      request_docstring<SimulateRequest>(
          "A simulated measurement (virtual gonioreflectometer), as `roadbrdf simulate` makes it.",
          "Returns the dataset (a dict of roadbrdf.Dataset), also written to `output` when given.")
          .c_str());
  bind_instruments(m);
  // The request of `roadbrdf convert` (its field table: io/convert_request.cpp), positional inputs first.
  m.def(
      "convert",
      [](const py::args& args, const py::kwargs& kwargs) {
        return dataset_to_dict(convert(request_from_arguments<ConvertRequest>(args, kwargs)));
      },
      request_docstring<ConvertRequest>(
          "A dataset converted from dataset CSV, CUReT, ALTA, instrument, manifest or USGS files, as `roadbrdf "
          "convert` makes it.",
          "Returns the dataset (a dict of roadbrdf.Dataset), also written to `output` when given.")
          .c_str());
}

}  // namespace roadbrdf::python
