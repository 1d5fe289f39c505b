#include "roadbrdf/surface/materials.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::surface {

MaterialSpec material_spec(const std::string& fit_path, const std::string& fit_model, const std::string& model,
                           const std::map<std::string, double>& parameters,
                           const std::map<std::string, std::string>& options) {
  MaterialSpec m;
  if (!fit_path.empty()) {
    if (!parameters.empty()) throw FieldError("parameters", "apply to a model, not to a fit file");
    if (!options.empty()) throw FieldError("options", "apply to a model, not to a fit file");
    read_fit_file(fit_path, fit_model);
    m.name = std::filesystem::path(fit_path).stem().string();
    m.fit = fit_path;
    m.fit_path = fit_path;
    m.fit_model = fit_model;
    return m;
  }
  if (!fit_model.empty()) throw FieldError("fit", "selects a fit of a fit file; '" + model + "' is a model name");
  const std::unique_ptr<Model> made = make_model(model, options);
  parameters_from_assignments(made->description(), parameters);
  m.name = model;
  m.model = model;
  m.parameters = parameters;
  m.options = options;
  return m;
}

namespace {

// The fit of a material: its content given as a value, or its file.
SpectralModel material_fit(const MaterialSpec& spec) {
  return spec.fit_text.empty() ? read_fit_file(spec.fit_path, spec.fit_model)
                               : parse_fit_file(spec.fit_text, spec.fit_path, spec.fit_model);
}

}  // namespace

std::vector<RenderMaterial> load_materials(const HeightField& field, const std::vector<double>& wavelengths) {
  if (wavelengths.empty()) throw InputError("render: no wavelengths");
  std::vector<RenderMaterial> out;
  for (const MaterialSpec& spec : field.materials) {
    RenderMaterial m;
    m.name = spec.name;
    if (!spec.model.empty()) {
      std::shared_ptr<const Model> model = make_model(spec.model, spec.options);
      const std::vector<double> p = parameters_from_assignments(model->description(), spec.parameters);
      m.model = model;
      for (std::size_t w = 0; w < wavelengths.size(); ++w) m.parameters.insert(m.parameters.end(), p.begin(), p.end());
    } else {
      const SpectralModel sm = material_fit(spec);
      m.model = sm.model_ptr();
      for (double wl : wavelengths) {
        std::vector<double> p;
        if (sm.is_spectral()) {
          try {
            p = sm.parameters_at(wl);
          } catch (const InputError& e) {
            throw InputError("material '" + spec.name + "' (" + spec.fit_path + "): " + e.what());
          }
        } else {
          p = sm.parameter_table();
        }
        m.parameters.insert(m.parameters.end(), p.begin(), p.end());
      }
    }
    m.has_delta = m.model->description().has_delta;
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<double> default_wavelengths(const HeightField& field) {
  double lo = -1e300, hi = 1e300;
  std::vector<double> first;
  for (const MaterialSpec& spec : field.materials) {
    if (!spec.model.empty()) continue;
    const SpectralModel sm = material_fit(spec);
    if (!sm.is_spectral()) continue;
    lo = std::max(lo, sm.wavelengths().front());
    hi = std::min(hi, sm.wavelengths().back());
    if (first.empty()) first = sm.wavelengths();
  }
  if (first.empty()) return {550.0};
  std::vector<double> out;
  for (double w : first) {
    if (w >= lo && w <= hi) out.push_back(w);
  }
  if (out.empty()) throw InputError("the spectral materials of the surface have no common wavelength range");
  return out;
}

MaterialSet::MaterialSet(std::vector<RenderMaterial> materials, std::size_t wavelength_count)
    : materials_(std::move(materials)), m_(wavelength_count) {
  for (const RenderMaterial& mat : materials_) {
    if (mat.parameters.size() != wavelength_count * mat.model->parameter_count()) {
      throw InputError("render: material '" + mat.name + "' has a wrong parameter table size");
    }
    any_delta_ = any_delta_ || mat.has_delta;
    samplers_.emplace_back(*mat.model, mat.parameters, wavelength_count);
    evaluators_.push_back(mat.model->fixed_sets(mat.parameters.data(), wavelength_count));
    reads_angles_.push_back(mat.model->reads_angles() ? 1 : 0);
  }
}

}  // namespace roadbrdf::surface
