#include "roadbrdf/models/composite.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace roadbrdf {

ModelDescription CompositeModel::make_description(const std::vector<std::unique_ptr<Model>>& components,
                                                  const std::vector<std::string>& prefixes) {
  ModelDescription d;
  std::string name;
  d.summary = "weighted sum:";
  d.citation = "sum of components (report eqs. 3.16, 3.17 for two terms)";
  d.reciprocal = true;
  d.energy_conserving = false;  // the weights are free; sum_k w_k <= 1 is not enforced
  d.has_delta = false;
  d.mirror_lobe = false;  // unless a component has one
  for (std::size_t k = 0; k < components.size(); ++k) {
    const ModelDescription& c = components[k]->description();
    name += (k ? "+" : "") + c.name;
    d.summary += (k ? " + " : " ") + c.summary;
    d.reciprocal = d.reciprocal && c.reciprocal;
    d.non_negative = d.non_negative && c.non_negative;
    d.has_delta = d.has_delta || c.has_delta;
    d.mirror_lobe = d.mirror_lobe || c.mirror_lobe;
    if (!c.grazing_zero.empty()) {
      d.grazing_zero += (d.grazing_zero.empty() ? "" : "; ") + prefixes[k] + ": " + c.grazing_zero;
    }
    const std::string& prefix = prefixes[k];
    combine_isotropy(d, c, prefix);
    d.parameters.push_back(
        {prefix + ".weight", "1", "weight of the " + c.name + " component", 1.0, 0.0, 1.0e6, true, true});
    for (ParameterInfo p : c.parameters) {
      p.name = prefix + "." + p.name;
      d.parameters.push_back(p);
    }
    for (const auto& [name, range] : c.physical_bounds) d.physical_bounds[prefix + "." + name] = range;
    for (OptionInfo o : c.options) {
      o.name = prefix + "." + o.name;
      d.options.push_back(o);
    }
    for (const auto& [key, value] : c.option_values) d.option_values[prefix + "." + key] = value;
  }
  d.name = name;
  return d;
}

CompositeModel::CompositeModel(std::vector<std::unique_ptr<Model>> components, const std::vector<std::string>& prefixes)
    : Model(make_description(components, prefixes)), components_(std::move(components)) {
  std::size_t offset = 0;
  for (const auto& c : components_) {
    offsets_.push_back(offset);
    offset += 1 + c->parameter_count();
  }
}

double CompositeModel::evaluate(const double* params, const Geometry& g) const {
  double f = 0.0;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double* p = params + offsets_[k];
    f += p[0] * components_[k]->evaluate(p + 1, g);
  }
  return f;
}

double CompositeModel::evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const {
  double f = 0.0;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double* p = params + offsets_[k];
    double* grad = gradient + offsets_[k];
    const double fk = components_[k]->evaluate_with_gradient(p + 1, g, grad + 1);
    const std::size_t n = components_[k]->parameter_count();
    for (std::size_t j = 1; j <= n; ++j) grad[j] *= p[0];
    grad[0] = fk;
    f += p[0] * fk;
  }
  return f;
}

void CompositeModel::evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    std::size_t n_sets, double* out) const {
  const std::size_t n_params = parameter_count();
  std::fill(out, out + n_geometries * n_sets, 0.0);
  std::vector<double> component_params;
  std::vector<double> component_out(n_geometries * n_sets);
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const std::size_t nk = components_[k]->parameter_count();
    component_params.resize(n_sets * nk);
    for (std::size_t s = 0; s < n_sets; ++s) {
      const double* p = params + s * n_params + offsets_[k] + 1;
      std::copy(p, p + nk, component_params.begin() + static_cast<std::ptrdiff_t>(s * nk));
    }
    components_[k]->evaluate_batch(geometries, n_geometries, component_params.data(), n_sets, component_out.data());
    for (std::size_t n = 0; n < n_geometries; ++n) {
      for (std::size_t s = 0; s < n_sets; ++s) {
        out[n * n_sets + s] += params[s * n_params + offsets_[k]] * component_out[n * n_sets + s];
      }
    }
  }
}

void CompositeModel::evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries,
                                                  const double* params, double* values, double* jacobian) const {
  const std::size_t n_params = parameter_count();
  std::fill(values, values + n_geometries, 0.0);
  // Scratch without zero-initialisation (every entry is written by the component).
  const std::unique_ptr<double[]> vk(new double[n_geometries]);
  std::size_t max_nk = 0;
  for (const auto& c : components_) max_nk = std::max(max_nk, c->parameter_count());
  const std::unique_ptr<double[]> jk(new double[n_geometries * max_nk]);
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const std::size_t nk = components_[k]->parameter_count();
    const double* p = params + offsets_[k];
    components_[k]->evaluate_batch_with_gradient(geometries, n_geometries, p + 1, vk.get(), jk.get());
    for (std::size_t n = 0; n < n_geometries; ++n) {
      values[n] += p[0] * vk[n];
      double* row = jacobian + n * n_params + offsets_[k];
      row[0] = vk[n];
      for (std::size_t j = 0; j < nk; ++j) row[1 + j] = p[0] * jk[n * nk + j];
    }
  }
}

struct CompositeModel::Prepared final : PreparedGeometries {
  // `expected`: the composite's parameter vector (component k's own parameters follow its weight), or null.
  Prepared(const CompositeModel& owner, const Geometry* geometries, std::size_t count, const double* expected)
      : PreparedGeometries(geometries, count), composite(&owner) {
    for (std::size_t k = 0; k < owner.components_.size(); ++k) {
      const Model& c = *owner.components_[k];
      parts.push_back(expected != nullptr ? c.prepare_expecting(geometries, count, expected + owner.offsets_[k] + 1)
                                          : c.prepare(geometries, count));
    }
  }
  const CompositeModel* composite;                         // the model that built it
  std::vector<std::unique_ptr<PreparedGeometries>> parts;  // one per component
};

std::unique_ptr<PreparedGeometries> CompositeModel::prepare(const Geometry* geometries, std::size_t count) const {
  return std::make_unique<Prepared>(*this, geometries, count, nullptr);
}

std::unique_ptr<PreparedGeometries> CompositeModel::prepare_expecting(const Geometry* geometries, std::size_t count,
                                                                      const double* expected) const {
  return std::make_unique<Prepared>(*this, geometries, count, expected);
}

const CompositeModel::Prepared* CompositeModel::own_prepared(const PreparedGeometries& prepared) const {
  const auto* own = dynamic_cast<const Prepared*>(&prepared);
  return own != nullptr && own->composite == this ? own : nullptr;
}

// Same arithmetic as evaluate_batch with one parameter set, on the components' prepared geometries.
void CompositeModel::evaluate_prepared(const PreparedGeometries& prepared, const double* params, double* values) const {
  const Prepared* own = own_prepared(prepared);
  if (own == nullptr) return Model::evaluate_prepared(prepared, params, values);
  const std::size_t n_geometries = prepared.size();
  std::fill(values, values + n_geometries, 0.0);
  // Scratch without zero-initialisation (every entry is written by the component).
  const std::unique_ptr<double[]> vk(new double[n_geometries]);
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double* p = params + offsets_[k];
    components_[k]->evaluate_prepared(*own->parts[k], p + 1, vk.get());
    for (std::size_t n = 0; n < n_geometries; ++n) values[n] += p[0] * vk[n];
  }
}

// Same arithmetic as evaluate_batch_with_gradient, on the components' prepared geometries.
void CompositeModel::evaluate_prepared_with_gradient(const PreparedGeometries& prepared, const double* params,
                                                     double* values, double* jacobian) const {
  const Prepared* own = own_prepared(prepared);
  if (own == nullptr) return Model::evaluate_prepared_with_gradient(prepared, params, values, jacobian);
  const std::size_t n_params = parameter_count();
  const std::size_t n_geometries = prepared.size();
  std::fill(values, values + n_geometries, 0.0);
  // Scratch without zero-initialisation (every entry is written by the component).
  const std::unique_ptr<double[]> vk(new double[n_geometries]);
  std::size_t max_nk = 0;
  for (const auto& c : components_) max_nk = std::max(max_nk, c->parameter_count());
  const std::unique_ptr<double[]> jk(new double[n_geometries * max_nk]);
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const std::size_t nk = components_[k]->parameter_count();
    const double* p = params + offsets_[k];
    components_[k]->evaluate_prepared_with_gradient(*own->parts[k], p + 1, vk.get(), jk.get());
    for (std::size_t n = 0; n < n_geometries; ++n) {
      values[n] += p[0] * vk[n];
      double* row = jacobian + n * n_params + offsets_[k];
      row[0] = vk[n];
      for (std::size_t j = 0; j < nk; ++j) row[1 + j] = p[0] * jk[n * nk + j];
    }
  }
}

bool CompositeModel::reads_angles() const {
  return std::any_of(components_.begin(), components_.end(), [](const auto& c) { return c->reads_angles(); });
}

double CompositeModel::delta_reflectance(const double* params, double cos_theta_i) const {
  double r = 0.0;
  for (std::size_t k = 0; k < components_.size(); ++k) {
    const double* p = params + offsets_[k];
    r += p[0] * components_[k]->delta_reflectance(p + 1, cos_theta_i);
  }
  return r;
}

}  // namespace roadbrdf
