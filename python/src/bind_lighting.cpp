// Python bindings of the lighting module: each task through the request contract
// (python/src/request_kwargs.h), its result as a roadbrdf.Result with the same JSON as the command
// line's --json.
#include <pybind11/pybind11.h>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/lighting/luminaire_request.h"

namespace roadbrdf::python {

void bind_lighting(pybind11::module_& m) {
  namespace py = pybind11;
  m.def(
      "luminaire",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<lighting::LuminaireRequest>(args, kwargs);
        const lighting::LuminaireSummary result = lighting::luminaire_summary(request);
        return python_result(result.to_json(), result.diagnostics, result.summary_text());
      },
      request_docstring<lighting::LuminaireRequest>(
          "Summary of a luminaire photometry file (EULUMDAT .ldt or IES LM-63 .ies): name, flux, maximum "
          "intensity and its direction, DLOR, ULOR, symmetry, and the principal planes in cd/klm.")
          .c_str());
}

}  // namespace roadbrdf::python
