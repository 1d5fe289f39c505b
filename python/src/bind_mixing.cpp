// Python binding of mixing: a MixRequest (mixing/mix_request.h) from the keyword arguments of
// roadbrdf.mix, and the run as an object; MIX.json is written by the same writer as `roadbrdf mix`.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/calibration.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/mixing/mix_request.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/mixing/residual_file.h"

namespace py = pybind11;

namespace roadbrdf::python {

void bind_mixing(py::module_& m) {
  using mixing::MixRun;
  // Fit files read once, and end-member integrals and r-table values computed once, for many mixes
  // (mixing/end_member_cache.h; the design studies' fast path keeps one per worker process).
  py::class_<mixing::EndMemberCache, std::shared_ptr<mixing::EndMemberCache>>(m, "EndMemberCache")
      .def(py::init<>())
      .def_property_readonly("fits_read", &mixing::EndMemberCache::fits_read)
      .def_property_readonly("integrals_computed", &mixing::EndMemberCache::integrals_computed)
      .def_property_readonly("values_computed", &mixing::EndMemberCache::values_computed);
  py::class_<MixRun, std::shared_ptr<MixRun>>(m, "MixRun")
      .def_property_readonly("notes", [](const MixRun& r) { return r.notes; })
      .def_property_readonly("count", [](const MixRun& r) { return r.content.results.size(); })
      .def("method", [](const MixRun& r, std::size_t i) { return name_of(r.content.results.at(i).method); })
      .def("spectral_model", [](const MixRun& r, std::size_t i) { return *r.content.results.at(i).model; })
      .def(
          "content", [](const MixRun& r) { return json_to_python(mixing::mix_file_json(r.content)); },
          "The MIX.json content as Python objects.")
      .def("table", &MixRun::table, "The report `roadbrdf mix` prints.")
      .def(
          "write", [](const MixRun& r, const std::string& path) { mixing::write_mix_file(path, r.content); },
          py::arg("path"))
      .def(
          "write_residuals",
          [](const MixRun& r, const std::string& path) {
            if (!r.data) throw FieldError("residuals", "needs data (the held-out residuals of a measured mixture)");
            mixing::write_residual_file(path, *r.data, r.content.comparisons);
          },
          py::arg("path"));

  m.def(
      "mix",
      [](const py::args& args, py::kwargs kwargs) {
        // The end-member cache is Python's own argument (the studies keep one per worker), not a field.
        std::shared_ptr<mixing::EndMemberCache> cache;
        if (kwargs.contains("cache")) {
          cache = kwargs["cache"].cast<std::shared_ptr<mixing::EndMemberCache>>();
          PyDict_DelItemString(kwargs.ptr(), "cache");
        }
        // Fit files given as values, by the reference the formulation gives (not a field: the command
        // line has the files).
        std::map<std::string, std::string> fits;
        if (kwargs.contains("fits")) {
          fits = kwargs["fits"].cast<std::map<std::string, std::string>>();
          PyDict_DelItemString(kwargs.ptr(), "fits");
        }
        auto request = request_from_arguments<mixing::MixRequest>(args, kwargs);
        request.end_member_cache = std::move(cache);
        request.fits = std::move(fits);
        std::shared_ptr<MixRun> run;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          run = std::make_shared<MixRun>(mixing::run_mix(request));
          mixing::write_mix_outputs(*run);
        }
        return run;
      },
      request_docstring<mixing::MixRequest>(
          "Predict the BRDF of a road formulation from its components' fits, as `roadbrdf mix` does. The "
          "formulation may be given as a dict, and `fits` gives fit files' JSON texts by the references the "
          "formulation names them with (not read from disk).",
          "Returns the run (roadbrdf.MixResult wraps it); `output` and `residuals` are written.")
          .c_str());
  // Calibrated intimate mixing (mixing/calibration.h): the request of `roadbrdf mix-calibrate` (its field
  // table, mixing/cross_section_file.cpp); returns the calibration (the file written to `output` when
  // given) and the report.
  m.def(
      "mix_calibrate",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<mixing::CrossSectionRequest>(args, kwargs);
        mixing::CrossSectionRun run;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          run = mixing::run_cross_section_calibration(request);
        }
        const mixing::CrossSectionCalibration& c = run.content.calibration;
        py::dict factors, errors;
        for (std::size_t i = 0; i < c.end_members.size(); ++i) {
          factors[py::str(c.end_members[i])] = c.factors[i];
          errors[py::str(c.end_members[i])] = c.standard_errors[i];
        }
        py::dict out;
        out["reference"] = c.reference;
        out["factors"] = factors;
        out["standard_errors"] = errors;
        out["mixtures"] = c.mixtures;
        out["rms_uncalibrated"] = c.rms_uncalibrated;
        out["rms_calibrated"] = c.rms_calibrated;
        out["notes"] = c.notes;
        out["table"] = run.table();
        return out;
      },
      request_docstring<mixing::CrossSectionRequest>(
          "Fit effective cross-section factors of the hapke method's end-members, as `roadbrdf mix-calibrate`.",
          "Returns a dict: reference, factors, standard_errors, mixtures, rms_uncalibrated, rms_calibrated, "
          "notes, table.")
          .c_str());
  m.def("read_spectral_model_file", &read_spectral_model_file, py::arg("path"), py::arg("selection") = "");
  // The mixing methods in the library's order, with what the studies need to know of each.
  m.def("mixing_methods", [] {
    py::list methods;
    for (const auto& entry : mixing::kMethodNames) {
      py::dict d;
      d["name"] = std::string(entry.name);
      d["description"] = std::string(entry.description);
      d["needs_data"] = mixing::method_needs_data(entry.value);
      methods.append(d);
    }
    return methods;
  });
}

}  // namespace roadbrdf::python
