// A surface as the front ends ask for it (`roadbrdf surface`, roadbrdf.surface / flat_surface /
// gaussian_slope_surface in Python), validated once here: a virtual sample of a formulation
// (generate.h) or a validation surface of one material (flat, or Gaussian facet slopes). Its field
// table (fields(), core/request_fields.h) makes the command's options and Python's keywords; errors
// are FieldError with the table's names ("size_mm", "cell_mm", "sigma_rad", ...), which the command
// line spells as the table's flags.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/materials.h"

namespace roadbrdf::surface {

struct SurfaceRequest {
  enum class Kind { formulation, flat, gaussian_slopes };
  // What the surface is made of: a formulation (its file, or its content: Python's dict, a design
  // study's candidate), or for a flat or Gaussian-slope surface one material, a model name (with
  // `parameters` and `options`) or a fit file (with `fit`).
  Source input;
  // Fit files given as values (Python's `fits`, as MixRequest::fits): the JSON text of each by the
  // reference the formulation's "fit" gives; a reference found here is not read from disk, at
  // rendering either (MaterialSpec::fit_text). Not a row of the table: the command reads files.
  std::map<std::string, std::string> fits;
  LengthMm size_mm;      // side of the periodic sample [mm] (default 60), a whole number of cells
  double cell_mm = 0.1;  // grid spacing [mm], in [0.005, 10]
  std::uint64_t seed = 1;
  std::optional<double> matrix_level;     // mastic level / slab thickness in [0, 1] (default 0.7), or
  std::optional<double> target_mpd;       // the level giving this MPD [mm] (> 0), or
  std::optional<double> mastic_fraction;  // the level exposing this mastic area fraction, in (0, 1)
  std::string preview;                    // a PNG of the height map coloured by material ("" = none)
  // A validation surface: flat, or Gaussian slopes of standard deviation sigma_rad [rad] in (0, 1.3).
  bool flat = false;
  std::optional<double> sigma_rad;
  std::optional<int> cells;  // cells per side, [2, 4096] (default 16 flat, 128 Gaussian; >= 32 Gaussian)
  std::map<std::string, double> parameters;    // of a model-name material
  std::map<std::string, std::string> options;  // of a model-name material
  std::string fit;                             // which fit of a fit-file material (default: the best)
  std::string output;                          // the SURFACE file ("" = none: Python keeps the value)

  static std::span<const RequestField<SurfaceRequest>> fields();

  // flat, gaussian_slopes (sigma_rad given) or formulation.
  Kind kind() const;
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

// The material of a validation surface: `input` a fit file (FIT.json, MIX.json; `fit` chooses) or
// a model name (`parameters`, `options`), by modelfile's one rule (is_fit_file_argument). Throws as
// material_spec (materials.h).
MaterialSpec validation_material(const SurfaceRequest& request);
// A flat or Gaussian-slope surface of the request (validated), its material checked.
HeightField validation_surface(const SurfaceRequest& request);

}  // namespace roadbrdf::surface
