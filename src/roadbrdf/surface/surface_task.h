// The `surface` task of both front ends (`roadbrdf surface`, roadbrdf.surface in Python): the
// request (surface_request.h) validated, its files checked, the surface built (a formulation's
// sample packed by generate.h, or a validation surface of one material), its texture statistics,
// and the SURFACE file and preview written when the request names them. The command line prints the
// summary text and the diagnostics; Python returns the surface and issues the warnings.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/surface_request.h"

namespace roadbrdf::surface {

struct SurfaceResult {
  HeightField field;
  TextureStatistics statistics;
  // A formulation's packing report (generate.h); its `field` and `grains` are left empty (the field
  // is above). Absent for a validation surface.
  std::optional<GeneratedSample> sample;
  std::vector<std::string> classes;                 // the sample's material classes, in the report's order
  std::optional<double> requested_mastic_fraction;  // the request's `mastic_fraction`, for the summary
  Diagnostics diagnostics;
  std::vector<std::string> written;  // the files written, in order (`output`, then `preview`)

  // The generator's report of a formulation's sample (GeneratedSample::to_json) with its material
  // `classes`; null for a validation surface.
  nlohmann::json sample_report() const;
  // The command's report: the sample's description and mastic level, the texture statistics per
  // material, the files written.
  std::string summary_text() const;
};

// Throws FieldError (a request field), FileError (a formulation or fit file) or InputError.
SurfaceResult make_surface(const SurfaceRequest& request, const ProgressCallback& progress = {});

}  // namespace roadbrdf::surface
