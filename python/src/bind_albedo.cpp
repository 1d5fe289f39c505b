// Python binding of albedo: the same request (albedo/report.h, its field table) and report as
// `roadbrdf albedo --json`, the arguments converted by the request contract (request_kwargs.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/mixing/end_member_cache.h"
#include "roadbrdf/mixing/mix_request.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

// The report of compute_albedo (`roadbrdf albedo --json`), kept as the library's document so that
// Python writes it with the command line's writer (albedo::write_albedo_report).
struct AlbedoReport {
  nlohmann::json json;
};

// The request of a call that passes the model itself: the keywords of the other fields.
albedo::AlbedoRequest request_without_source(const py::kwargs& kwargs) {
  for (const char* source : {"model", "parameters", "options", "fit"}) {
    if (kwargs.contains(source)) {
      throw FieldError(source, "is given by the model argument itself (a Model or SpectralModel object)");
    }
  }
  return request_from_arguments<albedo::AlbedoRequest>(py::args(), kwargs);
}

std::shared_ptr<AlbedoReport> report(const SpectralModel& model, const albedo::AlbedoRequest& request) {
  auto result = std::make_shared<AlbedoReport>();
  SigintGuard interruptible;
  py::gil_scoped_release release;
  result->json = albedo::compute_albedo(model, request);
  return result;
}

}  // namespace

void bind_albedo(py::module_& m) {
  py::class_<AlbedoReport, std::shared_ptr<AlbedoReport>>(m, "AlbedoReport")
      .def("content", [](const AlbedoReport& r) { return json_to_python(r.json); })
      .def("table", [](const AlbedoReport& r) { return albedo::albedo_table(r.json); })
      .def("write", [](const AlbedoReport& r, const std::string& path, bool as_json) {
        albedo::write_albedo_report(r.json, path, as_json);
      });
  m.def(
      "albedo",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<albedo::AlbedoRequest>(args, kwargs);
        auto result = std::make_shared<AlbedoReport>();
        SigintGuard interruptible;
        py::gil_scoped_release release;
        result->json = albedo::albedo(request).report;
        return result;
      },
      request_docstring<albedo::AlbedoRequest>(
          "Black-sky, white-sky and blue-sky albedo per wavelength and solar-weighted, as `roadbrdf albedo --json`.")
          .c_str());
  m.def("albedo_spectral", [](const SpectralModel& model, const py::kwargs& kwargs) {
    return report(model, request_without_source(kwargs));
  });
  m.def("albedo_model",
        [](const std::shared_ptr<Model>& model, const std::vector<double>& parameters, const py::kwargs& kwargs) {
          const albedo::AlbedoRequest request = request_without_source(kwargs);
          check_parameters(model->description(), parameters);
          return report(SpectralModel(std::const_pointer_cast<const Model>(model), parameters), request);
        });
  // The same report for method `index` of a mix run, its end-members' integrals shared through
  // `cache` (mixing/end_member_cache.h; the design studies' fast path). The request's other fields are
  // keywords, as roadbrdf.albedo takes them (the model is the mixture itself).
  m.def(
      "mixture_albedo",
      [](const mixing::MixRun& run, std::size_t index, mixing::EndMemberCache& cache, const py::kwargs& kwargs) {
        const albedo::AlbedoRequest request = request_without_source(kwargs);
        nlohmann::json result;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          result = mixing::mixture_albedo(run.content.results.at(index), request, cache);
        }
        return json_to_python(result);
      },
      py::arg("run"), py::arg("index"), py::arg("cache"),
      request_docstring<albedo::AlbedoRequest>(
          "The albedo report of method `index` of a mix run, from its end-members' integrals kept in `cache`; "
          "the model fields (model, parameters, options, fit) are the mixture itself.",
          "Returns the report as a dict (the document of `roadbrdf albedo --json`).")
          .c_str());
}

}  // namespace roadbrdf::python
