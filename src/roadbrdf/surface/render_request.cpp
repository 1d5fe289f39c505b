#include "roadbrdf/surface/render_request.h"

#include <fmt/core.h>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/surface/materials.h"
#include "roadbrdf/surface/scheduler.h"

namespace roadbrdf::surface {

std::span<const RequestField<RenderRequest>> RenderRequest::fields() {
  using R = RenderRequest;
  // Help texts that list an enumeration's names are made once from its table (core/enum_names.h).
  static const std::string sampling_help =
      "Continuation directions: " + described_names_text<Sampling>() + " (default brdf)";
  static const std::string format_help = "Output CSV layout: " + names_text<DatasetFormat>() + " (default wide)";
  static const RequestField<R> rows[] = {
      {"surface", "SURFACE", "", "SURFACE.json written by `roadbrdf surface`", &R::surface, FileRole::input},
      {"grid", "--grid", "", "Geometry table (CSV, theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta)", &R::grid,
       FileRole::input},
      {"sun_zenith", "--albedo", "deg",
       "Instead of a grid: black-sky albedo at these sun zenith angles (D, D1,D2,... or A:B:STEP) and the white-sky "
       "albedo; writes an albedo CSV like `roadbrdf albedo`",
       &R::sun_zenith},
      {"white_sky_nodes", "--white-sky-nodes", "",
       "Albedo: Gauss-Legendre nodes in cos(theta) for the white-sky albedo (default 8; 0 = none)",
       &R::white_sky_nodes},
      {"wavelengths", "--wavelengths", "nm",
       "Wavelengths START:STOP:STEP or a list (default: those of the materials' fits, or 550)", &R::wavelengths},
      {"samples", "--samples", "", "Paths per geometry, 2 to 2^30 (default 4096 without a target error)", &R::samples},
      {"target_error", "--target-error", "",
       "Adaptive sampling: add paths until every wavelength's standard error is <= this fraction of |BRDF| (e.g. "
       "0.01), at least 1024 paths",
       &R::target_error},
      {"max_samples", "--max-samples", "",
       "Adaptive sampling: at most this many paths per geometry (default 1048576); geometries stopped here are "
       "reported",
       &R::max_samples},
      {"error_floor", "--error-floor", "sr^-1",
       "Adaptive sampling: absolute standard error accepted for BRDF values near 0 (default 1e-5)", &R::error_floor},
      {"sampling", "--sampling", "", sampling_help, &R::sampling},
      {"acceptance_deg", "--acceptance", "deg", "Detector acceptance half-angle (1 or 5 typical; default 1)",
       &R::acceptance_deg},
      {"seed", "--seed", "", "Random seed (default 1); each geometry has its own streams", &R::seed},
      {"threads", "--threads", "", "Threads (default: all cores)", &R::threads},
      {"max_bounces", "--max-bounces", "", "Limit the number of surface interactions (0 = unlimited)", &R::max_bounces},
      {"format", "--format", "", format_help, &R::format},
      {"output", "-o,--output", "", "Output dataset (CSV), or with sun zenith angles the albedo table (CSV)",
       &R::output, FileRole::output},
  };
  return rows;
}

std::vector<double> render_wavelengths(const RenderRequest& request, const HeightField& field) {
  if (request.wavelengths.empty()) return default_wavelengths(field);
  check_range_values(request.wavelengths, "wavelengths", wavelength_rules());
  return request.wavelengths;
}

RenderSettings render_settings(const RenderRequest& r) {
  RenderSettings s;
  if (r.samples && r.target_error) throw FieldError("samples", "excludes target_error: give one of them");
  if (r.samples) {
    if (*r.samples < 2)
      throw FieldError("samples", fmt::format("{} is below 2 (a standard error needs 2 paths)", *r.samples));
    if (*r.samples > kMaxPathsPerGeometry) {
      throw FieldError("samples",
                       fmt::format("{} is above the limit of {} paths per geometry", *r.samples, kMaxPathsPerGeometry));
    }
    s.samples = *r.samples;
  }
  if (r.target_error) {
    if (!(*r.target_error >= 1e-6 && *r.target_error <= 1.0)) {
      throw FieldError("target_error",
                       fmt::format("{} is outside [1e-6, 1] (a relative standard error)", *r.target_error));
    }
    s.target_relative_error = *r.target_error;
  }
  if (!(r.error_floor >= 0.0 && r.error_floor <= 1.0)) {
    throw FieldError("error_floor", fmt::format("{} is outside [0, 1] sr^-1", r.error_floor));
  }
  if (!(r.acceptance_deg >= 0.0 && r.acceptance_deg <= 45.0)) {
    throw FieldError("acceptance_deg", fmt::format("{} is outside [0, 45] deg", r.acceptance_deg));
  }
  s.sampling = parse_name<Sampling>(r.sampling, "sampling");
  check_thread_count(r.threads);
  if (r.max_bounces < 0 || r.max_bounces > 1000) {
    throw FieldError("max_bounces", fmt::format("{} is outside [0, 1000] (0 = unlimited)", r.max_bounces));
  }
  if (r.white_sky_nodes < 0 || r.white_sky_nodes > 64) {
    throw FieldError("white_sky_nodes", fmt::format("{} is outside [0, 64]", r.white_sky_nodes));
  }
  if (!r.wavelengths.empty()) check_range_values(r.wavelengths, "wavelengths", wavelength_rules());
  s.max_samples = r.max_samples;
  s.absolute_error_floor = r.error_floor;
  s.acceptance_half_angle_deg = r.acceptance_deg;
  s.seed = r.seed;
  s.threads = r.threads;
  s.max_bounces = r.max_bounces;
  validate_sampling(s);  // the checks of the settings themselves (max_samples), made for every render
  return s;
}

}  // namespace roadbrdf::surface
