// Python binding of the road-lighting calculation: roadbrdf.lighting(installation, surface=...,
// target_class=..., operating_hours=..., map=...), the same request and result as `roadbrdf
// lighting` (lighting/lighting_request.h), made by the request contract (request_kwargs.h).
// The design studies' lighting predictions (roadbrdf.studies) use the same calculation on each
// candidate mixture's BRDF: the installation and its luminaire are read once per process
// (read_lighting_installation), then mixture_lighting evaluates them over the mixture of a mix run.
// Without an end-member cache the surface is made as `roadbrdf lighting INSTALLATION --surface
// MIX.json` makes it (lighting::surface_from_model). With the study's cache (mixing/end_member_cache.h)
// the r-table and the luminance at the true observation angles come from the end-members' values
// kept in the cache (bit for bit the same numbers) and, for a method linear in its
// end-members, the directional-hemispherical reflectance is the luminous (V x CIE A) black-sky albedo
// combined from the end-members' integrals, computed once per process for all the candidates: the
// same quantity within the quadratures' error estimates (both 1e-4) and the difference between the
// albedo's luminous weighting over the fit's bands and the r-table's over the 1 nm grid.
#include <pybind11/pybind11.h>

#include <algorithm>
#include <memory>
#include <string>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/lighting_request.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/lighting/road_surface.h"
#include "roadbrdf/mixing/end_member_cache.h"
#include "roadbrdf/mixing/mix_request.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

// An installation file read with its luminaire, for many surfaces.
struct PreparedInstallation {
  std::string file;  // the installation file, as a LightingRequest names it
  lighting::Installation installation;
  lighting::Luminaire luminaire;
  Diagnostics diagnostics;  // of reading the luminaire file

  double power_w() const {
    const auto& layout = installation.luminaires;
    return layout.power_w ? *layout.power_w : luminaire.power_w;
  }
};

// The road surface of a mixture through the end-member cache (see the top of this file).
lighting::RoadSurface cached_mixture_surface(const mixing::MixResult& mixture, mixing::EndMemberCache& cache,
                                             Diagnostics& diagnostics) {
  photometry::WeightedBrdf brdf = mixing::mixture_weighted_brdf(mixture, cache);
  const photometry::RTableReport report = photometry::rtable_report(*mixture.model, photometry::RTableRequest{}, brdf);
  for (const std::string& note : report.notes) diagnostics.note("rtable", note);
  for (const std::string& warning : report.warnings) diagnostics.warn("rtable", warning);
  lighting::RoadSurface surface = lighting::surface_from_table(report.table, "candidate mixture");
  surface.model = *mixture.model;
  surface.weighting = photometry::effective_weighting(*mixture.model, photometry::SpectralWeighting{});
  surface.weighted_brdf = std::move(brdf);  // the luminance at the true observation angles, the same way
  if (!mixing::method_is_linear(mixture.method)) return surface;
  lighting::ReflectanceTable table;
  table.theta_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80, 85, 89};  // the nodes of hemispherical_reflectance
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = table.theta_deg;
  request.azimuth_mean = true;  // anisotropic models: the luminaires' azimuths vary over the road
  request.illuminant = "A";
  request.tolerance = 1e-4;
  request.uncertainty = false;
  const nlohmann::json albedo = mixing::mixture_albedo(mixture, request, cache);
  const nlohmann::json& luminous = albedo.at("luminous");
  if (luminous.is_null()) return surface;  // no visible bands: the library's own integral says why
  for (const auto& value : luminous.at("black_sky")) table.reflectance.push_back(value.get<double>());
  for (const auto& row : albedo.at("black_sky_error")) {
    for (const auto& e : row) {
      if (e.is_number()) table.max_error = std::max(table.max_error, e.get<double>());
    }
  }
  surface.reflectance = std::move(table);
  return surface;
}

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
        prepared->file = path;
        prepared->installation = lighting::read_installation(path);
        prepared->luminaire = lighting::read_luminaire(prepared->installation.luminaires.file, prepared->diagnostics);
        return prepared;
      },
      py::arg("path"));
  m.def(
      "mixture_lighting",
      [](const mixing::MixRun& run, std::size_t index, const PreparedInstallation& prepared,
         std::shared_ptr<mixing::EndMemberCache> cache, const py::kwargs& kwargs) {
        // The request's keywords other than its files (the installation is read, the surface is the mixture).
        for (const char* given : {"surface", "map"}) {
          if (kwargs.contains(given)) throw FieldError(given, "is not taken here: the surface is the mixture");
        }
        auto fields = py::reinterpret_steal<py::kwargs>(PyDict_Copy(kwargs.ptr()));
        if (!fields) throw py::error_already_set();
        fields["installation"] = prepared.file;
        const auto request = request_from_arguments<lighting::LightingRequest>(py::args(), fields);
        request.validate();
        lighting::LightingOptions options;
        options.target_class = request.target_class;
        options.operating_hours = request.operating_hours;
        lighting::LightingResult result;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          const mixing::MixResult& mixture = run.content.results.at(index);
          Diagnostics diagnostics = prepared.diagnostics;
          const lighting::RoadSurface surface =
              cache ? cached_mixture_surface(mixture, *cache, diagnostics)
                    : lighting::surface_from_model(*mixture.model, "candidate mixture", diagnostics);
          result = lighting::evaluate_installation(prepared.installation, prepared.luminaire, surface, options,
                                                   std::move(diagnostics));
        }
        return json_to_python(result.to_json());
      },
      py::arg("run"), py::arg("index"), py::arg("installation"), py::arg("cache") = py::none(),
      request_docstring<lighting::LightingRequest>(
          "The lighting calculation of a prepared installation (read_lighting_installation) over method `index` "
          "of a mix run, its surface from the end-members kept in `cache` (or from the mixture itself); of the "
          "request's fields, target_class and operating_hours are keywords here.",
          "Returns the document of `roadbrdf lighting --json` as a dict.")
          .c_str());
}

}  // namespace roadbrdf::python
