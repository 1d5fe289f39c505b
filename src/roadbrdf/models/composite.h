// Weighted sum of models: f = sum_k w_k f_k (report eqs. 3.16 and 3.17 are the two-term cases
// "oren-nayar+torrance-sparrow" and "lambert+torrance-sparrow").
//
// Parameters are the components' own, prefixed by the component name ("oren-nayar.albedo"),
// each component first contributing its weight ("oren-nayar.weight", default 1). A model that
// appears twice gets "#2" appended to its prefix ("lambert#2.albedo"). A weight and an amplitude of
// the same component (albedo) are not separately identifiable: fix one of them when fitting.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/models/model.h"

namespace roadbrdf {

class CompositeModel final : public Model {
 public:
  // `prefixes[k]` names component k in parameter and option names.
  CompositeModel(std::vector<std::unique_ptr<Model>> components, const std::vector<std::string>& prefixes);

  double evaluate(const double* params, const Geometry& g) const override;
  double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const override;
  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override;
  void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    double* values, double* jacobian) const override;
  std::unique_ptr<PreparedGeometries> prepare(const Geometry* geometries, std::size_t count) const override;
  std::unique_ptr<PreparedGeometries> prepare_expecting(const Geometry* geometries, std::size_t count,
                                                        const double* expected) const override;
  void evaluate_prepared(const PreparedGeometries& prepared, const double* params, double* values) const override;
  void evaluate_prepared_with_gradient(const PreparedGeometries& prepared, const double* params, double* values,
                                       double* jacobian) const override;
  double delta_reflectance(const double* params, double cos_theta_i) const override;
  bool reads_angles() const override;  // whether any component does

  std::size_t component_count() const { return components_.size(); }
  const Model& component(std::size_t k) const { return *components_[k]; }
  // Index of component k's weight in the parameter vector; its own parameters follow it.
  std::size_t weight_index(std::size_t k) const { return offsets_[k]; }

 private:
  static ModelDescription make_description(const std::vector<std::unique_ptr<Model>>& components,
                                           const std::vector<std::string>& prefixes);
  // The components' prepared geometries (see prepare()).
  struct Prepared;
  const Prepared* own_prepared(const PreparedGeometries& prepared) const;

  std::vector<std::unique_ptr<Model>> components_;
  std::vector<std::size_t> offsets_;
};

}  // namespace roadbrdf
