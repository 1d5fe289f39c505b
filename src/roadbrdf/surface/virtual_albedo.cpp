#include "roadbrdf/surface/virtual_albedo.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/core/quadrature.h"

namespace roadbrdf::surface {

VirtualAlbedo render_albedo(const HeightField& field, const std::vector<double>& sun_zenith_deg,
                            const std::vector<double>& wavelengths, const RenderSettings& request_settings,
                            int white_sky_nodes) {
  if (sun_zenith_deg.empty() && white_sky_nodes <= 0) throw InputError("render albedo: no sun zenith angle");
  for (double t : sun_zenith_deg) {
    if (!(t >= 0.0 && t < 90.0)) {
      throw InputError("render albedo: sun zenith " + std::to_string(t) + " deg is outside [0, 90)");
    }
  }
  if (wavelengths.empty()) throw InputError("render albedo: no wavelength");
  for (std::size_t k = 1; k < wavelengths.size(); ++k) {
    if (!(wavelengths[k] > wavelengths[k - 1])) throw InputError("render albedo: wavelengths must increase");
  }
  const std::size_t m = wavelengths.size();
  // Progress in estimates (one per sun zenith and white-sky node), not in the blocks of each.
  RenderSettings settings = request_settings;
  settings.progress = nullptr;
  ProgressCounter progress(request_settings.progress,
                           sun_zenith_deg.size() + static_cast<std::size_t>(std::max(white_sky_nodes, 0)));
  Renderer renderer(field, load_materials(field, wavelengths), m);
  VirtualAlbedo out;
  out.wavelengths = wavelengths;
  out.sun_zenith_deg = sun_zenith_deg;
  // Random streams: black-sky angle k uses stream k, white-sky node j stream 1000000 + j, so every
  // estimate is independent and reproducible.
  for (std::size_t k = 0; k < sun_zenith_deg.size(); ++k) {
    const Estimate e = renderer.directional_albedo(deg_to_rad(sun_zenith_deg[k]), 0.0, settings, k);
    out.black_sky.push_back(e.mean);
    out.black_sky_error.push_back(e.standard_error);
    out.paths += e.paths;
    out.converged.push_back(e.converged);
    progress.add();
  }
  if (white_sky_nodes > 0) {
    const QuadratureRule rule = gauss_legendre(white_sky_nodes, 0.0, 1.0);
    out.white_sky.assign(m, 0.0);
    std::vector<double> variance(m, 0.0);
    for (std::size_t j = 0; j < rule.nodes.size(); ++j) {
      const double mu = rule.nodes[j];
      const double weight = 2.0 * rule.weights[j] * mu;
      const Estimate e = renderer.directional_albedo(std::acos(mu), 0.0, settings, 1000000 + j);
      for (std::size_t w = 0; w < m; ++w) {
        out.white_sky[w] += weight * e.mean[w];
        variance[w] += sqr(weight * e.standard_error[w]);
      }
      out.paths += e.paths;
      out.converged.push_back(e.converged);
      progress.add();
    }
    out.white_sky_error.resize(m);
    for (std::size_t w = 0; w < m; ++w) out.white_sky_error[w] = std::sqrt(variance[w]);
    out.white_sky_nodes = white_sky_nodes;
  }
  progress.finish();
  return out;
}

void write_virtual_albedo(const std::string& path, const VirtualAlbedo& albedo, const std::string& surface_name) {
  const bool white_sky = albedo.white_sky_nodes > 0;
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# virtual albedo of " << surface_name << " (virtual gonioreflectometer); dimensionless reflectances, "
      << "Monte Carlo standard errors; sun azimuth 0 in the sample frame";
  if (white_sky) out << "; white-sky by " << albedo.white_sky_nodes << "-point Gauss-Legendre in cos(theta)";
  out << "\nwavelength_nm";
  if (white_sky) out << ",white_sky,white_sky_error";
  for (double z : albedo.sun_zenith_deg) out << fmt::format(",black_sky_{:g}deg,black_sky_error_{:g}deg", z, z);
  out << "\n";
  for (std::size_t w = 0; w < albedo.wavelengths.size(); ++w) {
    out << fmt::format("{:g}", albedo.wavelengths[w]);
    if (white_sky) out << fmt::format(",{:.8f},{:.2e}", albedo.white_sky[w], albedo.white_sky_error[w]);
    for (std::size_t k = 0; k < albedo.sun_zenith_deg.size(); ++k) {
      out << fmt::format(",{:.8f},{:.2e}", albedo.black_sky[k][w], albedo.black_sky_error[k][w]);
    }
    out << "\n";
  }
  file.commit();
}

nlohmann::json VirtualAlbedo::to_json() const {
  return {{"wavelengths", wavelengths},
          {"sun_zenith", sun_zenith_deg},
          {"black_sky", black_sky},
          {"black_sky_error", black_sky_error},
          {"white_sky", white_sky},
          {"white_sky_error", white_sky_error},
          {"white_sky_nodes", white_sky_nodes},
          {"paths", paths},
          {"converged", converged}};
}

}  // namespace roadbrdf::surface
