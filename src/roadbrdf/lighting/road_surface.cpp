#include "roadbrdf/lighting/road_surface.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/modelfile/model_by_name.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace roadbrdf::lighting {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void scale_table(photometry::RTable& table, double q0_wanted) {
  const double factor = q0_wanted / photometry::q0(table);
  for (double& v : table.scaled) v *= factor;
}

}  // namespace

SpectralModel model_with_parameters(const SurfaceSpec& spec) {
  const std::map<std::string, double> parameters(spec.parameters.begin(), spec.parameters.end());
  return spectral_model_with(spec.name, parameters, spec.options);
}

std::vector<double> RoadSurface::brdf(const std::vector<Geometry>& geometries) const {
  if (!model) throw std::logic_error("RoadSurface::brdf without a BRDF");
  if (weighted_brdf) return weighted_brdf(*model, weighting, geometries);
  return photometry::weighted_brdf(*model, weighting, geometries);
}

RoadSurface surface_from_table(photometry::RTable table, std::string description) {
  RoadSurface surface;
  surface.description = std::move(description);
  surface.table = std::move(table);
  surface.q0 = photometry::q0(surface.table);
  if (surface.table.defined(0, 0) && surface.table.defined(8, 0) && surface.table.at(0, 0) != 0.0) {
    surface.s1 = photometry::s1(surface.table);
    surface.road_class = photometry::classify(surface.s1).name;
  }
  return surface;
}

RoadSurface surface_from_model(const SpectralModel& model, std::string description, Diagnostics& diagnostics) {
  // The r-table exactly as `roadbrdf rtable` computes it (photometric weighting under CIE A).
  const photometry::RTableReport report = photometry::rtable_report(model, photometry::RTableRequest{});
  for (const std::string& note : report.notes) diagnostics.note("rtable", note);
  for (const std::string& warning : report.warnings) diagnostics.warn("rtable", warning);
  RoadSurface surface = surface_from_table(report.table, std::move(description));
  surface.model = model;
  photometry::SpectralWeighting w;
  surface.weighting = photometry::effective_weighting(model, w);
  return surface;
}

RoadSurface make_surface(const SurfaceSpec& spec, Diagnostics& diagnostics) {
  switch (spec.kind) {
    case SurfaceSpec::Kind::standard_table: {
      const std::string file = data_file("third-party/rtables/" + lower(spec.name) + "-table.dat");
      photometry::RTable table = photometry::read_rtable(file, photometry::RTableFormat::radiance).table;
      std::string description = "CIE " + spec.name;
      if (spec.q0) {
        scale_table(table, *spec.q0);
        description += fmt::format(" scaled to Q0 = {:g} sr^-1", *spec.q0);
      }
      table.name = description;
      return surface_from_table(std::move(table), description);
    }
    case SurfaceSpec::Kind::rtable_file: {
      photometry::RTable table = photometry::read_rtable(spec.path).table;
      std::string description = spec.path;
      if (spec.q0) {
        scale_table(table, *spec.q0);
        description += fmt::format(" scaled to Q0 = {:g} sr^-1", *spec.q0);
      }
      return surface_from_table(std::move(table), description);
    }
    case SurfaceSpec::Kind::model_file:
      return surface_from_model(read_spectral_model_file(spec.path, spec.selection), spec.path, diagnostics);
    case SurfaceSpec::Kind::model:
      return surface_from_model(model_with_parameters(spec), spec.name, diagnostics);
  }
  throw std::logic_error("unknown surface kind");
}

double ReflectanceTable::at(double theta) const {
  if (theta <= theta_deg.front()) return reflectance.front();
  if (theta >= theta_deg.back()) return reflectance.back();
  const auto upper = std::upper_bound(theta_deg.begin(), theta_deg.end(), theta);
  const auto i = static_cast<std::size_t>(upper - theta_deg.begin()) - 1;
  const double t = (theta - theta_deg[i]) / (theta_deg[i + 1] - theta_deg[i]);
  return (1.0 - t) * reflectance[i] + t * reflectance[i + 1];
}

ReflectanceTable hemispherical_reflectance(const RoadSurface& surface) {
  if (!surface.model) throw std::logic_error("hemispherical_reflectance without a BRDF");
  if (surface.reflectance) return *surface.reflectance;
  const SpectralModel& model = *surface.model;
  const Model& m = model.model();
  // The parameter sets of the photometric reduction and their weights (one set, weight 1, for a
  // wavelength-independent model), as the r-table uses them.
  std::vector<double> params, weights;
  if (model.is_spectral()) {
    const photometry::WeightedWavelengths w = photometry::weighted_wavelengths(model, surface.weighting);
    for (double wavelength : w.wavelengths) {
      const std::vector<double> p = model.parameters_at(wavelength);
      params.insert(params.end(), p.begin(), p.end());
    }
    weights = w.weights;
  } else {
    params = model.parameter_table();
    weights = {1.0};
  }
  const std::size_t sets = weights.size();
  const bool isotropic = albedo::is_isotropic(m, params.data(), sets);
  ReflectanceTable table;
  table.theta_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80, 85, 89};
  albedo::QuadratureSettings settings;
  settings.tolerance = 1e-4;  // absolute, on a reflectance of order 0.1: 0.1% of the reflected flux
  for (double theta : table.theta_deg) {
    const double rad = deg_to_rad(theta);
    const albedo::SpectralIntegral integral =
        isotropic ? albedo::black_sky(m, params.data(), sets, rad, 0.0, settings)
                  : albedo::black_sky_azimuth_mean(m, params.data(), sets, rad, settings);
    double value = 0.0;
    for (std::size_t k = 0; k < sets; ++k) value += weights[k] * integral.value[k];
    table.reflectance.push_back(value);
    table.max_error = std::max(table.max_error, integral.max_error());
  }
  return table;
}

}  // namespace roadbrdf::lighting
