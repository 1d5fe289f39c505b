// roadbrdf.marking and roadbrdf.export: the requests of photometry/marking_request.h and
// io/model_export.h, made by the request contract (request_kwargs.h): the same fields, rules and
// messages as `roadbrdf marking` and `roadbrdf export`.
#include <pybind11/pybind11.h>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/io/model_export.h"
#include "roadbrdf/lighting/marking_contrast.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/photometry/marking_request.h"

namespace roadbrdf::python {

void bind_marking(pybind11::module_& m) {
  namespace py = pybind11;
  m.def(
      "marking",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<photometry::MarkingRequest>(args, kwargs);
        check_request_files(request);
        const photometry::MarkingResult result = lighting::marking(request);
        return python_result(result.to_json(), result.diagnostics, result.summary_text());
      },
      request_docstring<photometry::MarkingRequest>(
          "Road-marking photometry (EN 1436): R_L at the 30 m geometry, Q_d, beta and their classes; the "
          "contrast against a pavement.")
          .c_str());
  m.def(
      "export",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<ExportRequest>(args, kwargs);
        check_request_files(request);
        const ExportResult result = export_model(request);
        return python_result(result.to_json(), result.diagnostics, result.summary_text());
      },
      request_docstring<ExportRequest>(
          "A model's BRDF on a grid as an OpenMATERIAL 3D look-up table, a CSV dataset or ALTA text data.")
          .c_str());
}

}  // namespace roadbrdf::python
