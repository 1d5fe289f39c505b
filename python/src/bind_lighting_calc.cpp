// Python binding of the road-lighting calculation: roadbrdf.lighting(installation, surface=...,
// target_class=..., operating_hours=..., map=...), the same request and result as `roadbrdf
// lighting` (lighting/lighting_request.h), made by the request contract (request_kwargs.h).
// The design studies' lighting predictions (roadbrdf.studies) use the same calculation on each
// candidate mixture's BRDF: the installation and its luminaire are read once per process
// (read_lighting_installation), then mixture_lighting evaluates them over the mixture of a mix run,
// its r-table computed as `roadbrdf rtable` does (lighting::surface_from_model), i.e. exactly what
// `roadbrdf lighting INSTALLATION --surface MIX.json` gives for that mixture.
#include <pybind11/pybind11.h>

#include <memory>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/lighting/lighting_request.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/lighting/road_surface.h"
#include "roadbrdf/mixing/mix_request.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

// An installation file read with its luminaire, for many surfaces.
struct PreparedInstallation {
  lighting::Installation installation;
  lighting::Luminaire luminaire;
  Diagnostics diagnostics;  // of reading the luminaire file

  double power_w() const {
    const auto& layout = installation.luminaires;
    return layout.power_w ? *layout.power_w : luminaire.power_w;
  }
};

}  // namespace

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
  py::class_<PreparedInstallation, std::shared_ptr<PreparedInstallation>>(m, "PreparedInstallation")
      .def_property_readonly("power_w", &PreparedInstallation::power_w)
      .def_property_readonly("luminaire_file",
                             [](const PreparedInstallation& p) { return p.installation.luminaires.file; })
      .def_property_readonly("luminaire_name", [](const PreparedInstallation& p) { return p.luminaire.name; });
  m.def(
      "read_lighting_installation",
      [](const std::string& path) {
        auto prepared = std::make_shared<PreparedInstallation>();
        prepared->installation = lighting::read_installation(path);
        prepared->luminaire = lighting::read_luminaire(prepared->installation.luminaires.file, prepared->diagnostics);
        return prepared;
      },
      py::arg("path"));
  m.def(
      "mixture_lighting",
      [](const mixing::MixRun& run, std::size_t index, const PreparedInstallation& prepared,
         const std::string& target_class, double operating_hours) {
        lighting::LightingOptions options;
        options.target_class = target_class;
        options.operating_hours = operating_hours;
        lighting::LightingResult result;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          const mixing::MixResult& mixture = run.content.results.at(index);
          Diagnostics diagnostics = prepared.diagnostics;
          const lighting::RoadSurface surface =
              lighting::surface_from_model(*mixture.model, "candidate mixture", diagnostics);
          result = lighting::evaluate_installation(prepared.installation, prepared.luminaire, surface, options,
                                                   std::move(diagnostics));
        }
        return json_to_python(result.to_json());
      },
      py::arg("run"), py::arg("index"), py::arg("installation"), py::arg("target_class") = "",
      py::arg("operating_hours") = 4000.0);
}

}  // namespace roadbrdf::python
