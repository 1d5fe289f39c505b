// The type-erased BRDF model used by every command, and the adapter that turns a templated
// model struct (one per file in this folder) into it.
//
// A model struct M provides:
//   static constexpr const char* kName;                 // CLI name, e.g. "oren-nayar"
//   static constexpr int kMaxParameters;                // upper bound of the parameter count (checked
//                                                       // when the model is built: std::logic_error)
//   static std::vector<OptionInfo> options();           // discrete choices (may be empty)
//   static ModelDescription describe(const OptionSet&); // parameters for resolved options
//   explicit M(const OptionSet& resolved_options);
//   template <typename T> T operator()(const T* p, const Geometry& g) const;   // smooth BRDF [sr^-1]
// and optionally, for an ideal specular (delta) part f = R(theta_i) delta(w_r - mirror(w_i)) / cos(theta_r):
//   double delta_reflectance(const double* p, double cos_theta_i) const;
// and optionally, to compute geometry-only quantities (trigonometry, half vector...) once per geometry
// instead of once per evaluation (see HasPreparedGeometry below):
//   struct Prepared { ... };                                          // plain data
//   Prepared prepare(const Geometry& g) const;
//   template <typename T> T operator()(const T* p, const Prepared& g) const;
// The Geometry overload of operator() must then return exactly operator()(p, prepare(g)), so that both
// paths give the same values bit for bit. A model with Prepared may also split off its parameter-only
// quantities, computed once per parameter set by the batch paths (see HasCoefficients below):
//   template <typename T> struct Coefficients { ... };
//   template <typename T> Coefficients<T> coefficients(const T* p) const;
//   template <typename T> T operator()(const Coefficients<T>& k, const Prepared& g) const;
// with operator()(p, g) returning exactly operator()(coefficients(p), g).
// A model with Prepared may also share parameter-dependent work between the geometries of a set
// (e.g. a function of one zenith angle evaluated once per distinct angle) and give its gradient
// analytically (see HasSharedTerms below):
//   struct SharedTerms { ... };
//   SharedTerms share(const Prepared* g, std::size_t n) const;
//   void evaluate_shared(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p,
//                        double* values, double* jacobian /* null: values only */) const;
// Its values must be exactly operator()(p, g[k]); every gradient path of the adapter (single, batch,
// prepared) then uses it instead of ceres::Jet, so the gradient paths agree with each other bit for bit.
// A model with Prepared may also precompute, per geometry, terms of parameters that are expected to
// keep given values (the fitter's fixed parameters, e.g. the refractive index of a Torrance-Sparrow
// lobe; see HasExpectedParameters below):
//   Prepared prepare(const Geometry& g, const double* expected) const;
// operator() must check that the parameter still has the expected value and compute the term
// otherwise, so that its values are the same bit for bit whatever `expected` was.
//
// operator() is templated on the scalar so that the fitter differentiates it with ceres::Jet.
// Geometry is plain double: angles are data, parameters are unknowns.
#pragma once

#include <ceres/jet.h>

#include <concepts>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

// Geometry-only data of a set of geometries, computed once by Model::prepare() and then reused by
// Model::evaluate_prepared() / evaluate_prepared_with_gradient() for any number of parameter sets
// (the fitter evaluates the same geometries at every wavelength and iteration). The base class only
// remembers the geometries; models that precompute something derive from it. It refers to the
// geometries passed to prepare(), which must outlive it, and is immutable once built: several threads
// may share one.
class PreparedGeometries {
 public:
  PreparedGeometries(const Geometry* geometries, std::size_t count) : geometries_(geometries), count_(count) {}
  virtual ~PreparedGeometries() = default;
  PreparedGeometries(const PreparedGeometries&) = delete;
  PreparedGeometries& operator=(const PreparedGeometries&) = delete;

  const Geometry* geometries() const { return geometries_; }
  std::size_t size() const { return count_; }

 private:
  const Geometry* geometries_;
  std::size_t count_;
};

class Model;

// Fixed parameter sets evaluated at one geometry at a time: out[s] = f(params_s, g), s < n_sets. The
// path tracer keeps one parameter set per wavelength for a whole render and asks for the spectrum at
// each path vertex; a model may precompute parameter-only work here once (Hapke: its H table reduced
// to the albedo of each set). The base evaluator calls Model::evaluate_batch (same values bit for
// bit); a model's own evaluator must agree with it to rounding. Immutable once built: several threads
// may share one.
class FixedSetEvaluator {
 public:
  FixedSetEvaluator(const Model& model, const double* params, std::size_t n_sets);
  virtual ~FixedSetEvaluator() = default;
  FixedSetEvaluator(const FixedSetEvaluator&) = delete;
  FixedSetEvaluator& operator=(const FixedSetEvaluator&) = delete;

  virtual void evaluate(const Geometry& g, double* out) const;
  std::size_t size() const { return n_sets_; }

 protected:
  const Model& model_;
  std::vector<double> params_;  // n_sets x parameter count, row-major
  std::size_t n_sets_;
};

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
  virtual void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                            double* values, double* jacobian) const = 0;

  // Geometry-only data of `count` geometries for the evaluate_prepared*() calls below (see
  // PreparedGeometries). The default keeps only the geometries.
  virtual std::unique_ptr<PreparedGeometries> prepare(const Geometry* geometries, std::size_t count) const {
    return std::make_unique<PreparedGeometries>(geometries, count);
  }

  // prepare() for evaluations at parameters of which some are expected to stay at the values in
  // `expected` (parameter_count() values; the fitter passes its start, whose fixed parameters never
  // move). Terms of those parameters may be precomputed per geometry; the evaluations give the same
  // values bit for bit at any parameters (a precomputed term is used only where its parameter still
  // has the expected value). The default ignores `expected`.
  virtual std::unique_ptr<PreparedGeometries> prepare_expecting(const Geometry* geometries, std::size_t count,
                                                                const double* /*expected*/) const {
    return prepare(geometries, count);
  }

  // evaluate_batch() for one parameter set at prepared geometries: values[n] = f(params, geometries[n]).
  // Same values as evaluate_batch(prepared.geometries(), prepared.size(), params, 1, values).
  virtual void evaluate_prepared(const PreparedGeometries& prepared, const double* params, double* values) const {
    evaluate_batch(prepared.geometries(), prepared.size(), params, 1, values);
  }

  // evaluate_batch_with_gradient() at prepared geometries (same values and Jacobian).
  virtual void evaluate_prepared_with_gradient(const PreparedGeometries& prepared, const double* params, double* values,
                                               double* jacobian) const {
    evaluate_batch_with_gradient(prepared.geometries(), prepared.size(), params, values, jacobian);
  }

  // Reflectance R(theta_i) of the ideal specular part (0 when the model has none).
  virtual double delta_reflectance(const double* /*params*/, double /*cos_theta_i*/) const { return 0.0; }

  // Whether the evaluations read the angle fields of a Geometry (theta_i, phi_i, theta_r, phi_r) rather
  // than only its direction vectors and cos_delta_phi. A caller that builds geometries from vectors
  // (the path tracer's facet frames) may leave the angles out for a model that does not read them,
  // saving two acos and two atan2 per evaluation. A model struct reads only the vectors unless it
  // declares `static constexpr bool kReadsAngles = true;` (Oren-Nayar); model_properties_test checks
  // every model by evaluating it with the angle fields set to NaN. Classes other than the adapter
  // answer true unless they know better.
  virtual bool reads_angles() const { return true; }

  // `n_sets` parameter sets (as for evaluate_batch) fixed for repeated single-geometry evaluation
  // (FixedSetEvaluator). The default evaluates through evaluate_batch.
  virtual std::unique_ptr<FixedSetEvaluator> fixed_sets(const double* params, std::size_t n_sets) const {
    return std::make_unique<FixedSetEvaluator>(*this, params, n_sets);
  }

 protected:
  explicit Model(ModelDescription description) : description_(std::move(description)) {}
  ModelDescription description_;
};

inline FixedSetEvaluator::FixedSetEvaluator(const Model& model, const double* params, std::size_t n_sets)
    : model_(model), params_(params, params + n_sets * model.parameter_count()), n_sets_(n_sets) {}

inline void FixedSetEvaluator::evaluate(const Geometry& g, double* out) const {
  model_.evaluate_batch(&g, 1, params_.data(), n_sets_, out);
}

template <class M>
concept HasDeltaPart = requires(const M& m, const double* p, double c) {
  { m.delta_reflectance(p, c) } -> std::convertible_to<double>;
};

// A model struct with geometry-only precomputation (see the top of this file).
template <class M>
concept HasPreparedGeometry = requires(const M& m, const double* p, const Geometry& g, const typename M::Prepared& pg) {
  { m.prepare(g) } -> std::same_as<typename M::Prepared>;
  { m(p, pg) } -> std::convertible_to<double>;
};

// A model struct whose prepared geometry may hold terms of expected parameter values (see the top of
// this file).
template <class M>
concept HasExpectedParameters = HasPreparedGeometry<M> && requires(const M& m, const Geometry& g, const double* p) {
  { m.prepare(g, p) } -> std::same_as<typename M::Prepared>;
};

// A model struct with prepared geometry and parameter-only coefficients (see the top of this file).
template <class M>
concept HasCoefficients = HasPreparedGeometry<M> &&
    requires(const M& m, const double* p, const typename M::Prepared& pg) {
  { m(m.coefficients(p), pg) } -> std::convertible_to<double>;
};

// A model struct with terms shared by a set of prepared geometries and an analytic gradient (see the
// top of this file).
template <class M>
concept HasSharedTerms = HasPreparedGeometry<M> &&
    requires(const M& m, const typename M::Prepared* g, std::size_t n, const typename M::SharedTerms& s,
             const double* p, double* out) {
  { m.share(g, n) } -> std::same_as<typename M::SharedTerms>;
  m.evaluate_shared(s, g, n, p, out, out);
};

// A model struct with its own evaluator of fixed parameter sets (see FixedSetEvaluator):
//   struct FixedSets { ... };                                  // parameter-only data of n sets
//   FixedSets fix(const double* p, std::size_t n) const;
//   void evaluate_fixed(const FixedSets& f, const Geometry& g, double* out) const;  // out[s], s < n
// with values equal to operator()(p_s, g) to rounding.
template <class M>
concept HasFixedSets = requires(const M& m, const double* p, std::size_t n, const typename M::FixedSets& f,
                                const Geometry& g, double* out) {
  { m.fix(p, n) } -> std::same_as<typename M::FixedSets>;
  m.evaluate_fixed(f, g, out);
};

template <class M>
struct FixedSetsOf {
  struct type {};
};
template <HasFixedSets M>
struct FixedSetsOf<M> {
  using type = typename M::FixedSets;
};

template <class M>
struct SharedTermsOf {
  struct type {};
};
template <HasSharedTerms M>
struct SharedTermsOf<M> {
  using type = typename M::SharedTerms;
};

// What ModelAdapter keeps per geometry: M::Prepared, or the Geometry itself for models without it.
template <class M>
struct PreparedGeometryOf {
  using type = Geometry;
};
template <HasPreparedGeometry M>
struct PreparedGeometryOf<M> {
  using type = typename M::Prepared;
};

template <class M>
class ModelAdapter final : public Model {
 public:
  explicit ModelAdapter(const OptionSet& given) : ModelAdapter(given, M::kName) {}
  // Under another name (a ModelAlias): the description, and so every file written, carries `name`.
  ModelAdapter(const OptionSet& given, const std::string& name)
      : Model(describe_resolved(resolve_options(name, M::options(), given), name)),
        model_(description().option_values) {}

  double evaluate(const double* params, const Geometry& g) const override { return model_(params, g); }

  double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const override {
    if constexpr (HasSharedTerms<M>) {
      const auto q = model_.prepare(g);
      double f = 0.0;
      model_.evaluate_shared(model_.share(&q, 1), &q, 1, params, &f, gradient);
      return f;
    }
    return with_jet_size([&](auto size) {
      using J = ceres::Jet<double, decltype(size)::value>;
      const std::size_t n = parameter_count();
      J p[decltype(size)::value];
      for (std::size_t k = 0; k < n; ++k) p[k] = J(params[k], static_cast<int>(k));
      const J f = model_(p, g);
      for (std::size_t k = 0; k < n; ++k) gradient[k] = f.v[static_cast<int>(k)];
      return f.a;
    });
  }

  // Each geometry is prepared once and evaluated for all parameter sets.
  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override {
    const std::size_t n_params = parameter_count();
    for (std::size_t n = 0; n < n_geometries; ++n) {
      const auto& g = prepare_one(geometries[n]);
      double* row = out + n * n_sets;
      for (std::size_t s = 0; s < n_sets; ++s) row[s] = model_(params + s * n_params, g);
    }
  }

  void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    double* values, double* jacobian) const override {
    if constexpr (HasSharedTerms<M>) {
      std::vector<GeometryData> data;
      data.reserve(n_geometries);
      for (std::size_t n = 0; n < n_geometries; ++n) data.push_back(model_.prepare(geometries[n]));
      model_.evaluate_shared(model_.share(data.data(), n_geometries), data.data(), n_geometries, params, values,
                             jacobian);
      return;
    }
    with_jet_size([&](auto size) {
      using J = ceres::Jet<double, decltype(size)::value>;
      const std::size_t n_params = parameter_count();
      J p[decltype(size)::value];
      for (std::size_t k = 0; k < n_params; ++k) p[k] = J(params[k], static_cast<int>(k));
      for (std::size_t n = 0; n < n_geometries; ++n) {
        const J f = model_(p, prepare_one(geometries[n]));
        values[n] = f.a;
        for (std::size_t k = 0; k < n_params; ++k) jacobian[n * n_params + k] = f.v[static_cast<int>(k)];
      }
    });
  }

  std::unique_ptr<PreparedGeometries> prepare(const Geometry* geometries, std::size_t count) const override {
    return std::make_unique<Prepared>(*this, geometries, count, nullptr);
  }

  std::unique_ptr<PreparedGeometries> prepare_expecting(const Geometry* geometries, std::size_t count,
                                                        const double* expected) const override {
    return std::make_unique<Prepared>(*this, geometries, count, expected);
  }

  void evaluate_prepared(const PreparedGeometries& prepared, const double* params, double* values) const override {
    const auto* own = dynamic_cast<const Prepared*>(&prepared);
    if (own == nullptr || own->adapter != this) return Model::evaluate_prepared(prepared, params, values);
    if constexpr (HasSharedTerms<M>) {
      model_.evaluate_shared(own->shared, own->data.data(), own->size(), params, values, nullptr);
    } else if constexpr (HasCoefficients<M>) {
      const auto k = model_.coefficients(params);
      for (std::size_t n = 0; n < own->size(); ++n) values[n] = model_(k, own->at(n));
    } else {
      for (std::size_t n = 0; n < own->size(); ++n) values[n] = model_(params, own->at(n));
    }
  }

  void evaluate_prepared_with_gradient(const PreparedGeometries& prepared, const double* params, double* values,
                                       double* jacobian) const override {
    const auto* own = dynamic_cast<const Prepared*>(&prepared);
    if (own == nullptr || own->adapter != this) {
      return Model::evaluate_prepared_with_gradient(prepared, params, values, jacobian);
    }
    if constexpr (HasSharedTerms<M>) {
      model_.evaluate_shared(own->shared, own->data.data(), own->size(), params, values, jacobian);
      return;
    }
    with_jet_size([&](auto size) {
      using J = ceres::Jet<double, decltype(size)::value>;
      const std::size_t n_params = parameter_count();
      J p[decltype(size)::value];
      for (std::size_t k = 0; k < n_params; ++k) p[k] = J(params[k], static_cast<int>(k));
      auto store = [&](std::size_t n, const J& f) {
        values[n] = f.a;
        for (std::size_t k = 0; k < n_params; ++k) jacobian[n * n_params + k] = f.v[static_cast<int>(k)];
      };
      if constexpr (HasCoefficients<M>) {
        const auto coefficients = model_.coefficients(p);
        for (std::size_t n = 0; n < own->size(); ++n) store(n, model_(coefficients, own->at(n)));
      } else {
        for (std::size_t n = 0; n < own->size(); ++n) store(n, model_(p, own->at(n)));
      }
    });
  }

  double delta_reflectance(const double* params, double cos_theta_i) const override {
    if constexpr (HasDeltaPart<M>) {
      return model_.delta_reflectance(params, cos_theta_i);
    } else {
      return 0.0;
    }
  }

  bool reads_angles() const override {
    if constexpr (requires { M::kReadsAngles; }) {
      return M::kReadsAngles;
    } else {
      return false;
    }
  }

  std::unique_ptr<FixedSetEvaluator> fixed_sets(const double* params, std::size_t n_sets) const override {
    if constexpr (HasFixedSets<M>) {
      return std::make_unique<FixedSets>(*this, params, n_sets);
    } else {
      return Model::fixed_sets(params, n_sets);
    }
  }

  const M& model() const { return model_; }

 private:
  // The gradient paths differentiate with ceres::Jet<double, N>, every operation of which costs in
  // proportion to N: N = kSmallJet when the resolved options describe no more parameters (a one-lobe
  // Lafortune has 5 of its kMaxParameters = 21), else M::kMaxParameters. Each derivative is computed
  // by the same operations whatever N, so the gradients are the same numbers.
  static constexpr int kSmallJet = 8;
  template <typename Body>
  auto with_jet_size(Body&& body) const {
    if constexpr (M::kMaxParameters > kSmallJet) {
      if (parameter_count() <= static_cast<std::size_t>(kSmallJet)) {
        return body(std::integral_constant<int, kSmallJet>{});
      }
    }
    return body(std::integral_constant<int, M::kMaxParameters>{});
  }
  using GeometryData = typename PreparedGeometryOf<M>::type;

  // M::Prepared by value, or a reference to the geometry itself.
  decltype(auto) prepare_one(const Geometry& g) const {
    if constexpr (HasPreparedGeometry<M>) {
      return model_.prepare(g);
    } else {
      return (g);
    }
  }

  // M::Prepared of every geometry (models without it: the geometries are used directly).
  struct Prepared final : PreparedGeometries {
    Prepared(const ModelAdapter& owner, const Geometry* geometries, std::size_t count, const double* expected)
        : PreparedGeometries(geometries, count), adapter(&owner) {
      if constexpr (HasPreparedGeometry<M>) {
        data.reserve(count);
        for (std::size_t n = 0; n < count; ++n) {
          if constexpr (HasExpectedParameters<M>) {
            data.push_back(expected != nullptr ? owner.model_.prepare(geometries[n], expected)
                                               : owner.model_.prepare(geometries[n]));
          } else {
            data.push_back(owner.model_.prepare(geometries[n]));
          }
        }
      }
      if constexpr (HasSharedTerms<M>) shared = owner.model_.share(data.data(), count);
    }
    const GeometryData& at(std::size_t n) const {
      if constexpr (HasPreparedGeometry<M>) {
        return data[n];
      } else {
        return geometries()[n];
      }
    }
    const ModelAdapter* adapter;  // the adapter that built it
    std::vector<GeometryData> data;
    typename SharedTermsOf<M>::type shared;  // empty unless HasSharedTerms<M>
  };

  // The model's own fixed-set data (models with HasFixedSets only).
  struct FixedSets final : FixedSetEvaluator {
    FixedSets(const ModelAdapter& owner, const double* params, std::size_t n_sets)
        : FixedSetEvaluator(owner, params, n_sets), adapter(owner), data(owner.model_.fix(params, n_sets)) {}
    void evaluate(const Geometry& g, double* out) const override { adapter.model_.evaluate_fixed(data, g, out); }
    const ModelAdapter& adapter;
    typename FixedSetsOf<M>::type data;
  };

  static ModelDescription describe_resolved(const OptionSet& resolved, const std::string& name) {
    ModelDescription d = M::describe(resolved);
    // The gradient paths hold the parameters in ceres::Jet<double, M::kMaxParameters> arrays of that
    // size: a description with more parameters is a defect of the model's header, not of the input.
    if (d.parameters.size() > static_cast<std::size_t>(M::kMaxParameters)) {
      throw std::logic_error("model '" + name + "' describes " + std::to_string(d.parameters.size()) +
                             " parameters, more than its kMaxParameters = " + std::to_string(M::kMaxParameters));
    }
    d.name = name;
    d.options = M::options();
    d.option_values = resolved;
    d.has_delta = d.has_delta || HasDeltaPart<M>;
    return d;
  }

  M model_;
};

}  // namespace roadbrdf
