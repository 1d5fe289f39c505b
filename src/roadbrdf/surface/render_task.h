// The `render` tasks of both front ends (`roadbrdf render`, roadbrdf.render and
// roadbrdf.render_albedo in Python): a surface rendered at the geometries of a grid into a dataset,
// or into its black-sky (and white-sky) albedo, with the settings of a RenderRequest
// (render_request.h), the Monte Carlo report and the warnings of estimates that missed their target.
// The surface and the geometries are values: the command line reads them from the request's
// `surface` and `grid` files (read_render_inputs), Python passes its own.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/virtual_albedo.h"

namespace roadbrdf::surface {

struct RenderResult {
  SpectralDataset data;             // BRDF with the standard errors as sigma
  std::vector<Estimate> estimates;  // per geometry
  Diagnostics diagnostics;          // a warning per geometry that missed `target_error`, and their count
  std::string summary;              // paths, the worst relative errors' median/90th percentile/max
  const std::string& summary_text() const { return summary; }
  // Keys: wavelengths, brdf and sigma ([geometry][wavelength], sr^-1), metadata, and per geometry
  // paths and converged.
  nlohmann::json to_json() const;
};

struct RenderAlbedoResult {
  VirtualAlbedo albedo;
  Diagnostics diagnostics;  // estimates that reached `max_samples` before `target_error`
  std::string summary;
  const std::string& summary_text() const { return summary; }
};

// `surface_name` names the surface in the report and the albedo table's comment. With the request's
// `output`, the dataset (in `format`) or the albedo table is written (atomically), never over the
// `surface` or `grid` file or a material's fit file. Throws FieldError, InputError.
// `convention` is the grid's, kept in the dataset.
RenderResult render_grid(const HeightField& field, const std::string& surface_name,
                         const std::vector<Geometry>& geometries, AngleConvention convention,
                         const RenderRequest& request, const ProgressCallback& progress = {});
RenderAlbedoResult render_surface_albedo(const HeightField& field, const std::string& surface_name,
                                         const RenderRequest& request, const ProgressCallback& progress = {});

}  // namespace roadbrdf::surface
