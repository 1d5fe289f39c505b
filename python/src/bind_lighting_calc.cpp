// Python binding of the road-lighting calculation: roadbrdf.lighting(installation, surface=...,
// target_class=..., operating_hours=..., map=...), the same request and result as `roadbrdf
// lighting` (lighting/lighting_request.h), made by the request contract (request_kwargs.h).
#include <pybind11/pybind11.h>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/lighting/lighting_request.h"

namespace py = pybind11;

namespace roadbrdf::python {

void bind_lighting_calc(py::module_& m) {
  m.def(
      "lighting",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<lighting::LightingRequest>(args, kwargs);
        const lighting::LightingResult result = lighting::lighting(request);
        return python_result(result.to_json(), result.diagnostics, result.summary_text());
      },
      request_docstring<lighting::LightingRequest>(
          "EN 13201 road-lighting calculation of an installation file, as `roadbrdf lighting --json`: "
          "L_av, U_o, U_l, f_TI, R_EI, E_av, the M class, D_P, D_E, the least flux for `target_class`, "
          "the upward light and the luminance at the true observation angles.")
          .c_str());
}

}  // namespace roadbrdf::python
