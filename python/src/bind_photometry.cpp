// Python bindings of road photometry: r-tables and their summary figures.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>

#include "binding.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/spectra/cie.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_coverage.h"
#include "roadbrdf/photometry/rtable_io.h"

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
    d["classes"] = py::dict(py::arg("R") = classify(s, ClassSystem::R).name,
                            py::arg("N") = classify(s, ClassSystem::N).name,
                            py::arg("C") = classify(s, ClassSystem::C).name);
  } else {
    d["class"] = py::none();
  }
  d["declared_q0"] = declared_q0 ? py::object(py::float_(*declared_q0)) : py::object(py::none());
  return d;
}

RTable rtable_from_array(const Array& r, const std::string& name, double alpha_deg) {
  if (r.ndim() != 2 || r.shape(0) != static_cast<py::ssize_t>(kRows) || r.shape(1) != static_cast<py::ssize_t>(kColumns)) {
    throw InputError("r must be a 29 x 20 array (tan gamma rows, beta columns)");
  }
  RTable t;
  t.name = name;
  t.alpha_deg = alpha_deg;
  t.scaled.resize(kRows * kColumns);
  for (std::size_t k = 0; k < kRows * kColumns; ++k) t.scaled[k] = r.data()[k] * kRScale;
  return t;
}

SpectralWeighting weighting_from(const std::string& illuminant, std::optional<double> wavelength,
                                 std::optional<std::pair<double, double>> band) {
  SpectralWeighting w;
  if (wavelength && band) throw InputError("give either wavelength or band, not both");
  if (wavelength) {
    w.kind = SpectralWeighting::Kind::wavelength;
    w.wavelength_nm = *wavelength;
  } else if (band) {
    w.kind = SpectralWeighting::Kind::band;
    w.band_lo_nm = band->first;
    w.band_hi_nm = band->second;
  } else {
    w.illuminant = illuminant_from_name(illuminant);
  }
  return w;
}

}  // namespace

void bind_photometry(py::module_& m) {
  m.def(
      "rtable_from_model",
      [](const Model& model, const std::vector<double>& parameters, double alpha) {
        check_parameters(model.description(), parameters);
        return rtable_to_dict(compute_rtable(model, parameters, alpha));
      },
      py::arg("model"), py::arg("parameters"), py::arg("alpha") = 1.0);
  m.def(
      "rtable_from_spectral",
      [](const SpectralModel& model, double alpha, const std::string& illuminant, std::optional<double> wavelength,
         std::optional<std::pair<double, double>> band) {
        std::string note;
        const SpectralWeighting w = effective_weighting(model, weighting_from(illuminant, wavelength, band), &note);
        const RTable table = compute_rtable(model, w, alpha);
        py::dict d = rtable_to_dict(table);
        d["note"] = note.empty() ? py::object(py::none()) : py::object(py::str(note));
        // The command line's "coverage" (photometry/rtable_coverage.h); its WARNING notes as UserWarning.
        const RTableCoverage coverage = rtable_coverage(table, model.coverage());
        d["coverage"] = json_to_python(coverage.to_json());
        for (const std::string& n : coverage.notes()) {
          if (n.rfind("WARNING: ", 0) == 0) {
            py::module_::import("warnings").attr("warn")(n.substr(9), py::module_::import("builtins").attr("UserWarning"), 2);
          }
        }
        return d;
      },
      py::arg("model"), py::arg("alpha") = 1.0, py::arg("illuminant") = "A", py::arg("wavelength") = py::none(),
      py::arg("band") = py::none());
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
