// Render settings as the front ends give them (`roadbrdf render`, roadbrdf.render in Python),
// validated once here: RenderSettings (render.h) from a RenderRequest. Errors are FieldError with
// these field names ("samples", "target_error", "acceptance_deg", ...); the command line maps them
// to its flags (cli/common.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "roadbrdf/surface/render.h"

namespace roadbrdf::surface {

struct RenderRequest {
  std::optional<long> samples;         // paths per geometry, >= 2 (default 4096); excludes target_error
  std::optional<double> target_error;  // adaptive: relative standard error in [1e-6, 1]
  long max_samples = 1L << 20;         // adaptive: at most this many paths per geometry, >= 2
  double error_floor = 1e-5;           // adaptive: absolute standard error [sr^-1] in [0, 1]
  double acceptance_deg = 1.0;         // detector cone half-angle [deg] in [0, 45]
  std::string sampling = "brdf";       // a name of kSamplingNames (render.h)
  std::uint64_t seed = 1;
  int threads = 0;          // [0, 1024], 0 = all cores
  int max_bounces = 0;      // [0, 1000], 0 = unlimited
  int white_sky_nodes = 8;  // albedo: Gauss-Legendre nodes in cos(theta), [0, 64]
};

// Throws FieldError.
RenderSettings render_settings(const RenderRequest& request);

}  // namespace roadbrdf::surface
