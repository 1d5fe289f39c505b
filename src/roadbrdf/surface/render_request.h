// Render settings as the front ends give them (`roadbrdf render`, roadbrdf.render and
// roadbrdf.render_albedo in Python), validated once here: RenderSettings (render.h) from a
// RenderRequest, whose field table (core/request_fields.h) makes the command's options and Python's
// keywords. Errors are FieldError with these field names ("samples", "target_error",
// "acceptance_deg", ...); the command line spells them as the table's flags.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"

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
  int threads = 0;                  // [0, 1024], 0 = all cores
  int max_bounces = 0;              // [0, 1000], 0 = unlimited
  int white_sky_nodes = 8;          // albedo: Gauss-Legendre nodes in cos(theta), [0, 64]
  std::vector<double> wavelengths;  // [nm], increasing; empty = those of the materials' fits (or 550)
  // What the command reads and writes (Python passes a Surface and angles instead, and may give
  // `output` for the albedo table): the SURFACE file, and either a geometry table (`grid`, a dataset
  // in `format` written to `output`) or sun zenith angles (`sun_zenith`, an albedo table to `output`).
  std::string surface;
  std::string grid;
  std::vector<double> sun_zenith;  // [deg]
  std::string format = "wide";     // a name of DatasetFormat (io/dataset_io.h)
  std::string output;

  static std::span<const RequestField<RenderRequest>> fields();
};

// Throws FieldError.
RenderSettings render_settings(const RenderRequest& request);
// The request's `wavelengths`, checked (increasing, positive), or the default of `field`'s materials.
std::vector<double> render_wavelengths(const RenderRequest& request, const HeightField& field);

}  // namespace roadbrdf::surface
