// Materials of a virtual sample as the path tracer sees them (render.h): each material of the
// height field's material map is a BRDF model with one parameter set per rendered wavelength, its
// ideal specular (delta) part if the model has one, and its tabulated importance sampler
// (brdf_sampler.h). One geometric path serves every wavelength, so every evaluation returns the
// whole spectrum at once.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/model.h"
#include "roadbrdf/surface/brdf_sampler.h"
#include "roadbrdf/surface/height_field.h"

namespace roadbrdf::surface {

// A material ready for rendering: a model and one parameter set per wavelength.
struct RenderMaterial {
  std::string name;
  std::shared_ptr<const Model> model;
  std::vector<double> parameters;  // wavelengths x parameter_count, row-major
  bool has_delta = false;
};

// The material of a flat or Gaussian-slopes sample (height_field.h), as both front ends give it:
// a fit file `fit_path` (its best fit, or the fit `fit_model` selects), or, when fit_path is empty,
// the model `model` with fixed `parameters` (defaults for the rest) and `options`. It is checked
// now rather than at the first render: the fit file is read, the model made and its parameters
// assigned. Throws FieldError("parameters" or "options" with a fit file, "fit" with a model, or the
// fit file reader's "fit"), FileError (a bad fit file) or InputError (an unknown model, option or
// parameter).
MaterialSpec material_spec(const std::string& fit_path, const std::string& fit_model, const std::string& model,
                           const std::map<std::string, double>& parameters,
                           const std::map<std::string, std::string>& options);

// Load the materials of a height field at the given wavelengths (fit files are read; model
// materials use their fixed parameters at every wavelength). Throws InputError / FileError.
std::vector<RenderMaterial> load_materials(const HeightField& field, const std::vector<double>& wavelengths);

// Wavelengths to render by default: those of the first spectral material inside the range common
// to all spectral materials; {550} when no material is spectral.
std::vector<double> default_wavelengths(const HeightField& field);

// The materials of one render, indexed like the material map.
class MaterialSet {
 public:
  // Checks that every parameter table holds wavelength_count sets; builds the samplers.
  MaterialSet(std::vector<RenderMaterial> materials, std::size_t wavelength_count);

  std::size_t size() const { return materials_.size(); }
  std::size_t wavelength_count() const { return m_; }
  bool any_delta() const { return any_delta_; }
  bool has_delta(int material) const { return materials_[material].has_delta; }
  const BrdfSampler& sampler(int material) const { return samplers_[material]; }
  // Whether the material's model reads the angle fields of a geometry (Model::reads_angles).
  bool reads_angles(int material) const { return reads_angles_[material] != 0; }

  // Smooth BRDF [sr^-1] of `material` at a geometry in the facet's frame: out[w], w < wavelength_count().
  // Through the model's evaluator of its fixed per-wavelength parameter sets (model.h,
  // FixedSetEvaluator): evaluate_batch's values, to rounding for models with their own evaluator.
  void evaluate(int material, const Geometry& g, double* out) const { evaluators_[material]->evaluate(g, out); }
  // Reflectance R of the delta part for light arriving at cos_theta from the facet normal, per
  // wavelength: beta[w] *= factor * R_w.
  void scale_by_delta_reflectance(int material, double cos_theta, double factor, double* beta) const {
    const RenderMaterial& mat = materials_[material];
    const std::size_t np = mat.model->parameter_count();
    for (std::size_t w = 0; w < m_; ++w)
      beta[w] *= factor * mat.model->delta_reflectance(mat.parameters.data() + w * np, cos_theta);
  }

 private:
  std::vector<RenderMaterial> materials_;
  std::vector<BrdfSampler> samplers_;
  std::vector<std::unique_ptr<FixedSetEvaluator>> evaluators_;
  std::vector<char> reads_angles_;
  std::size_t m_ = 0;
  bool any_delta_ = false;
};

}  // namespace roadbrdf::surface
