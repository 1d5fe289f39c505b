#include "roadbrdf/surface/surface_request.h"

#include <fmt/core.h>

#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/formulation/formulation.h"

namespace roadbrdf::surface {

void SurfaceRequest::validate() const {
  if (kind == Kind::formulation) {
    if (cells) throw FieldError("cells", "is for a flat or Gaussian-slope surface; a sample's size is size_mm");
    if (sigma_rad) throw FieldError("sigma_rad", "is for a Gaussian-slope surface");
    const int levels = (matrix_level ? 1 : 0) + (target_mpd ? 1 : 0) + (mastic_fraction ? 1 : 0);
    if (levels > 1) {
      throw FieldError(matrix_level ? "matrix_level" : "target_mpd",
                       "matrix_level, target_mpd and mastic_fraction exclude each other");
    }
    GeneratorSettings s;
    s.size_mm = size_mm.value_or(s.size_mm);
    s.cell_size_mm = cell_mm;
    s.matrix_level = matrix_level.value_or(s.matrix_level);
    s.target_mpd_mm = target_mpd;
    s.mastic_fraction = mastic_fraction;
    surface::validate(s);
    return;
  }
  if (size_mm) {
    throw FieldError("size_mm", "is for samples of a formulation; a flat or Gaussian-slope surface is cells x cell_mm");
  }
  if (matrix_level || target_mpd || mastic_fraction) {
    throw FieldError(matrix_level ? "matrix_level"
                     : target_mpd ? "target_mpd"
                                  : "mastic_fraction",
                     "is for samples of a formulation");
  }
  if (!(cell_mm >= 0.005 && cell_mm <= 10.0)) {
    throw FieldError("cell_mm", fmt::format("must be in [0.005, 10] mm, got {}", cell_mm));
  }
  const bool rough = kind == Kind::gaussian_slopes;
  if (cells && !(*cells >= (rough ? 32 : 2) && *cells <= 4096)) {
    throw FieldError("cells", fmt::format("must be in [{}, 4096] for a {} surface, got {}", rough ? 32 : 2,
                                          rough ? "Gaussian-slope" : "flat", *cells));
  }
  if (rough && !(sigma_rad && *sigma_rad > 0.0 && *sigma_rad < 1.3)) {
    throw FieldError("sigma_rad", sigma_rad ? fmt::format("must be in (0, 1.3) rad, got {}", *sigma_rad)
                                            : std::string("is needed for a Gaussian-slope surface"));
  }
  if (!rough && sigma_rad) throw FieldError("sigma_rad", "is for a Gaussian-slope surface");
}

GeneratorSettings SurfaceRequest::generator_settings() const {
  validate();
  GeneratorSettings s;
  s.size_mm = size_mm.value_or(s.size_mm);
  s.cell_size_mm = cell_mm;
  s.seed = seed;
  s.matrix_level = matrix_level.value_or(s.matrix_level);
  s.target_mpd_mm = target_mpd;
  s.mastic_fraction = mastic_fraction;
  return s;
}

int SurfaceRequest::cell_count() const {
  validate();
  return cells.value_or(kind == Kind::flat ? 16 : 128);
}

SampleRecipe sample_recipe(const SurfaceRequest& request) {
  const Source& given = request.formulation;
  if (given.empty()) throw FieldError("formulation", "give the formulation file");
  const Formulation formulation =
      given.in_memory() ? parse_formulation(given.text, given.path, false) : read_formulation(given.path, false);
  SampleRecipe recipe = recipe_from_formulation(formulation);
  const auto attach = [&request](MaterialSpec& material) {
    const auto value = request.fits.find(material.fit_path);
    if (value != request.fits.end()) material.fit_text = value->second;
  };
  attach(recipe.matrix);
  for (GrainClass& c : recipe.classes) attach(c.material);
  return recipe;
}

}  // namespace roadbrdf::surface
