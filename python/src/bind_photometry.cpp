// Python bindings of road photometry: r-tables and their summary figures.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/end_member_cache.h"
#include "roadbrdf/mixing/mix_request.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_coverage.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/photometry/rtable_request.h"
#include "roadbrdf/spectra/cie.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

using namespace roadbrdf::photometry;
using Array = DoubleArray;

py::dict rtable_to_dict(const RTable& t, std::optional<double> declared_q0 = std::nullopt) {
  py::dict d;
  d["name"] = t.name;
  d["alpha_deg"] = t.alpha_deg;
  Array r({static_cast<py::ssize_t>(kRows), static_cast<py::ssize_t>(kColumns)});
  double* out = r.mutable_data();
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) out[i * kColumns + j] = t.r(i, j);
  }
  d["r"] = r;  // plain r [sr^-1], NaN = missing
  d["beta_deg"] = std::vector<double>(standard_beta_deg().begin(), standard_beta_deg().end());
  d["tan_gamma"] = std::vector<double>(standard_tan_gamma().begin(), standard_tan_gamma().end());
  auto figure = [&](auto f) -> py::object {
    try {
      return py::float_(f());
    } catch (const InputError&) {
      return py::none();
    }
  };
  d["Q0"] = figure([&] { return q0(t); });
  d["S1"] = figure([&] { return s1(t); });
  d["S2"] = figure([&] { return s2(t); });
  d["Qd"] = figure([&] { return qd(t); });
  if (!d["S1"].is_none()) {
    const double s = d["S1"].cast<double>();
    d["class"] = classify(s, ClassSystem::R).name;
    d["classes"] =
        py::dict(py::arg("R") = classify(s, ClassSystem::R).name, py::arg("N") = classify(s, ClassSystem::N).name,
                 py::arg("C") = classify(s, ClassSystem::C).name);
  } else {
    d["class"] = py::none();
  }
  d["declared_q0"] = declared_q0 ? py::object(py::float_(*declared_q0)) : py::object(py::none());
  d["uncertainty"] = py::none();  // a table alone has no covariance (report_to_dict sets a fit's)
  return d;
}

RTable rtable_from_array(const Array& r, const std::string& name, double alpha_deg) {
  if (r.ndim() != 2 || r.shape(0) != static_cast<py::ssize_t>(kRows) ||
      r.shape(1) != static_cast<py::ssize_t>(kColumns)) {
    throw InputError("r must be a 29 x 20 array (tan gamma rows, beta columns)");
  }
  RTable t;
  t.name = name;
  t.alpha_deg = alpha_deg;
  t.scaled.resize(kRows * kColumns);
  for (std::size_t k = 0; k < kRows * kColumns; ++k) t.scaled[k] = r.data()[k] * kRScale;
  return t;
}

RTableRequest request_from(double alpha, const std::string& illuminant, std::optional<double> wavelength,
                           std::optional<std::pair<double, double>> band, const std::string& q0_region,
                           const std::string& class_system) {
  RTableRequest request;
  request.alpha = alpha;
  request.illuminant = illuminant;
  request.wavelength = wavelength;
  request.band = band;
  request.q0_region = q0_region;
  request.class_system = class_system;
  return request;
}

// The library's report (photometry/rtable_request.h) as the Python dict: the table's figures, the
// report's notes (the first as "note") and its warnings as UserWarning, as the command line prints them.
py::dict report_to_dict(const RTableReport& report) {
  py::dict d = rtable_to_dict(report.table, report.declared_q0);
  d["q0_region"] = report.q0_region;
  d["Q0"] = report.summary.q0;
  d["class"] = report.chosen.name;
  d["class_system"] = report.class_system;
  d["coverage"] = json_to_python(report.coverage.to_json());
  d["extrapolated"] = report.coverage.extrapolated();  // no standard-region cell measured: no class probability
  d["uncertainty"] = json_to_python(report.uncertainty_json());  // None without a fit's covariance
  d["weighting"] = json_to_python(report.weighting);
  d["notes"] = report.notes;
  d["warnings"] = report.warnings;
  d["note"] = report.notes.empty() ? py::object(py::none()) : py::object(py::str(report.notes.front()));
  // Where the table came from, where it was written and its comparison, as in `roadbrdf rtable --json`.
  const nlohmann::json j = report.to_json();
  for (const char* key : {"source", "output", "comparison"}) {
    if (j.contains(key)) d[key] = json_to_python(j.at(key));
  }
  for (const std::string& warning : report.warnings) {
    py::module_::import("roadbrdf.core").attr("warn_at_caller")(warning);
  }
  return d;
}

}  // namespace

void bind_photometry(py::module_& m) {
  // The request of `roadbrdf rtable` (its field table, photometry/rtable_task.cpp): a model name, a
  // FIT.json or MIX.json as `model`, or an r-table file as `import_file`.
  m.def(
      "rtable",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<RTableRequest>(args, kwargs);
        return report_to_dict(rtable(request));
      },
      request_docstring<RTableRequest>(
          "Road-photometry r-table and its figures, as `roadbrdf rtable --json` computes them.",
          "Returns a dict (roadbrdf.RTable): the table, its figures, notes and warnings; warnings are also issued.")
          .c_str());
  // The same request for a model the caller holds (a Model as a constant spectral model, or a
  // SpectralModel): the keywords of the other fields.
  m.def("rtable_spectral", [](const SpectralModel& model, const py::kwargs& kwargs) {
    return report_to_dict(rtable(model, request_from_arguments<RTableRequest>(py::args(), kwargs)));
  });
  // The same report for method `index` of a mix run, from its end-members' values at the table's
  // geometries shared through `cache` (mixing/end_member_cache.h; the design studies' fast path). The
  // request's fields are keywords only, named as RTableRequest's (rtable_request.h).
  m.def(
      "mixture_rtable_report",
      [](const mixing::MixRun& run, std::size_t index, mixing::EndMemberCache& cache, double alpha,
         const std::string& illuminant, std::optional<double> wavelength, std::optional<std::pair<double, double>> band,
         const std::string& q0_region, const std::string& class_system) {
        const RTableRequest request = request_from(alpha, illuminant, wavelength, band, q0_region, class_system);
        RTableReport report;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          report = mixing::mixture_rtable(run.content.results.at(index), request, cache);
        }
        return report_to_dict(report);
      },
      py::arg("run"), py::arg("index"), py::arg("cache"), py::kw_only(), py::arg("alpha") = 1.0,
      py::arg("illuminant") = "", py::arg("wavelength") = py::none(), py::arg("band") = py::none(),
      py::arg("q0_region") = "standard", py::arg("class_system") = "R");
  m.def(
      "read_rtable",
      [](const std::string& path, std::optional<std::string> format, double alpha, double scale) {
        std::optional<RTableFormat> f;
        if (format) f = rtable_format_from_name(*format);
        const RTableFile file = read_rtable(path, f, alpha, scale);
        return rtable_to_dict(file.table, file.declared_q0);
      },
      py::arg("path"), py::arg("format") = py::none(), py::arg("alpha") = 1.0, py::arg("scale") = kRScale);
  m.def(
      "write_rtable",
      [](const Array& r, const std::string& name, double alpha, const std::string& path, const std::string& format) {
        write_rtable_file(path, rtable_from_array(r, name, alpha), rtable_format_from_name(format));
      },
      py::arg("r"), py::arg("name"), py::arg("alpha"), py::arg("path"), py::arg("format"));
  m.def("rtable_summary", [](const Array& r, const std::string& name, double alpha) {
    return rtable_to_dict(rtable_from_array(r, name, alpha));
  });
}

}  // namespace roadbrdf::python
