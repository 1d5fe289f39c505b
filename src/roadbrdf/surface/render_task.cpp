// The `render` tasks (render_task.h).
#include "roadbrdf/surface/render_task.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf::surface {

namespace {

// The request's files and the materials' fit files are inputs; `output` is never one of them.
void check_render_files(const RenderRequest& request, const HeightField& field, const std::string& surface_name) {
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, RenderRequest::fields(), inputs, outputs);
  if (request.surface.empty() && !surface_name.empty()) inputs.push_back({"`surface`", surface_name});
  for (const auto& m : field.materials) inputs.push_back({"fit of material '" + m.name + "'", m.fit_path});
  check_distinct_files(inputs, outputs);
}

}  // namespace

RenderResult render_grid(const HeightField& field, const std::string& surface_name,
                         const std::vector<Geometry>& geometries, AngleConvention convention,
                         const RenderRequest& request, const ProgressCallback& progress) {
  RenderSettings settings = render_settings(request);
  const DatasetFormat format = parse_name<DatasetFormat>(request.format, "format");
  check_render_files(request, field, surface_name);
  settings.progress = progress;
  RenderResult result;
  result.data = render_dataset(field, geometries, render_wavelengths(request, field), settings, &result.estimates);
  result.data.convention = convention;
  if (!request.output.empty()) write_dataset(result.data, request.output, format);

  long total_paths = 0;
  std::vector<double> worst;
  for (const auto& e : result.estimates) {
    total_paths += e.paths;
    worst.push_back(e.worst_relative_error());
  }
  std::sort(worst.begin(), worst.end());
  const auto quantile = [&](double q) {
    return worst.empty() ? 0.0
                         : worst[static_cast<std::size_t>(std::lround(q * static_cast<double>(worst.size() - 1)))];
  };
  std::string& out = result.summary;
  out = fmt::format("rendered {}: {} geometries x {} wavelengths, {} sampling, acceptance {} deg, {} paths in total\n",
                    surface_name, result.data.geometry_count(), result.data.wavelength_count(), request.sampling,
                    request.acceptance_deg, total_paths);
  out += fmt::format(
      "per-geometry worst relative standard error over wavelengths: median {:.3g}, 90th percentile {:.3g}, max "
      "{:.3g}\n",
      quantile(0.5), quantile(0.9), worst.empty() ? 0.0 : worst.back());
  if (request.target_error) {
    const auto paths = result.data.metadata.find("paths_per_geometry");
    out += fmt::format("adaptive: target {} (or {} sr^-1 for values near 0), paths per geometry {}\n",
                       *request.target_error, request.error_floor,
                       paths == result.data.metadata.end() ? std::string("-") : paths->second);
    std::size_t missed = 0;
    for (std::size_t g = 0; g < result.estimates.size(); ++g) {
      if (result.estimates[g].converged) continue;
      ++missed;
      const Geometry& gg = geometries[g];
      result.diagnostics.warn(
          "target_missed",
          fmt::format("geometry {} ({:g},{:g},{:g},{:g} deg) reached `max_samples` {} with relative standard error "
                      "{:.3g} > `target_error` {}",
                      g + 1, rad_to_deg(gg.theta_i), rad_to_deg(gg.phi_i), rad_to_deg(gg.theta_r), rad_to_deg(gg.phi_r),
                      request.max_samples, result.estimates[g].worst_relative_error(), *request.target_error));
    }
    if (missed > 0) {
      result.diagnostics.warn("target_missed", fmt::format("{} of {} geometries did not reach the target", missed,
                                                           result.estimates.size()));
    }
  }
  if (!request.output.empty()) out += "wrote " + request.output + "\n";
  return result;
}

RenderAlbedoResult render_surface_albedo(const HeightField& field, const std::string& surface_name,
                                         const RenderRequest& request, const ProgressCallback& progress) {
  RenderSettings settings = render_settings(request);
  check_render_files(request, field, surface_name);
  const std::vector<double> wavelengths = render_wavelengths(request, field);
  settings.progress = progress;
  RenderAlbedoResult result;
  result.albedo = render_albedo(field, request.sun_zenith, wavelengths, settings, request.white_sky_nodes);
  const VirtualAlbedo& v = result.albedo;
  if (!request.output.empty()) write_virtual_albedo(request.output, v, surface_name);
  const auto missed = std::count(v.converged.begin(), v.converged.end(), false);
  result.summary = fmt::format("rendered the albedo of {}: {} sun zenith angles{}, {} wavelengths, {} paths in total\n",
                               surface_name, request.sun_zenith.size(),
                               v.white_sky_nodes > 0 ? fmt::format(" + white-sky ({} nodes)", v.white_sky_nodes) : "",
                               wavelengths.size(), v.paths);
  if (missed > 0) {
    result.diagnostics.warn("target_missed",
                            fmt::format("{} albedo estimates reached `max_samples` before the target error", missed));
  }
  if (!request.output.empty()) result.summary += "wrote " + request.output + "\n";
  return result;
}

nlohmann::json RenderResult::to_json() const {
  const std::size_t m = data.wavelength_count();
  nlohmann::json brdf = nlohmann::json::array(), sigma = nlohmann::json::array(), paths = nlohmann::json::array(),
                 converged = nlohmann::json::array();
  for (std::size_t k = 0; k < data.geometry_count(); ++k) {
    brdf.push_back(std::vector<double>(data.brdf.begin() + k * m, data.brdf.begin() + (k + 1) * m));
    sigma.push_back(std::vector<double>(data.sigma.begin() + k * m, data.sigma.begin() + (k + 1) * m));
  }
  for (const Estimate& e : estimates) {
    paths.push_back(e.paths);
    converged.push_back(e.converged);
  }
  return {{"wavelengths", data.wavelengths}, {"brdf", brdf},   {"sigma", sigma},
          {"metadata", data.metadata},       {"paths", paths}, {"converged", converged}};
}

}  // namespace roadbrdf::surface
