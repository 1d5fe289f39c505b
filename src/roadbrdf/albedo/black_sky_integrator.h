// Internal to the hemispherical integrals (hemisphere.cpp, white_sky.cpp): the adaptive black-sky
// rule of hemisphere.h, as a class shared by black_sky() and the inner integrals of white_sky().
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::albedo::detail {

// An integrand that evaluates a batch of geometries for all its parameter sets in its own way
// (gradient_integrals.cpp: every derivative of a set from one gradient evaluation).
class SetBatchIntegrand {
 public:
  virtual ~SetBatchIntegrand() = default;
  // out[n * n_sets + s] for n < n_geometries, s < n_sets, as Model::evaluate_batch.
  virtual void evaluate_sets(const Geometry* geometries, std::size_t n_geometries, const double* params,
                             std::size_t n_sets, double* out) const = 0;
};

// Values of `n_sets` parameter sets at a batch of geometries, out[n * n_sets + s]. A model that
// prepares its geometries (Model::prepare: geometry-only terms, and shared terms such as Hapke's H
// per distinct cosine) is prepared once for the batch and evaluated set by set, as the fitter does;
// parameter-only work is then done once per set and batch instead of once per evaluation. Models
// without preparation of their own (mixtures, composites) are evaluated by evaluate_batch, which
// prepares their components once for all sets. Same values as evaluate_batch to rounding.
// Whether every parameter of the model is a linear amplitude (ParameterInfo::linear: the fitter solves
// them jointly by linear least squares, so the BRDF is affine in them together), e.g. Lambert, Ross-Li.
inline bool affine_in_every_parameter(const ModelDescription& d) {
  return !d.parameters.empty() &&
         std::all_of(d.parameters.begin(), d.parameters.end(), [](const ParameterInfo& p) { return p.linear; });
}

// A model affine in every parameter: f(p_s) = f(p_0) + J(p_0) (p_s - p_0) for every set s, from one
// evaluation with gradient per geometry (Ross-Li's kernels once per geometry instead of once per
// wavelength). Checked on the last set against a direct evaluation (relative 1e-9); false, with
// nothing written, if it disagrees.
inline bool evaluate_affine_sets(const Model& model, const Geometry* geometries, std::size_t n_geometries,
                                 const double* params, std::size_t n_sets, double* out) {
  const std::size_t P = model.parameter_count();
  std::vector<double> values(n_geometries), jacobian(n_geometries * P), check(n_geometries);
  model.evaluate_batch_with_gradient(geometries, n_geometries, params, values.data(), jacobian.data());
  auto affine = [&](std::size_t n, std::size_t s) {
    double f = values[n];
    for (std::size_t k = 0; k < P; ++k) f += jacobian[n * P + k] * (params[s * P + k] - params[k]);
    return f;
  };
  model.evaluate_batch(geometries, n_geometries, params + (n_sets - 1) * P, 1, check.data());
  for (std::size_t n = 0; n < n_geometries; ++n) {
    const double f = affine(n, n_sets - 1);
    if (!(std::fabs(f - check[n]) <= 1e-9 * (std::fabs(check[n]) + std::fabs(values[n])) + 1e-300)) return false;
  }
  for (std::size_t n = 0; n < n_geometries; ++n) {
    for (std::size_t s = 0; s < n_sets; ++s) out[n * n_sets + s] = affine(n, s);
  }
  return true;
}

inline void evaluate_sets(const Model& model, const Geometry* geometries, std::size_t n_geometries,
                          const double* params, std::size_t n_sets, double* out, std::vector<double>& column) {
  if (n_sets > 2 && affine_in_every_parameter(model.description()) &&
      evaluate_affine_sets(model, geometries, n_geometries, params, n_sets, out)) {
    return;
  }
  const std::unique_ptr<PreparedGeometries> prepared = model.prepare(geometries, n_geometries);
  const PreparedGeometries& own = *prepared;
  if (typeid(own) == typeid(PreparedGeometries)) {
    model.evaluate_batch(geometries, n_geometries, params, n_sets, out);
    return;
  }
  const std::size_t P = model.parameter_count();
  column.resize(n_geometries);
  for (std::size_t s = 0; s < n_sets; ++s) {
    model.evaluate_prepared(*prepared, params + s * P, column.data());
    for (std::size_t n = 0; n < n_geometries; ++n) out[n * n_sets + s] = column[n];
  }
}

// The model's own evaluator of fixed parameter sets (model.h, FixedSetEvaluator), or null if it has
// none (the base evaluator only calls evaluate_batch). Hapke's reduces its H table to each set's albedo
// once (a one-variable series per set), so an H costs 12 multiply-adds per set instead of a
// two-variable table evaluation; its values equal evaluate_batch's to rounding (a few units in the
// last place, hapke_h_table.h). That pays where nearly every geometry has a cosine of its own (the
// mirror-polar rule: an H per geometry and set), not in the (mu, dphi) rule, whose batches share a
// few cosines and are prepared once (evaluate_sets), nor where the series would be built for each of
// many short integrals (white-sky's inner ones).
inline std::unique_ptr<FixedSetEvaluator> own_fixed_sets(const Model& model, const double* params, std::size_t n_sets) {
  if (n_sets == 0 || dynamic_cast<const SetBatchIntegrand*>(&model) != nullptr) return nullptr;
  std::unique_ptr<FixedSetEvaluator> fixed = model.fixed_sets(params, n_sets);
  const FixedSetEvaluator& own = *fixed;
  if (typeid(own) == typeid(FixedSetEvaluator)) return nullptr;
  return fixed;
}

// Evaluates batches of geometries for all parameter sets and accumulates weighted sums per target row.
// With `fixed` (own_fixed_sets of the same model, parameters and sets), geometry by geometry through it.
class Accumulator {
 public:
  Accumulator(const Model& model, const double* params, std::size_t n_sets, const FixedSetEvaluator* fixed = nullptr)
      : model_(model),
        batch_(dynamic_cast<const SetBatchIntegrand*>(&model)),
        fixed_(fixed),
        params_(params),
        n_sets_(n_sets) {}

  // Queue one geometry: its values are added with weight w1 to acc1[row] and w2 to acc2[row] (acc2 may be null).
  void add(const Geometry& g, std::size_t row, double w1, double w2) {
    geometries_.push_back(g);
    rows_.push_back(row);
    w1_.push_back(w1);
    w2_.push_back(w2);
    if (geometries_.size() == kChunk) flush();
  }
  void set_targets(double* acc1, double* acc2) {
    flush();
    acc1_ = acc1;
    acc2_ = acc2;
  }
  void flush() {
    if (geometries_.empty()) return;
    const std::size_t n = geometries_.size();
    out_.resize(n * n_sets_);
    if (batch_ != nullptr) {
      batch_->evaluate_sets(geometries_.data(), n, params_, n_sets_, out_.data());
    } else if (fixed_ != nullptr) {
      for (std::size_t k = 0; k < n; ++k) fixed_->evaluate(geometries_[k], out_.data() + k * n_sets_);
    } else {
      evaluate_sets(model_, geometries_.data(), n, params_, n_sets_, out_.data(), column_);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const double* f = out_.data() + k * n_sets_;
      double* a1 = acc1_ + rows_[k] * n_sets_;
      const double w1 = w1_[k];
      for (std::size_t s = 0; s < n_sets_; ++s) a1[s] += w1 * f[s];
      if (acc2_ != nullptr && w2_[k] != 0.0) {
        double* a2 = acc2_ + rows_[k] * n_sets_;
        const double w2 = w2_[k];
        for (std::size_t s = 0; s < n_sets_; ++s) a2[s] += w2 * f[s];
      }
    }
    count_ += n;
    geometries_.clear();
    rows_.clear();
    w1_.clear();
    w2_.clear();
  }
  std::size_t count() const { return count_ + geometries_.size(); }

 private:
  static constexpr std::size_t kChunk = 48;
  const Model& model_;
  const SetBatchIntegrand* batch_;
  const FixedSetEvaluator* fixed_;
  const double* params_;
  std::size_t n_sets_;
  std::vector<Geometry> geometries_;
  std::vector<std::size_t> rows_;
  std::vector<double> w1_, w2_;
  std::vector<double> out_, column_;
  double* acc1_ = nullptr;
  double* acc2_ = nullptr;
  std::size_t count_ = 0;
};

inline void check_finite(const std::vector<double>& values, const Model& model, double theta_s) {
  for (double v : values) {
    if (!std::isfinite(v)) {
      throw InputError("model '" + model.name() + "' returned a non-finite BRDF while integrating at sun zenith " +
                       std::to_string(rad_to_deg(theta_s)) + " deg");
    }
  }
}

// One Gauss-Kronrod node in mu (or, mirror-polar, in s) with its azimuth trapezoid (iterated
// integration; the nodes of one panel share their azimuth count, see run()).
struct MuNode {
  double mu = 0.0;
  double theta = 0.0;
  double wk = 0.0;          // Kronrod weight x half-length x mu
  double wg = 0.0;          // Gauss weight x half-length x mu (0 for Kronrod-only nodes)
  int n = 4;                // trapezoid intervals over the azimuth range
  std::vector<double> t;    // azimuth integral with n intervals, per set
  std::vector<double> tc;   // with n/2 intervals
  std::vector<double> err;  // wk |t - tc|: this node's azimuthal error contribution, per set
};

struct Panel {
  double a = 0.0, b = 1.0;        // mu range
  std::array<MuNode, 15> nodes;   // the K15 nodes
  std::vector<double> q, err_mu;  // per set: K15 value and |K15 - G7|
};

class BlackSkyIntegrator {
 public:
  BlackSkyIntegrator(const Model& model, const double* params, std::size_t n_sets, double theta_s, double phi_s,
                     bool isotropic, bool mirror_polar = false, const FixedSetEvaluator* fixed = nullptr)
      : model_(model),
        params_(params),
        n_sets_(n_sets),
        theta_s_(theta_s),
        phi_s_(phi_s),
        isotropic_(isotropic),
        polar_(mirror_polar),
        acc_(model, params, n_sets, fixed) {
    if (!(theta_s >= 0.0 && theta_s < kPi / 2)) {
      throw InputError("sun zenith " + std::to_string(rad_to_deg(theta_s)) + " deg is outside [0, 90) deg");
    }
    // Sub-intervals of the relative azimuth, split at the specular plane (pi) and at pi/2.
    // Isotropic: the integrand is even about dphi = 0 and pi, so [0, pi] counts twice.
    starts_ = isotropic_ ? std::vector<double>{0.0, 0.5 * kPi} : std::vector<double>{0.0, 0.5 * kPi, kPi, 1.5 * kPi};
    factor_ = isotropic_ ? 2.0 : 1.0;
    n0_ = 8;  // smallest n for which the n/2 rule is exact for constants (sin^4 has frequency 2)
    // Mirror-polar frame: e3 = mirror direction (theta_s, phi_s + pi), e1 = towards the normal in the
    // plane of incidence, e2 = e3 x e1 (horizontal).
    const double ct = std::cos(theta_s), st = std::sin(theta_s);
    const double cp = std::cos(phi_s + kPi), sp = std::sin(phi_s + kPi);
    e3_[0] = st * cp;
    e3_[1] = st * sp;
    e3_[2] = ct;
    e1_[0] = -ct * cp;
    e1_[1] = -ct * sp;
    e1_[2] = st;
    e2_[0] = -sp;
    e2_[1] = cp;
    e2_[2] = 0.0;
  }

  // One quadrature point: outer coordinate x of `node` (mu, or the scaled polar angle s) and azimuth
  // angle a (relative azimuth dphi, or the polar azimuth psi about the mirror direction); `w` is the
  // azimuth weight, multiplied here by the Jacobian of the mirror-polar map.
  void add_point(const MuNode& node, double a, std::size_t row, double w, double wc) {
    if (!polar_) {
      acc_.add(geometry_from_radians(theta_s_, phi_s_, node.theta, phi_s_ + a), row, w, wc);
      return;
    }
    // w_r = cos(rho) e3 + sin(rho) (cos(psi) e1 + sin(psi) e2), rho = s rho_max(psi), where rho_max is
    // the horizon: z = cos(rho) cos(theta_s) + sin(rho) cos(psi) sin(theta_s) = 0.
    const double cpsi = std::cos(a), spsi = std::sin(a);
    const double ct = std::cos(theta_s_), st = std::sin(theta_s_);
    const double rho_max = std::atan2(ct, -st * cpsi);
    const double rho = node.mu * rho_max;
    const double cr = std::cos(rho), sr = std::sin(rho);
    double v[3];
    for (int i = 0; i < 3; ++i) v[i] = cr * e3_[i] + sr * (cpsi * e1_[i] + spsi * e2_[i]);
    const double z = std::clamp(v[2], 0.0, 1.0);
    const double jac = z * sr * rho_max;  // cos(theta_r) dOmega = z sin(rho) rho_max ds dpsi
    const double phi_r = std::atan2(v[1], v[0]);
    acc_.add(geometry_from_radians(theta_s_, phi_s_, std::acos(z), phi_r), row, w * jac, wc * jac);
  }

  static auto constant_n(int n) {
    return [n](double) { return n; };
  }
  // Azimuth sub-interval [start, start + pi/2] mapped from t in [0, 1] by Sidi's sin^4 transformation
  //   dphi = (pi/2) psi(t),  psi(t) = t - 2 sin(2 pi t)/(3 pi) + sin(4 pi t)/(12 pi),  psi'(t) = (8/3) sin^4(pi t):
  // the transformed integrand and its first three derivatives vanish at both ends, so the trapezoid
  // rule in t converges as O(h^6) even though the integrand has kinks at the sub-interval ends
  // (Oren-Nayar's max(0, cos dphi) and |cos dphi| at dphi = pi/2) and is not periodic on them.
  // The end nodes have weight 0 and are never evaluated; doubling n reuses every node.
  static double azimuth_offset(double t) {
    return 0.5 * kPi * (t - 2.0 * std::sin(2.0 * kPi * t) / (3.0 * kPi) + std::sin(4.0 * kPi * t) / (12.0 * kPi));
  }
  double azimuth_weight(double t, int n) const {
    const double s = std::sin(kPi * t);
    return factor_ * 0.5 * kPi * (8.0 / 3.0) * s * s * s * s / n;
  }

  // Panel with fresh nodes; node j gets n_of(mu_j) azimuth intervals (a power of 2 times n0).
  template <class NOf>
  Panel make_panel(double a, double b, NOf n_of) {
    const KronrodRule& r = kronrod15();
    Panel p;
    p.a = a;
    p.b = b;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    std::vector<double> t(15 * n_sets_, 0.0), tc(15 * n_sets_, 0.0);
    acc_.set_targets(t.data(), tc.data());
    for (int j = 0; j < 15; ++j) {
      MuNode& node = p.nodes[j];
      node.mu = mid + half * r.x[j];
      node.theta = std::acos(std::clamp(node.mu, 0.0, 1.0));
      const double cosine = polar_ ? 1.0 : node.mu;  // polar: the cosine is in the azimuth weight
      node.wk = half * r.wk[j] * cosine;
      node.wg = half * r.wg[j] * cosine;
      const int n = n_of(node.mu);
      node.n = n;
      for (int k = 1; k < n; ++k) {
        const double tk = static_cast<double>(k) / n;
        const double w = azimuth_weight(tk, n);
        const double wc = (k % 2 == 0) ? azimuth_weight(tk, n / 2) : 0.0;
        for (const double start : starts_) {
          add_point(node, start + azimuth_offset(tk), static_cast<std::size_t>(j), w, wc);
        }
      }
    }
    acc_.flush();
    for (int j = 0; j < 15; ++j) {
      MuNode& node = p.nodes[j];
      node.t.assign(t.begin() + static_cast<std::ptrdiff_t>(j * n_sets_),
                    t.begin() + static_cast<std::ptrdiff_t>((j + 1) * n_sets_));
      node.tc.assign(tc.begin() + static_cast<std::ptrdiff_t>(j * n_sets_),
                     tc.begin() + static_cast<std::ptrdiff_t>((j + 1) * n_sets_));
      node_error(node);
    }
    panel_sums(p);
    return p;
  }

  void node_error(MuNode& node) {
    node.err.resize(n_sets_);
    for (std::size_t s = 0; s < n_sets_; ++s) node.err[s] = node.wk * std::fabs(node.t[s] - node.tc[s]);
  }

  void panel_sums(Panel& p) {
    p.q.assign(n_sets_, 0.0);
    p.err_mu.assign(n_sets_, 0.0);
    std::vector<double> qg(n_sets_, 0.0);
    for (const MuNode& node : p.nodes) {
      for (std::size_t s = 0; s < n_sets_; ++s) {
        p.q[s] += node.wk * node.t[s];
        qg[s] += node.wg * node.t[s];
      }
    }
    for (std::size_t s = 0; s < n_sets_; ++s) p.err_mu[s] = std::fabs(p.q[s] - qg[s]);
    check_finite(p.q, model_, theta_s_);
  }

  // Double the number of azimuth intervals of one node, reusing its nodes.
  void refine_azimuth(MuNode& node) {
    const int n2 = 2 * node.n;
    node.tc = node.t;
    for (double& v : node.t) v *= 0.5;
    acc_.set_targets(node.t.data(), nullptr);
    for (int k = 1; k < n2; k += 2) {
      const double t = static_cast<double>(k) / n2;
      const double w = azimuth_weight(t, n2);
      for (const double start : starts_) {
        add_point(node, start + azimuth_offset(t), 0, w, 0.0);
      }
    }
    acc_.flush();
    node.n = n2;
    node_error(node);
  }

  // Outer breakpoints. Polar: s graded geometrically towards the mirror direction (s = 2^-k), so a
  // lobe of any width down to ~1e-4 rad starts on panels of its own size.
  std::vector<double> breakpoints() const {
    std::vector<double> b;
    if (polar_) {
      b.push_back(0.0);
      for (int k = kPolarLevels; k >= 0; --k) b.push_back(std::ldexp(1.0, -k));
      return b;
    }
    const double mu_s = std::cos(theta_s_);
    b.push_back(0.0);
    if (mu_s > 1e-12 && mu_s < 1.0 - 1e-12) b.push_back(mu_s);
    b.push_back(1.0);
    return b;
  }

  // Restrict the outer mu to [0, cos(theta_s)] and halve the delta part (white-sky by reciprocity).
  void set_lower_triangle() { lower_ = true; }

  std::vector<Panel> initial_panels() {
    const double mu_s = std::cos(theta_s_);
    std::vector<Panel> panels;
    if (lower_) {
      panels.push_back(make_panel(0.0, mu_s, constant_n(n0_)));
    } else if (polar_) {
      const std::vector<double> b = breakpoints();
      for (std::size_t i = 0; i + 1 < b.size(); ++i) panels.push_back(make_panel(b[i], b[i + 1], constant_n(n0_)));
    } else if (mu_s > 1e-12 && mu_s < 1.0 - 1e-12) {
      panels.push_back(make_panel(0.0, mu_s, constant_n(n0_)));
      panels.push_back(make_panel(mu_s, 1.0, constant_n(n0_)));
    } else {
      panels.push_back(make_panel(0.0, 1.0, constant_n(n0_)));
    }
    return panels;
  }

  SpectralIntegral collect(const std::vector<Panel>& panels, bool converged) {
    SpectralIntegral result;
    result.converged = converged;
    result.value.assign(n_sets_, 0.0);
    result.error.assign(n_sets_, 0.0);
    for (const Panel& p : panels) {
      for (std::size_t s = 0; s < n_sets_; ++s) {
        result.value[s] += p.q[s];
        result.error[s] += p.err_mu[s];
      }
      for (const MuNode& node : p.nodes) {
        for (std::size_t s = 0; s < n_sets_; ++s) result.error[s] += node.err[s];
      }
    }
    const double mu_s = std::cos(theta_s_);
    const std::size_t n_params = model_.parameter_count();
    for (std::size_t s = 0; s < n_sets_; ++s) {
      result.value[s] += (lower_ ? 0.5 : 1.0) * model_.delta_reflectance(params_ + s * n_params, mu_s);
    }
    result.geometries = acc_.count();
    return result;
  }

  SpectralIntegral run(const QuadratureSettings& settings) {
    std::vector<Panel> panels = initial_panels();
    bool converged = true;
    // Per-set summed error estimate, kept up to date incrementally.
    std::vector<double> total(n_sets_, 0.0);
    auto add_panel = [&](const Panel& p, double sign) {
      for (std::size_t s = 0; s < n_sets_; ++s) total[s] += sign * p.err_mu[s];
      for (const MuNode& node : p.nodes) {
        for (std::size_t s = 0; s < n_sets_; ++s) total[s] += sign * node.err[s];
      }
    };
    for (const Panel& p : panels) add_panel(p, 1.0);
    std::size_t steps = 0;
    while (n_sets_ > 0) {
      if (++steps % 64 == 0) {  // limit the drift of the incremental sums
        std::fill(total.begin(), total.end(), 0.0);
        for (const Panel& p : panels) add_panel(p, 1.0);
      }
      const std::size_t worst = settings.worst_set(total.data(), n_sets_);
      if (worst == n_sets_) break;
      if (acc_.count() >= settings.max_geometries) {
        converged = false;
        break;
      }
      // The largest single contribution of the worst set: a panel's mu error or a node's azimuth error.
      std::size_t target_panel = 0;
      int target_node = -1;  // -1: the panel's mu error
      double largest = -1.0;
      for (std::size_t i = 0; i < panels.size(); ++i) {
        if (panels[i].err_mu[worst] > largest) {
          largest = panels[i].err_mu[worst];
          target_panel = i;
          target_node = -1;
        }
        for (int j = 0; j < 15; ++j) {
          if (panels[i].nodes[j].err[worst] > largest) {
            largest = panels[i].nodes[j].err[worst];
            target_panel = i;
            target_node = j;
          }
        }
      }
      Panel& p = panels[target_panel];
      if (target_node >= 0 && p.nodes[target_node].n < (1 << 16)) {
        add_panel(p, -1.0);
        // All nodes of a panel share one azimuth count and are refined together, so the
        // azimuth-integrated integrand is a smooth function of the outer variable on the panel. (Counts
        // per node made the nodes' differing azimuth errors look like noise in mu, which the K15 - G7
        // estimate cannot resolve: near-mirror lobes then never converged.)
        for (MuNode& node : p.nodes) refine_azimuth(node);
        panel_sums(p);
        add_panel(p, 1.0);
      } else if (p.b - p.a > 1e-9) {
        add_panel(p, -1.0);
        // The children start with the parent's azimuth count.
        const Panel parent = std::move(p);
        auto inherited = [&parent](double) { return parent.nodes[0].n; };
        const double a = parent.a, b = parent.b, m = 0.5 * (a + b);
        panels[target_panel] = make_panel(a, m, inherited);
        panels.push_back(make_panel(m, b, inherited));
        add_panel(panels[target_panel], 1.0);
        add_panel(panels.back(), 1.0);
      } else {
        converged = false;
        break;
      }
    }
    return collect(panels, converged);
  }

  SpectralIntegral run_fixed(int mu_panels, int phi_intervals) {
    std::vector<Panel> panels;
    auto split = [&](double a, double b) {
      for (int i = 0; i < mu_panels; ++i) {
        panels.push_back(make_panel(a + (b - a) * i / mu_panels, a + (b - a) * (i + 1) / mu_panels,
                                    constant_n(std::max(2, phi_intervals))));
      }
    };
    const std::vector<double> b = breakpoints();
    for (std::size_t i = 0; i + 1 < b.size(); ++i) split(b[i], b[i + 1]);
    SpectralIntegral result = collect(panels, false);
    std::fill(result.error.begin(), result.error.end(), 0.0);
    return result;
  }

 private:
  const Model& model_;
  const double* params_;
  std::size_t n_sets_;
  double theta_s_, phi_s_;
  bool isotropic_;
  bool polar_ = false;
  bool lower_ = false;
  static constexpr int kPolarLevels = 13;
  double e1_[3], e2_[3], e3_[3];
  std::vector<double> starts_;
  double factor_ = 2.0;
  int n0_ = 8;
  Accumulator acc_;
};

}  // namespace roadbrdf::albedo::detail
