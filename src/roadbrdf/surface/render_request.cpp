#include "roadbrdf/surface/render_request.h"

#include <fmt/core.h>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/surface/scheduler.h"

namespace roadbrdf::surface {

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
  if (r.threads < 0 || r.threads > 1024)
    throw FieldError("threads", fmt::format("{} is outside [0, 1024] (0 = all cores)", r.threads));
  if (r.max_bounces < 0 || r.max_bounces > 1000) {
    throw FieldError("max_bounces", fmt::format("{} is outside [0, 1000] (0 = unlimited)", r.max_bounces));
  }
  if (r.white_sky_nodes < 0 || r.white_sky_nodes > 64) {
    throw FieldError("white_sky_nodes", fmt::format("{} is outside [0, 64]", r.white_sky_nodes));
  }
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
