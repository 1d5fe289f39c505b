#include "roadbrdf/surface/surface_request.h"

#include <fmt/core.h>

#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/modelfile/fit_file_read.h"

namespace roadbrdf::surface {

std::span<const RequestField<SurfaceRequest>> SurfaceRequest::fields() {
  using R = SurfaceRequest;
  static const RequestField<R> rows[] = {
      {"input", "INPUT", "",
       "Formulation file (JSON), or for a flat or Gaussian-slope surface the material: a model name (with "
       "parameters) or FIT.json",
       &R::input, FileRole::input, true},
      {"size_mm", "--size", "mm",
       "Side of the periodic sample, with its unit on the command line, e.g. 60mm (default 60)", &R::size_mm},
      {"cell_mm", "--cell", "mm", "Grid spacing, 0.005 to 10 (default 0.1)", &R::cell_mm},
      {"seed", "--seed", "", "Random seed (default 1)", &R::seed},
      {"matrix_level", "--matrix-level", "",
       "Mastic level as a fraction of the slab thickness (largest grain size), 0 to 1, default 0.7", &R::matrix_level},
      {"target_mpd", "--target-mpd", "mm", "Choose the mastic level so that the MPD is this", &R::target_mpd},
      {"mastic_fraction", "--mastic-fraction", "",
       "Choose the mastic level so that the exposed (projected) area fraction of the mastic is this, in (0, 1), "
       "within max(0.001, 1/cells); an unreachable value is an error naming the reachable range",
       &R::mastic_fraction},
      {"preview", "--preview", "", "Write a PNG of the height map coloured by material", &R::preview, FileRole::output},
      {"flat", "--flat", "", "Flat sample z = 0 of one material (validation)", &R::flat},
      {"sigma_rad", "--gaussian-slopes,--vgrooves", "rad",
       "Isotropic random rough surface of one material with this facet slope angle sigma (validation; compare "
       "with oren-nayar sigma)",
       &R::sigma_rad},
      {"cells", "--cells", "",
       "Cells per side of a validation surface, 2 (32 rough) to 4096 (default 16 flat, 128 rough)", &R::cells},
      {"parameters", "-p,--parameter", "", "Model parameter NAME=VALUE of a model-name material (repeatable)",
       &R::parameters},
      {"options", "--option", "", "Model option NAME=VALUE of a model-name material (repeatable)", &R::options},
      {"fit", "--fit", "",
       "Which fit of a FIT.json material (its model name) or which method of a MIX.json (default: the best-ranked)",
       &R::fit},
      {"output", "-o,--output", "", "Output SURFACE.json (format: src/roadbrdf/surface/height_field.h)", &R::output,
       FileRole::output},
  };
  return rows;
}

SurfaceRequest::Kind SurfaceRequest::kind() const {
  if (flat) return Kind::flat;
  return sigma_rad ? Kind::gaussian_slopes : Kind::formulation;
}

void SurfaceRequest::validate() const {
  if (flat && sigma_rad) throw FieldError("flat", "excludes `sigma_rad`: a surface is flat or has Gaussian slopes");
  if (kind() == Kind::formulation) {
    if (!parameters.empty() || !options.empty() || !fit.empty()) {
      throw FieldError(!parameters.empty() ? "parameters"
                       : !options.empty()  ? "options"
                                           : "fit",
                       "is for the material of a flat or Gaussian-slope surface");
    }
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
    throw FieldError("size_mm",
                     "is for samples of a formulation; a flat or Gaussian-slope surface is `cells` x `cell_mm`");
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
  if (input.in_memory()) {
    throw FieldError("input", "the material of a flat or Gaussian-slope surface is a model name or a fit file");
  }
  if (!fits.empty()) throw FieldError("fits", "are for samples of a formulation");
  const bool rough = kind() == Kind::gaussian_slopes;
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
  return cells.value_or(kind() == Kind::flat ? 16 : 128);
}

SampleRecipe sample_recipe(const SurfaceRequest& request) {
  const Source& given = request.input;
  if (given.empty()) throw FieldError("input", "give the formulation file");
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

MaterialSpec validation_material(const SurfaceRequest& request) {
  const std::string& material = request.input.path;
  if (material.empty()) throw FieldError("input", "give the material: a model name or a fit file");
  if (is_fit_file_argument(material)) {
    return material_spec(material, request.fit, "", request.parameters, request.options);
  }
  return material_spec("", request.fit, material, request.parameters, request.options);
}

HeightField validation_surface(const SurfaceRequest& request) {
  const int n = request.cell_count();  // validates
  const MaterialSpec material = validation_material(request);
  HeightField field = request.kind() == SurfaceRequest::Kind::flat
                          ? make_flat(material, n, request.cell_mm)
                          : make_gaussian_slope_surface(material, *request.sigma_rad, n, request.cell_mm, request.seed);
  validate(field);
  return field;
}

}  // namespace roadbrdf::surface
