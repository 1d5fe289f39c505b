// A surface as the front ends ask for it (`roadbrdf surface`, roadbrdf.surface / flat_surface /
// gaussian_slope_surface in Python), validated once here: a virtual sample of a formulation
// (generate.h) or a validation surface of one material (flat, or Gaussian facet slopes).
// Errors are FieldError with these field names, which are also the Python keywords ("size_mm",
// "cell_mm", "matrix_level", "target_mpd", "mastic_fraction", "cells", "sigma_rad"); the command
// line maps them to its flags (cli/common.h).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/surface/generate.h"

namespace roadbrdf::surface {

struct SurfaceRequest {
  enum class Kind { formulation, flat, gaussian_slopes };
  Kind kind = Kind::formulation;
  double cell_mm = 0.1;  // grid spacing [mm], in [0.005, 10]
  std::uint64_t seed = 1;
  // A sample of a formulation: its file, or its content (Python: a dict; a design study's candidate).
  Source formulation;
  // Fit files given as values (Python's `fits`, as MixRequest::fits): the JSON text of each by the
  // reference the formulation's "fit" gives; a reference found here is not read from disk, at
  // rendering either (MaterialSpec::fit_text).
  std::map<std::string, std::string> fits;
  std::optional<double> size_mm;          // side of the periodic sample [mm] (default 60), a whole number of cells
  std::optional<double> matrix_level;     // mastic level / slab thickness in [0, 1] (default 0.7), or
  std::optional<double> target_mpd;       // the level giving this MPD [mm] (> 0), or
  std::optional<double> mastic_fraction;  // the level exposing this mastic area fraction, in (0, 1)
  // A validation surface:
  std::optional<int> cells;         // cells per side, [2, 4096] (default 16 flat, 128 Gaussian; >= 32 Gaussian)
  std::optional<double> sigma_rad;  // Gaussian slopes: facet slope angle sigma [rad] in (0, 1.3)

  // Throws FieldError.
  void validate() const;
  // The generator's settings of a formulation sample (validated).
  GeneratorSettings generator_settings() const;
  // Cells per side of a validation surface (validated).
  int cell_count() const;
};

// The recipe of the request's formulation (recipe_from_formulation), its materials' fits given as
// values attached. The fit files are not checked here: they are needed only to render. Throws
// FieldError("formulation") without one, FileError / InputError for a bad formulation.
SampleRecipe sample_recipe(const SurfaceRequest& request);

}  // namespace roadbrdf::surface
