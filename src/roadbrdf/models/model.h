// The type-erased BRDF model used by every command, and the adapter that turns a templated
// model struct (one per file in this folder) into it.
//
// A model struct M provides:
//   static constexpr const char* kName;                 // CLI name, e.g. "oren-nayar"
//   static constexpr int kMaxParameters;                // upper bound of the parameter count
//   static std::vector<OptionInfo> options();           // discrete choices (may be empty)
//   static ModelDescription describe(const OptionSet&); // parameters for resolved options
//   explicit M(const OptionSet& resolved_options);
//   template <typename T> T operator()(const T* p, const Geometry& g) const;   // smooth BRDF [sr^-1]
// and optionally, for an ideal specular (delta) part f = R(theta_i) delta(w_r - mirror(w_i)) / cos(theta_r):
//   double delta_reflectance(const double* p, double cos_theta_i) const;
//
// operator() is templated on the scalar so that the fitter differentiates it with ceres::Jet.
// Geometry is plain double: angles are data, parameters are unknowns.
#pragma once

#include <ceres/jet.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

class Model {
 public:
  virtual ~Model() = default;

  const ModelDescription& description() const { return description_; }
  const std::string& name() const { return description_.name; }
  std::size_t parameter_count() const { return description_.parameters.size(); }

  // Smooth part of the BRDF [sr^-1] at one geometry; `params` holds parameter_count() values.
  virtual double evaluate(const double* params, const Geometry& g) const = 0;

  // Value and its gradient with respect to the parameters (automatic differentiation).
  virtual double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const = 0;

  // Batch evaluation: `n_sets` parameter sets (e.g. one per wavelength, each parameter_count()
  // values, contiguous) at `n_geometries` geometries. out[n * n_sets + s] = f(params_s, geometries[n]).
  virtual void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params,
                              std::size_t n_sets, double* out) const = 0;

  // Batch with Jacobian for one parameter set: values[n] and jacobian[n * parameter_count() + k].
  virtual void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries,
                                            const double* params, double* values, double* jacobian) const = 0;

  // Reflectance R(theta_i) of the ideal specular part (0 when the model has none).
  virtual double delta_reflectance(const double* /*params*/, double /*cos_theta_i*/) const { return 0.0; }

 protected:
  explicit Model(ModelDescription description) : description_(std::move(description)) {}
  ModelDescription description_;
};

template <class M>
concept HasDeltaPart = requires(const M& m, const double* p, double c) {
  { m.delta_reflectance(p, c) } -> std::convertible_to<double>;
};

template <class M>
class ModelAdapter final : public Model {
 public:
  explicit ModelAdapter(const OptionSet& given)
      : ModelAdapter(resolve_options(M::kName, M::options(), given), 0) {}

  double evaluate(const double* params, const Geometry& g) const override { return model_(params, g); }

  double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const override {
    const std::size_t n = parameter_count();
    Jet p[M::kMaxParameters];
    for (std::size_t k = 0; k < n; ++k) p[k] = Jet(params[k], static_cast<int>(k));
    const Jet f = model_(p, g);
    for (std::size_t k = 0; k < n; ++k) gradient[k] = f.v[static_cast<int>(k)];
    return f.a;
  }

  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params,
                      std::size_t n_sets, double* out) const override {
    const std::size_t n_params = parameter_count();
    for (std::size_t n = 0; n < n_geometries; ++n) {
      const Geometry& g = geometries[n];
      double* row = out + n * n_sets;
      for (std::size_t s = 0; s < n_sets; ++s) row[s] = model_(params + s * n_params, g);
    }
  }

  void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    double* values, double* jacobian) const override {
    const std::size_t n_params = parameter_count();
    Jet p[M::kMaxParameters];
    for (std::size_t k = 0; k < n_params; ++k) p[k] = Jet(params[k], static_cast<int>(k));
    for (std::size_t n = 0; n < n_geometries; ++n) {
      const Jet f = model_(p, geometries[n]);
      values[n] = f.a;
      for (std::size_t k = 0; k < n_params; ++k) jacobian[n * n_params + k] = f.v[static_cast<int>(k)];
    }
  }

  double delta_reflectance(const double* params, double cos_theta_i) const override {
    if constexpr (HasDeltaPart<M>) {
      return model_.delta_reflectance(params, cos_theta_i);
    } else {
      return 0.0;
    }
  }

  const M& model() const { return model_; }

 private:
  using Jet = ceres::Jet<double, M::kMaxParameters>;

  ModelAdapter(const OptionSet& resolved, int) : Model(describe_resolved(resolved)), model_(resolved) {}

  static ModelDescription describe_resolved(const OptionSet& resolved) {
    ModelDescription d = M::describe(resolved);
    d.name = M::kName;
    d.options = M::options();
    d.option_values = resolved;
    d.has_delta = d.has_delta || HasDeltaPart<M>;
    return d;
  }

  M model_;
};

}  // namespace roadbrdf
