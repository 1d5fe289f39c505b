#include "roadbrdf/fitting/fit.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <condition_variable>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt_double(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// The data of one fit, prepared once: per point multipliers and the loss.
struct Prepared {
  const Model* model = nullptr;
  std::size_t p = 0;          // parameter count
  std::size_t n = 0;          // geometries
  std::size_t m = 0;          // wavelengths
  FitLoss loss = FitLoss::kPlain;
  const Geometry* geometries = nullptr;
  // Geometry-only data of `geometries` (Model::prepare), built once and shared by every wavelength,
  // iteration and thread.
  std::shared_ptr<const PreparedGeometries> prepared_geometries;
  std::vector<double> y;      // M x N (wavelength-major: y[w * n + g]) for contiguous access
  std::vector<double> mult;   // M x N multiplier of the loss residual (sqrt solid angle / sigma [/ |y|] [* c])
  std::vector<double> cos_i;  // N
  std::vector<double> lin_weight;  // M x N weight of (f - y) in the linearised loss (for the amplitude solve)

  RobustLoss robust = RobustLoss::kNone;
  double robust_b = 1.0;  // scale^2

  // Residuals r[g] (and, if jac != nullptr, jac[g * p + k] = dr/dp_k) of wavelength w at full params.
  // scratch_f: N, scratch_j: N * p. Returns false where the loss is undefined (log of <= 0).
  // With a robust loss rho (and apply_robust), each residual is replaced by sign(r) sqrt(rho(r^2)),
  // so that 1/2 sum of squares is 1/2 sum rho(r_g^2) per point. (Ceres' LossFunction would act on
  // the squared norm of the whole residual block, i.e. of all geometries together.)
  bool residuals(std::size_t w, const double* params, double* r, double* jac, double* scratch_f,
                 double* scratch_j, bool apply_robust = true) const {
    if (jac != nullptr) {
      model->evaluate_prepared_with_gradient(*prepared_geometries, params, scratch_f, scratch_j);
    } else {
      model->evaluate_prepared(*prepared_geometries, params, scratch_f);
    }
    return residuals_of_values(w, scratch_f, jac != nullptr ? scratch_j : nullptr, r, jac, apply_robust);
  }

  // The same from model values f (N) and, if jac != nullptr, their gradients model_jac (N x p).
  bool residuals_of_values(std::size_t w, const double* scratch_f, const double* scratch_j, double* r, double* jac,
                           bool apply_robust) const {
    const double* yw = y.data() + w * n;
    const double* mw = mult.data() + w * n;
    for (std::size_t g = 0; g < n; ++g) {
      const double f = scratch_f[g];
      double d = 0.0;   // dr/df
      if (loss == FitLoss::kLog) {
        const double c = cos_i[g];
        const double a = 1.0 + f * c;
        if (!(a > 0.0) || !std::isfinite(f)) return false;
        r[g] = mw[g] * (std::log(a) - std::log(1.0 + yw[g] * c));
        d = mw[g] * c / a;
      } else {
        if (!std::isfinite(f)) return false;
        r[g] = mw[g] * (f - yw[g]);
        d = mw[g];
      }
      if (apply_robust && robust != RobustLoss::kNone) {
        const double sq = r[g] * r[g];
        double rho = sq, drho = 1.0;
        if (robust == RobustLoss::kHuber) {
          if (sq > robust_b) {
            const double root = std::sqrt(sq * robust_b);
            rho = 2.0 * root - robust_b;
            drho = robust_b / root;
          }
        } else {
          rho = robust_b * std::log1p(sq / robust_b);
          drho = 1.0 / (1.0 + sq / robust_b);
        }
        const double rt = std::sqrt(rho);
        if (sq > 0.0) d *= drho * std::fabs(r[g]) / rt;
        r[g] = r[g] < 0.0 ? -rt : rt;
      }
      if (jac != nullptr) {
        const double* js = scratch_j + g * p;
        double* jr = jac + g * p;
        for (std::size_t k = 0; k < p; ++k) jr[k] = d * js[k];
      }
    }
    return true;
  }

  double chi2(std::size_t w, const double* params, bool apply_robust = false) const {
    std::vector<double> r(n), f(n);
    if (!residuals(w, params, r.data(), nullptr, f.data(), nullptr, apply_robust)) {
      return std::numeric_limits<double>::infinity();
    }
    double s = 0.0;
    for (double v : r) s += v * v;
    return s;
  }
};

// Per-wavelength cost: one block holding all parameters.
class WavelengthCost final : public ceres::CostFunction {
 public:
  WavelengthCost(const Prepared& d, std::size_t w) : d_(d), w_(w), f_(d.n), j_(d.n * d.p) {
    set_num_residuals(static_cast<int>(d.n));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(d.p));
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    double* jac = (jacobians != nullptr && jacobians[0] != nullptr) ? jacobians[0] : nullptr;
    return d_.residuals(w_, parameters[0], residuals, jac, f_.data(), j_.data());
  }

 private:
  const Prepared& d_;
  std::size_t w_;
  mutable std::vector<double> f_, j_;
};

// Per-wavelength cost over the free parameters only: one block holding the free parameters
// (indices `free` of the full vector), the fixed ones taken from `full`. Ceres then works with an
// N x (free count) Jacobian instead of N x p projected through a SubsetManifold.
class FreeWavelengthCost final : public ceres::CostFunction {
 public:
  FreeWavelengthCost(const Prepared& d, std::size_t w, std::vector<double> full, std::vector<std::size_t> free)
      : d_(d), w_(w), full_(std::move(full)), free_(std::move(free)), f_(d.n), j_(d.n * d.p) {
    set_num_residuals(static_cast<int>(d.n));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(free_.size()));
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    for (std::size_t i = 0; i < free_.size(); ++i) full_[free_[i]] = parameters[0][i];
    double* jac = (jacobians != nullptr && jacobians[0] != nullptr) ? jacobians[0] : nullptr;
    if (d_.loss != FitLoss::kLog && d_.robust == RobustLoss::kNone) {
      // Fast path of Prepared::residuals for the losses r = m (f - y): the same arithmetic, written
      // straight into Ceres' residuals and the free columns of its Jacobian.
      const std::size_t n = d_.n, p = d_.p, nf = free_.size();
      const double* yw = d_.y.data() + w_ * n;
      const double* mw = d_.mult.data() + w_ * n;
      // Ceres evaluates a candidate point without the Jacobian and, when it accepts the step, asks
      // for the Jacobian at the same point. The model's values and gradients are therefore computed
      // together at every new point and kept: the Jacobian request then costs no model evaluation.
      bool same_point = cached_;
      for (std::size_t i = 0; i < nf && same_point; ++i) same_point = cached_x_[i] == parameters[0][i];
      if (!same_point) {
        d_.model->evaluate_prepared_with_gradient(*d_.prepared_geometries, full_.data(), f_.data(), j_.data());
        cached_x_.assign(parameters[0], parameters[0] + nf);
        cached_ = true;
      }
      for (std::size_t g = 0; g < n; ++g) {
        if (!std::isfinite(f_[g])) return false;
        residuals[g] = mw[g] * (f_[g] - yw[g]);
      }
      if (jac != nullptr) {
        for (std::size_t g = 0; g < n; ++g) {
          const double* src = j_.data() + g * p;
          double* dst = jac + g * nf;
          for (std::size_t i = 0; i < nf; ++i) dst[i] = mw[g] * src[free_[i]];
        }
      }
      return true;
    }
    cached_ = false;
    if (jac != nullptr) r_jac_.resize(d_.n * d_.p);
    if (!d_.residuals(w_, full_.data(), residuals, jac != nullptr ? r_jac_.data() : nullptr, f_.data(), j_.data())) {
      return false;
    }
    if (jac != nullptr) {
      const std::size_t nf = free_.size();
      for (std::size_t g = 0; g < d_.n; ++g) {
        const double* src = r_jac_.data() + g * d_.p;
        double* dst = jac + g * nf;
        for (std::size_t i = 0; i < nf; ++i) dst[i] = src[free_[i]];
      }
    }
    return true;
  }

 private:
  const Prepared& d_;
  std::size_t w_;
  mutable std::vector<double> full_;
  std::vector<std::size_t> free_;
  mutable std::vector<double> f_, j_, r_jac_;
  mutable std::vector<double> cached_x_;  // free parameters of the values in f_ and gradients in j_
  mutable bool cached_ = false;
};

// Joint cost of one wavelength: blocks [shared, local]; full parameter k comes from
// (block_of[k], index_in_block[k]).
class JointCost final : public ceres::CostFunction {
 public:
  JointCost(const Prepared& d, std::size_t w, const std::vector<int>& block_of, const std::vector<int>& index_in_block,
            int shared_size, int local_size)
      : d_(d), w_(w), block_of_(block_of), index_(index_in_block), f_(d.n), j_(d.n * d.p), full_(d.p),
        r_jac_(d.n * d.p) {
    set_num_residuals(static_cast<int>(d.n));
    mutable_parameter_block_sizes()->push_back(shared_size);
    mutable_parameter_block_sizes()->push_back(local_size);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    for (std::size_t k = 0; k < d_.p; ++k) full_[k] = parameters[block_of_[k]][index_[k]];
    const bool want = jacobians != nullptr && (jacobians[0] != nullptr || jacobians[1] != nullptr);
    if (!d_.residuals(w_, full_.data(), residuals, want ? r_jac_.data() : nullptr, f_.data(), j_.data())) return false;
    if (!want) return true;
    const int sizes[2] = {parameter_block_sizes()[0], parameter_block_sizes()[1]};
    for (std::size_t g = 0; g < d_.n; ++g) {
      for (std::size_t k = 0; k < d_.p; ++k) {
        const int b = block_of_[k];
        if (jacobians[b] != nullptr) jacobians[b][g * sizes[b] + index_[k]] = r_jac_[g * d_.p + k];
      }
    }
    return true;
  }

 private:
  const Prepared& d_;
  std::size_t w_;
  const std::vector<int>& block_of_;
  const std::vector<int>& index_;
  mutable std::vector<double> f_, j_, full_, r_jac_;
};

// The robust function is applied per residual inside Prepared::residuals.
ceres::LossFunction* make_robust(const FitOptions&) { return nullptr; }

ceres::Solver::Options solver_options(const FitOptions& o) {
  ceres::Solver::Options s;
  s.minimizer_type = ceres::TRUST_REGION;
  s.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  // Per wavelength the Jacobian is N x (a few) columns: the normal equations (a p x p Cholesky) cost
  // less than a Householder QR of the N x p matrix and give the same steps to rounding (the final
  // costs of bench/fit_bench.sh agree to 1e-14 relative).
  s.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  s.max_num_iterations = o.max_iterations;
  s.function_tolerance = o.function_tolerance;
  s.gradient_tolerance = o.gradient_tolerance;
  s.parameter_tolerance = o.parameter_tolerance;
  s.logging_type = ceres::SILENT;
  s.minimizer_progress_to_stdout = false;
  s.num_threads = 1;
  // Bounds: every trust-region step is projected onto the box by Ceres (ParameterBlock::Plus clamps).
  // Ceres would also follow each step of a bounded problem by a projected Armijo line search whose
  // first trial re-evaluates the step just evaluated (with cubic interpolation, a full Jacobian too).
  // It is switched off: on the 13 example samples (ON+TS, multi-start 8, 1404 wavelength fits) the
  // summed RMSE is the same to 1e-4 relative (1.62798e-1 without, 1.62812e-1 with) for 38 % less
  // CPU, and bench/fit_bench.sh's final costs are unchanged.
  s.max_num_line_search_step_size_iterations = 0;
  s.line_search_interpolation_type = ceres::QUADRATIC;  // used only if the line search is re-enabled
  return s;
}

// ---------------------------------------------------------------------------------------------
// Parameter bookkeeping.
struct Layout {
  std::vector<ParameterInfo> info;
  std::vector<bool> fixed;
  std::vector<bool> shared;
  std::vector<double> start;
  std::vector<std::size_t> free_linear;     // free (not fixed), linear amplitudes, not shared
  std::vector<std::size_t> free_nonlinear;  // free, not linear (shared or not)
};

void nudge_off_bounds(const Layout& L, std::vector<double>& x) {
  for (std::size_t k : L.free_nonlinear) {
    const double lo = L.info[k].lower, hi = L.info[k].upper;
    const double step = 1e-4 * std::min(hi - lo, 1.0);
    if (x[k] <= lo) x[k] = lo + step;
    if (x[k] >= hi) x[k] = hi - step;
  }
}

// Bounded linear least squares for the free linear amplitudes of wavelength w, the other
// parameters held: minimise sum q^2 (f0 + G a - y)^2, a in bounds (projected coordinate descent on
// the normal equations). Keeps the result only if it lowers the true objective.
void solve_amplitudes(const Prepared& d, const Layout& L, std::size_t w, std::vector<double>& x) {
  const std::size_t k = L.free_linear.size();
  if (k == 0) return;
  const std::size_t n = d.n, p = d.p;
  std::vector<double> f(n), J(n * p);
  d.model->evaluate_prepared_with_gradient(*d.prepared_geometries, x.data(), f.data(), J.data());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(k));
  const double* yw = d.y.data() + w * n;
  const double* qw = d.lin_weight.data() + w * n;
  for (std::size_t g = 0; g < n; ++g) {
    double f0 = f[g];
    for (std::size_t a = 0; a < k; ++a) f0 -= x[L.free_linear[a]] * J[g * p + L.free_linear[a]];
    const double q2 = qw[g] * qw[g];
    if (!std::isfinite(f0) || !std::isfinite(q2)) return;
    for (std::size_t a = 0; a < k; ++a) {
      const double ga = J[g * p + L.free_linear[a]];
      b[static_cast<Eigen::Index>(a)] += q2 * ga * (yw[g] - f0);
      for (std::size_t c = 0; c < k; ++c) {
        A(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(c)) += q2 * ga * J[g * p + L.free_linear[c]];
      }
    }
  }
  std::vector<double> a(k);
  for (std::size_t i = 0; i < k; ++i) a[i] = x[L.free_linear[i]];
  for (int sweep = 0; sweep < 300; ++sweep) {
    double change = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      if (!(A(ii, ii) > 0.0)) continue;
      double s = b[ii];
      for (std::size_t c = 0; c < k; ++c) {
        if (c != i) s -= A(ii, static_cast<Eigen::Index>(c)) * a[c];
      }
      const ParameterInfo& info = L.info[L.free_linear[i]];
      const double v = std::clamp(s / A(ii, ii), info.lower, info.upper);
      change = std::max(change, std::fabs(v - a[i]) / (std::fabs(v) + 1e-300));
      a[i] = v;
    }
    if (change < 1e-12) break;
  }
  std::vector<double> trial = x;
  for (std::size_t i = 0; i < k; ++i) trial[L.free_linear[i]] = a[i];
  if (d.chi2(w, trial.data()) < d.chi2(w, x.data())) x = trial;
}

// Latin hypercube points (count x p, full vectors based on `base`) over the free nonlinear parameters.
std::vector<std::vector<double>> latin_hypercube(const Layout& L, const std::vector<double>& base, int count,
                                                 unsigned seed) {
  std::vector<std::vector<double>> points(static_cast<std::size_t>(std::max(count, 0)), base);
  if (count <= 0) return points;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t k : L.free_nonlinear) {
    double lo = L.info[k].lower, hi = L.info[k].upper;
    // Very wide bounds (e.g. 0..1e6 for an exponent): sample up to 10x the start instead.
    if (hi - lo > 1e3 * std::max(1.0, std::fabs(base[k]))) hi = std::min(hi, lo + std::max(10.0 * std::fabs(base[k]), 1.0));
    std::vector<int> perm(static_cast<std::size_t>(count));
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    for (int i = 0; i < count; ++i) {
      const double t = (perm[static_cast<std::size_t>(i)] + u(rng)) / count;
      points[static_cast<std::size_t>(i)][k] = lo + t * (hi - lo);
    }
  }
  return points;
}

bool converged(const ceres::Solver::Summary& s) { return s.termination_type == ceres::CONVERGENCE; }

void add_bounds(ceres::Problem& problem, double* block, const std::vector<std::size_t>& indices,
                const std::vector<ParameterInfo>& info) {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    problem.SetParameterLowerBound(block, static_cast<int>(i), info[indices[i]].lower);
    problem.SetParameterUpperBound(block, static_cast<int>(i), info[indices[i]].upper);
  }
}

// Fix coordinates `constant` (indices inside the block) of a block of size `size`.
void fix_coordinates(ceres::Problem& problem, double* block, int size, const std::vector<int>& constant) {
  if (size == 0) return;
  if (static_cast<int>(constant.size()) == size) {
    problem.SetParameterBlockConstant(block);
  } else if (!constant.empty()) {
    problem.SetManifold(block, new ceres::SubsetManifold(size, constant));
  }
}

// Statistics of one wavelength at its parameters.
void fill_statistics(const Prepared& d, std::size_t w, WavelengthFit& out) {
  const std::size_t n = d.n;
  std::vector<double> f(n), r(n);
  d.model->evaluate_prepared(*d.prepared_geometries, out.parameters.data(), f.data());
  d.residuals_of_values(w, f.data(), nullptr, r.data(), nullptr, false);
  const double* yw = d.y.data() + w * n;
  double ss = 0.0, sum_abs = 0.0, mean = 0.0, max_rel = 0.0, chi2 = 0.0;
  for (std::size_t g = 0; g < n; ++g) mean += yw[g];
  mean /= static_cast<double>(n);
  double ss_tot = 0.0;
  for (std::size_t g = 0; g < n; ++g) {
    const double e = f[g] - yw[g];
    ss += e * e;
    sum_abs += std::fabs(yw[g]);
    ss_tot += sqr(yw[g] - mean);
    if (yw[g] != 0.0) max_rel = std::max(max_rel, std::fabs(e) / std::fabs(yw[g]));
    chi2 += r[g] * r[g];
  }
  const double nn = static_cast<double>(n);
  out.points = n;
  out.rmse = std::sqrt(ss / nn);
  out.relative_rmse = sum_abs > 0.0 ? out.rmse / (sum_abs / nn) : kNaN;
  out.max_relative_error = max_rel;
  out.r_squared = ss_tot > 0.0 ? 1.0 - ss / ss_tot : kNaN;
  out.chi2 = chi2;
  const double k = static_cast<double>(out.free_parameters);
  // chi2 = 0 (exact fit, e.g. all-zero data) gives -inf: clamp the log at the smallest normal.
  const double ll = nn * std::log(std::max(chi2 / nn, std::numeric_limits<double>::min()));
  out.aic = ll + 2.0 * k;
  out.bic = ll + k * std::log(nn);
  out.at_bounds.clear();
}

void flag_bounds(const Layout& L, WavelengthFit& out) {
  out.at_bounds.clear();
  for (std::size_t k = 0; k < L.info.size(); ++k) {
    if (L.fixed[k]) continue;
    const double lo = L.info[k].lower, hi = L.info[k].upper;
    const double tol = 1e-7 * std::max(1.0, std::min(hi - lo, 1e3));
    if (out.parameters[k] <= lo + tol) out.at_bounds.push_back(L.info[k].name + "=lower");
    if (out.parameters[k] >= hi - tol) out.at_bounds.push_back(L.info[k].name + "=upper");
  }
}

// Standard errors and correlation from a covariance (p x p, zero rows for fixed parameters).
void set_covariance(const Layout& L, const Eigen::MatrixXd& cov, WavelengthFit& out) {
  const std::size_t p = L.info.size();
  out.standard_errors.assign(p, kNaN);
  out.correlation.assign(p * p, kNaN);
  for (std::size_t a = 0; a < p; ++a) {
    if (L.fixed[a]) continue;
    const double v = cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a));
    out.standard_errors[a] = v >= 0.0 ? std::sqrt(v) : kNaN;
  }
  for (std::size_t a = 0; a < p; ++a) {
    for (std::size_t b = 0; b < p; ++b) {
      if (L.fixed[a] || L.fixed[b]) continue;
      const double sa = out.standard_errors[a], sb = out.standard_errors[b];
      if (sa > 0.0 && sb > 0.0) {
        out.correlation[a * p + b] = cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) / (sa * sb);
      }
    }
  }
}

void no_covariance(const Layout& L, WavelengthFit& out, const std::string& why) {
  const std::size_t p = L.info.size();
  out.standard_errors.assign(p, kNaN);
  out.correlation.assign(p * p, kNaN);
  out.covariance_ok = false;
  out.covariance_message = why;
}

// ---------------------------------------------------------------------------------------------
// Per-wavelength mode.

struct SingleSolve {
  std::vector<double> x;
  ceres::Solver::Summary summary;
};

SingleSolve solve_one(const Prepared& d, const Layout& L, const FitOptions& o, std::size_t w, std::vector<double> x) {
  if (d.robust != RobustLoss::kNone) {
    // A robust loss is not convex: start it from the plain least-squares solution.
    Prepared plain = d;
    plain.robust = RobustLoss::kNone;
    x = solve_one(plain, L, o, w, x).x;
  }
  std::vector<std::size_t> free;
  for (std::size_t k = 0; k < d.p; ++k) {
    if (!L.fixed[k]) free.push_back(k);
  }
  SingleSolve s;
  s.x = x;
  if (free.empty()) {
    s.summary.termination_type = ceres::CONVERGENCE;
    s.summary.message = "no free parameter";
    return s;
  }
  std::vector<double> block(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) block[i] = x[free[i]];
  ceres::Problem::Options po;
  po.enable_fast_removal = false;
  ceres::Problem problem(po);
  problem.AddResidualBlock(new FreeWavelengthCost(d, w, x, free), make_robust(o), block.data());
  add_bounds(problem, block.data(), free, L.info);
  ceres::Solve(solver_options(o), &problem, &s.summary);
  for (std::size_t i = 0; i < free.size(); ++i) s.x[free[i]] = block[i];
  return s;
}

void covariance_one(const Prepared& d, const Layout& L, const FitOptions& o, std::size_t w, WavelengthFit& out,
                    const std::vector<int>& constant, std::vector<std::size_t>& all_indices) {
  if (out.free_parameters == 0) return no_covariance(L, out, "no free parameter");
  if (out.points <= out.free_parameters) return no_covariance(L, out, "no degrees of freedom (points <= free parameters)");
  std::vector<double> x = out.parameters;
  {
    // Rank check first (Ceres would log an error for a rank-deficient matrix): eigenvalues of
    // J^T J over the free columns, the same reciprocal-condition criterion.
    std::vector<double> r(d.n), J(d.n * d.p), f(d.n), js(d.n * d.p);
    if (!d.residuals(w, x.data(), r.data(), J.data(), f.data(), js.data())) {
      return no_covariance(L, out, "residuals undefined at the solution");
    }
    std::vector<std::size_t> free;
    for (std::size_t k = 0; k < d.p; ++k) {
      if (!L.fixed[k]) free.push_back(k);
    }
    const auto nf = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(nf, nf);
    for (std::size_t g = 0; g < d.n; ++g) {
      for (Eigen::Index a = 0; a < nf; ++a) {
        for (Eigen::Index b = 0; b < nf; ++b) {
          H(a, b) += J[g * d.p + free[static_cast<std::size_t>(a)]] * J[g * d.p + free[static_cast<std::size_t>(b)]];
        }
      }
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
    const double emax = es.eigenvalues().cwiseAbs().maxCoeff();
    if (!H.allFinite() || !(emax > 0.0) || !(es.eigenvalues().minCoeff() > 1e-13 * emax)) {
      return no_covariance(L, out, "rank-deficient Jacobian (parameters not separately identifiable at this solution)");
    }
  }
  ceres::Problem problem;
  problem.AddResidualBlock(new WavelengthCost(d, w), make_robust(o), x.data());
  fix_coordinates(problem, x.data(), static_cast<int>(d.p), constant);
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.min_reciprocal_condition_number = 1e-14;
  co.null_space_rank = 0;
  co.apply_loss_function = true;
  co.num_threads = 1;
  ceres::Covariance covariance(co);
  std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
  if (!covariance.Compute(blocks, &problem)) {
    return no_covariance(L, out, "rank-deficient Jacobian (parameters not separately identifiable at this solution)");
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(d.p, d.p);
  covariance.GetCovarianceBlock(x.data(), x.data(), c.data());
  const double s2 = out.chi2 / static_cast<double>(out.points - out.free_parameters);
  Eigen::MatrixXd cov = c * s2;
  if (!cov.allFinite()) return no_covariance(L, out, "covariance not finite");
  out.covariance_ok = true;
  out.covariance_message.clear();
  set_covariance(L, cov, out);
  (void)all_indices;
}

void fit_per_wavelength(const Prepared& d, const Layout& L, const FitOptions& o, FitResult& result) {
  const std::size_t M = d.m;
  result.wavelengths.assign(M, WavelengthFit{});
  std::vector<int> constant;
  std::vector<std::size_t> all_indices(d.p);
  std::iota(all_indices.begin(), all_indices.end(), 0);
  std::size_t n_free = 0;
  for (std::size_t k = 0; k < d.p; ++k) {
    if (L.fixed[k]) {
      constant.push_back(static_cast<int>(k));
    } else {
      ++n_free;
    }
  }
  const auto lhs = latin_hypercube(L, L.start, std::max(0, o.multistart - 2), o.seed);
  const int threads = std::max(1, std::min<int>(o.threads, static_cast<int>(M)));
  std::atomic<std::size_t> done{0};
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  std::mutex mutex;
  std::condition_variable cv;
  int finished = 0;

  auto work = [&](int t) {
    try {
      const std::size_t begin = M * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
      const std::size_t end = M * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
      std::vector<double> warm = L.start;
      for (std::size_t w = begin; w < end; ++w) {
        std::vector<std::vector<double>> candidates;
        candidates.push_back(warm);
        if (o.multistart >= 2 && w != begin && o.warm_start) candidates.push_back(L.start);
        for (const auto& q : lhs) candidates.push_back(q);
        while (candidates.size() > static_cast<std::size_t>(std::max(1, o.multistart))) candidates.pop_back();
        SingleSolve best;
        double best_cost = std::numeric_limits<double>::infinity();
        int best_index = 0;
        for (std::size_t c = 0; c < candidates.size(); ++c) {
          std::vector<double> x0 = candidates[c];
          nudge_off_bounds(L, x0);
          if (o.solve_linear) solve_amplitudes(d, L, w, x0);
          SingleSolve s = solve_one(d, L, o, w, x0);
          if (c == 0 || s.summary.final_cost < best_cost) {
            best_cost = s.summary.final_cost;
            best = std::move(s);
            best_index = static_cast<int>(c);
          }
        }
        WavelengthFit& out = result.wavelengths[w];
        out.wavelength = 0.0;
        out.parameters = best.x;
        out.free_parameters = n_free;
        out.cost = best.summary.final_cost;
        out.iterations = std::max(0, static_cast<int>(best.summary.iterations.size()) - 1);
        out.converged = converged(best.summary);
        out.status = best.summary.message;
        out.start_index = best_index;
        fill_statistics(d, w, out);
        flag_bounds(L, out);
        if (o.compute_covariance) {
          covariance_one(d, L, o, w, out, constant, all_indices);
        } else {
          no_covariance(L, out, "not computed");
        }
        if (o.warm_start) warm = best.x;
        done.fetch_add(1);
      }
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      ++finished;
    }
    cv.notify_all();
  };

  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work, t);
  if (o.progress) {
    std::unique_lock<std::mutex> lock(mutex);
    while (finished < threads) {
      cv.wait_for(lock, std::chrono::milliseconds(100));
      o.progress(done.load(), M);
    }
  }
  for (auto& th : pool) th.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  if (o.progress) o.progress(M, M);
}

// ---------------------------------------------------------------------------------------------
// Joint mode.

class ProgressCallback final : public ceres::IterationCallback {
 public:
  ProgressCallback(const FitOptions& o) : o_(o) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (o_.progress) {
      o_.progress(static_cast<std::size_t>(s.iteration), static_cast<std::size_t>(std::max(1, o_.max_iterations)));
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FitOptions& o_;
};

void fit_joint(const Prepared& d, const Layout& L, const FitOptions& o, FitResult& result) {
  const std::size_t M = d.m, p = d.p;
  std::vector<int> block_of(p), index(p);
  std::vector<std::size_t> shared_idx, local_idx;
  for (std::size_t k = 0; k < p; ++k) {
    if (L.shared[k]) {
      block_of[k] = 0;
      index[k] = static_cast<int>(shared_idx.size());
      shared_idx.push_back(k);
    } else {
      block_of[k] = 1;
      index[k] = static_cast<int>(local_idx.size());
      local_idx.push_back(k);
    }
  }
  const int S = static_cast<int>(shared_idx.size()), Lc = static_cast<int>(local_idx.size());
  std::vector<int> shared_const, local_const;
  for (int i = 0; i < S; ++i) {
    if (L.fixed[shared_idx[static_cast<std::size_t>(i)]]) shared_const.push_back(i);
  }
  for (int i = 0; i < Lc; ++i) {
    if (L.fixed[local_idx[static_cast<std::size_t>(i)]]) local_const.push_back(i);
  }
  const std::size_t shared_free = static_cast<std::size_t>(S) - shared_const.size();
  const std::size_t local_free = static_cast<std::size_t>(Lc) - local_const.size();

  const auto lhs = latin_hypercube(L, L.start, std::max(0, o.multistart - 1), o.seed);
  std::vector<std::vector<double>> candidates = {L.start};
  for (const auto& q : lhs) candidates.push_back(q);

  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<double> best_shared;
  std::vector<std::vector<double>> best_local;
  ceres::Solver::Summary best_summary;
  int best_index = 0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    std::vector<double> x0 = candidates[c];
    nudge_off_bounds(L, x0);
    std::vector<double> shared(static_cast<std::size_t>(S));
    for (int i = 0; i < S; ++i) shared[static_cast<std::size_t>(i)] = x0[shared_idx[static_cast<std::size_t>(i)]];
    std::vector<std::vector<double>> local(M, std::vector<double>(static_cast<std::size_t>(Lc)));
    for (std::size_t w = 0; w < M; ++w) {
      std::vector<double> xw = x0;
      if (o.solve_linear) solve_amplitudes(d, L, w, xw);
      for (int i = 0; i < Lc; ++i) local[w][static_cast<std::size_t>(i)] = xw[local_idx[static_cast<std::size_t>(i)]];
    }
    ceres::Problem problem;
    auto* ordering = new ceres::ParameterBlockOrdering;
    for (std::size_t w = 0; w < M; ++w) {
      double* lb = Lc > 0 ? local[w].data() : nullptr;
      std::vector<double*> blocks;
      // A zero-size block is not allowed: use the cost with only the non-empty blocks.
      if (S > 0 && Lc > 0) {
        problem.AddResidualBlock(new JointCost(d, w, block_of, index, S, Lc), make_robust(o), shared.data(), lb);
      } else {
        throw InputError("joint mode needs at least one shared and one per-wavelength parameter");
      }
      ordering->AddElementToGroup(lb, 0);
    }
    ordering->AddElementToGroup(shared.data(), 1);
    add_bounds(problem, shared.data(), shared_idx, L.info);
    fix_coordinates(problem, shared.data(), S, shared_const);
    for (std::size_t w = 0; w < M; ++w) {
      add_bounds(problem, local[w].data(), local_idx, L.info);
      fix_coordinates(problem, local[w].data(), Lc, local_const);
    }
    ceres::Solver::Options so = solver_options(o);
    // Schur complement: the per-wavelength blocks (group 0) are eliminated; the reduced system has
    // the size of the shared block, so a dense Schur solver is the right choice.
    if (o.joint_solver == "sparse-schur") {
      so.linear_solver_type = ceres::SPARSE_SCHUR;
    } else if (o.joint_solver == "iterative-schur") {
      so.linear_solver_type = ceres::ITERATIVE_SCHUR;
      so.preconditioner_type = ceres::JACOBI;
    } else {
      so.linear_solver_type = ceres::DENSE_SCHUR;
    }
    std::string why;
    if (!so.IsValid(&why)) throw InputError("joint solver '" + o.joint_solver + "' is not available: " + why);
    so.linear_solver_ordering.reset(ordering);
    so.num_threads = std::max(1, o.threads);
    ProgressCallback cb(o);
    if (o.progress) so.callbacks.push_back(&cb);
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (c == 0 || summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      best_shared = shared;
      best_local = local;
      best_summary = summary;
      best_index = static_cast<int>(c);
    }
  }

  result.joint_iterations = static_cast<int>(best_summary.iterations.size()) - 1;
  result.joint_status = best_summary.message;
  result.wavelengths.assign(M, WavelengthFit{});
  const std::size_t k_w = local_free + shared_free;
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = result.wavelengths[w];
    out.parameters.assign(p, 0.0);
    for (std::size_t k = 0; k < p; ++k) {
      out.parameters[k] = block_of[k] == 0 ? best_shared[static_cast<std::size_t>(index[k])]
                                           : best_local[w][static_cast<std::size_t>(index[k])];
    }
    out.free_parameters = k_w;
    out.iterations = result.joint_iterations;
    out.converged = converged(best_summary);
    out.status = best_summary.message;
    out.start_index = best_index;
    std::vector<double> f(d.n), r(d.n);
    fill_statistics(d, w, out);
    // Cost of this wavelength (robust function included).
    out.cost = 0.0;
    out.cost = 0.5 * d.chi2(w, out.parameters.data(), true);
    flag_bounds(L, out);
  }

  // Covariance by the block (Schur) formula on H = J^T J (robust function not applied).
  if (!o.compute_covariance) {
    for (auto& out : result.wavelengths) no_covariance(L, out, "not computed");
    return;
  }
  std::vector<std::size_t> lf, sf;  // free local / shared full indices
  for (std::size_t k : local_idx) {
    if (!L.fixed[k]) lf.push_back(k);
  }
  for (std::size_t k : shared_idx) {
    if (!L.fixed[k]) sf.push_back(k);
  }
  const auto nl = static_cast<Eigen::Index>(lf.size()), ns = static_cast<Eigen::Index>(sf.size());
  std::size_t n_total = 0;
  double chi2_total = 0.0;
  Eigen::MatrixXd Hss = Eigen::MatrixXd::Zero(ns, ns);
  std::vector<Eigen::MatrixXd> Hll_inv(M), Hls(M);
  std::vector<bool> ok(M, true);
  std::vector<double> r(d.n), J(d.n * p), f(d.n), Js(d.n * p);
  Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(ns, ns);
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = result.wavelengths[w];
    d.residuals(w, out.parameters.data(), r.data(), J.data(), f.data(), Js.data());
    n_total += d.n;
    chi2_total += out.chi2;
    Eigen::MatrixXd Jl(static_cast<Eigen::Index>(d.n), nl), Jsh(static_cast<Eigen::Index>(d.n), ns);
    for (std::size_t g = 0; g < d.n; ++g) {
      for (Eigen::Index i = 0; i < nl; ++i) Jl(static_cast<Eigen::Index>(g), i) = J[g * p + lf[static_cast<std::size_t>(i)]];
      for (Eigen::Index i = 0; i < ns; ++i) Jsh(static_cast<Eigen::Index>(g), i) = J[g * p + sf[static_cast<std::size_t>(i)]];
    }
    const Eigen::MatrixXd Hll = Jl.transpose() * Jl;
    Hls[w] = Jl.transpose() * Jsh;
    Hss += Jsh.transpose() * Jsh;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Hll);
    const double emax = nl > 0 ? es.eigenvalues().cwiseAbs().maxCoeff() : 1.0;
    if (nl > 0 && !(es.eigenvalues().minCoeff() > 1e-14 * emax)) {
      ok[w] = false;
      continue;
    }
    Hll_inv[w] = nl > 0 ? Eigen::MatrixXd(es.eigenvectors() * es.eigenvalues().cwiseInverse().asDiagonal() *
                                          es.eigenvectors().transpose())
                        : Eigen::MatrixXd(0, 0);
    schur += Hls[w].transpose() * Hll_inv[w] * Hls[w];
  }
  const std::size_t k_total = shared_free + M * local_free;
  if (n_total <= k_total) {
    for (auto& out : result.wavelengths) no_covariance(L, out, "no degrees of freedom");
    return;
  }
  const double s2 = chi2_total / static_cast<double>(n_total - k_total);
  const bool all_ok = std::all_of(ok.begin(), ok.end(), [](bool b) { return b; });
  Eigen::MatrixXd Css;
  bool shared_ok = all_ok;
  if (all_ok && ns > 0) {
    const Eigen::MatrixXd Sm = Hss - schur;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Sm);
    const double emax = es.eigenvalues().cwiseAbs().maxCoeff();
    if (!(es.eigenvalues().minCoeff() > 1e-14 * emax)) {
      shared_ok = false;
    } else {
      Css = es.eigenvectors() * es.eigenvalues().cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
    }
  } else if (ns == 0) {
    Css = Eigen::MatrixXd(0, 0);
  }
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = result.wavelengths[w];
    if (!shared_ok) {
      no_covariance(L, out, all_ok ? "rank-deficient: shared parameters not identifiable"
                                   : "rank-deficient Jacobian at some wavelength (parameters not separately identifiable)");
      continue;
    }
    // Blocks of the inverse of [[Hll, Hls], [Hsl, Hss]] (all wavelengths): Css = S^-1,
    // Cll = Hll^-1 + Hll^-1 Hls Css Hsl Hll^-1, Cls = -Hll^-1 Hls Css.
    const Eigen::MatrixXd Bw = Hll_inv[w] * Hls[w];
    const Eigen::MatrixXd Cll = Hll_inv[w] + Bw * Css * Bw.transpose();
    const Eigen::MatrixXd Cls = -Bw * Css;
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
    for (Eigen::Index a = 0; a < nl; ++a) {
      const auto ia = static_cast<Eigen::Index>(lf[static_cast<std::size_t>(a)]);
      for (Eigen::Index b = 0; b < nl; ++b) cov(ia, static_cast<Eigen::Index>(lf[static_cast<std::size_t>(b)])) = Cll(a, b);
      for (Eigen::Index b = 0; b < ns; ++b) {
        const auto ib = static_cast<Eigen::Index>(sf[static_cast<std::size_t>(b)]);
        cov(ia, ib) = Cls(a, b);
        cov(ib, ia) = Cls(a, b);
      }
    }
    for (Eigen::Index a = 0; a < ns; ++a) {
      for (Eigen::Index b = 0; b < ns; ++b) {
        cov(static_cast<Eigen::Index>(sf[static_cast<std::size_t>(a)]), static_cast<Eigen::Index>(sf[static_cast<std::size_t>(b)])) = Css(a, b);
      }
    }
    cov *= s2;
    out.covariance_ok = true;
    out.covariance_message.clear();
    set_covariance(L, cov, out);
  }
}

std::string lower_case(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

FitLoss fit_loss_from_string(const std::string& name) {
  const std::string s = lower_case(name);
  if (s == "plain") return FitLoss::kPlain;
  if (s == "relative") return FitLoss::kRelative;
  if (s == "log") return FitLoss::kLog;
  if (s == "cosine") return FitLoss::kCosine;
  throw InputError("unknown loss '" + name + "' (known: plain, relative, log, cosine)");
}

std::string to_string(FitLoss loss) {
  switch (loss) {
    case FitLoss::kRelative:
      return "relative";
    case FitLoss::kLog:
      return "log";
    case FitLoss::kCosine:
      return "cosine";
    default:
      return "plain";
  }
}

void robust_loss_from_string(const std::string& text, RobustLoss& kind, double& scale) {
  const std::string s = lower_case(text);
  if (s.empty() || s == "none") {
    kind = RobustLoss::kNone;
    scale = 1.0;
    return;
  }
  const auto colon = s.find(':');
  const std::string name = s.substr(0, colon);
  if (name == "huber") {
    kind = RobustLoss::kHuber;
  } else if (name == "cauchy") {
    kind = RobustLoss::kCauchy;
  } else {
    throw InputError("unknown robust loss '" + text + "' (use huber:SCALE or cauchy:SCALE)");
  }
  if (colon == std::string::npos) throw InputError("robust loss '" + text + "' needs a scale, e.g. " + name + ":0.01");
  const std::string number = s.substr(colon + 1);
  std::size_t used = 0;
  double v = kNaN;
  try {
    v = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != number.size() || !(v > 0.0) || !std::isfinite(v)) {
    throw InputError("robust loss scale '" + number + "' must be a positive number");
  }
  scale = v;
}

std::string to_string(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
    default:
      return "none";
  }
}

std::vector<double> solid_angle_weights(const std::vector<Geometry>& geometries) {
  const std::size_t n = geometries.size();
  std::vector<double> w(n, 1.0);
  if (n == 0) return w;
  auto chord = [](const Vec3& a, const Vec3& b) { return length(a - b); };
  constexpr double kSame = 1e-9;
  // Distinct incidence directions.
  std::vector<Vec3> incid;
  std::vector<std::size_t> group(n);
  for (std::size_t g = 0; g < n; ++g) {
    std::size_t k = 0;
    for (; k < incid.size(); ++k) {
      if (chord(incid[k], geometries[g].wi) < kSame) break;
    }
    if (k == incid.size()) incid.push_back(geometries[g].wi);
    group[g] = k;
  }
  // Cell of a direction among a set: pi (d/2)^2 with d the nearest distinct neighbour, shared
  // between duplicates.
  auto cells = [&](const std::vector<Vec3>& dirs) {
    const std::size_t m = dirs.size();
    std::vector<double> area(m, 1.0);
    if (m < 2) return area;
    for (std::size_t a = 0; a < m; ++a) {
      double dmin = std::numeric_limits<double>::infinity();
      std::size_t dup = 1;
      for (std::size_t b = 0; b < m; ++b) {
        if (a == b) continue;
        const double d = chord(dirs[a], dirs[b]);
        if (d < kSame) {
          ++dup;
        } else {
          dmin = std::min(dmin, d);
        }
      }
      area[a] = std::isfinite(dmin) ? kPi * 0.25 * dmin * dmin / static_cast<double>(dup) : 1.0 / static_cast<double>(dup);
    }
    return area;
  };
  const std::vector<double> incid_area = cells(incid);
  for (std::size_t k = 0; k < incid.size(); ++k) {
    std::vector<std::size_t> members;
    std::vector<Vec3> dirs;
    for (std::size_t g = 0; g < n; ++g) {
      if (group[g] == k) {
        members.push_back(g);
        dirs.push_back(geometries[g].wr);
      }
    }
    const std::vector<double> refl_area = cells(dirs);
    for (std::size_t i = 0; i < members.size(); ++i) w[members[i]] = incid_area[k] * refl_area[i];
  }
  const double mean = std::accumulate(w.begin(), w.end(), 0.0) / static_cast<double>(n);
  if (mean > 0.0) {
    for (double& v : w) v /= mean;
  }
  return w;
}

FitResult fit_model(const Model& model, const SpectralDataset& data, const FitOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const ModelDescription& desc = model.description();
  const std::size_t p = model.parameter_count();
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  if (N == 0) throw InputError("cannot fit: the dataset has no geometries");
  if (M == 0) throw InputError("cannot fit: the dataset has no wavelengths");
  if (data.brdf.size() != N * M) throw InputError("cannot fit: dataset BRDF table does not match its geometries x wavelengths");
  if (data.has_sigma() && data.sigma.size() != N * M) throw InputError("cannot fit: dataset sigma table has the wrong size");
  if (options.multistart < 1) throw InputError("--multistart must be at least 1");
  if (options.threads < 1) throw InputError("--threads must be at least 1");
  if (options.joint_solver != "dense-schur" && options.joint_solver != "sparse-schur" &&
      options.joint_solver != "iterative-schur") {
    throw InputError("unknown joint solver '" + options.joint_solver + "' (dense-schur, sparse-schur, iterative-schur)");
  }
  if (options.max_iterations < 1) throw InputError("the iteration limit must be at least 1");
  for (std::size_t g = 0; g < N; ++g) {
    for (std::size_t w = 0; w < M; ++w) {
      if (!std::isfinite(data.value(g, w))) {
        throw InputError("cannot fit: BRDF value at geometry " + std::to_string(g + 1) + ", wavelength " +
                         fmt_double(data.wavelengths[w]) + " nm is " + fmt_double(data.value(g, w)) +
                         " (missing values are not fitted; remove that geometry or wavelength)");
      }
    }
  }

  // Parameter layout.
  Layout L;
  L.info = desc.parameters;
  L.fixed.assign(p, false);
  L.shared.assign(p, false);
  auto index_of = [&](const std::string& name, const std::string& what) {
    const auto idx = desc.parameter_index(name);
    if (!idx) {
      std::string known;
      for (const auto& q : desc.parameters) known += (known.empty() ? "" : ", ") + q.name;
      throw InputError(what + ": model '" + desc.name + "' has no parameter '" + name + "' (parameters: " + known + ")");
    }
    return *idx;
  };
  L.start = desc.default_parameters();
  for (const auto& [name, value] : options.start) L.start[index_of(name, "start")] = value;
  for (const auto& [name, value] : options.fixed) {
    const std::size_t k = index_of(name, "fixed parameter");
    L.fixed[k] = true;
    L.start[k] = value;
  }
  for (std::size_t k = 0; k < p; ++k) {
    const ParameterInfo& q = L.info[k];
    if (!std::isfinite(L.start[k]) || L.start[k] < q.lower || L.start[k] > q.upper) {
      throw InputError(std::string(L.fixed[k] ? "fixed value" : "starting value") + " of '" + q.name + "' = " +
                       fmt_double(L.start[k]) + " is outside its bounds [" + fmt_double(q.lower) + ", " +
                       fmt_double(q.upper) + "] " + q.unit);
    }
  }
  for (const auto& name : options.shared) {
    const std::size_t k = index_of(name, "shared parameter");
    if (L.fixed[k]) throw InputError("parameter '" + name + "' is both fixed and shared: give only one of them");
    L.shared[k] = true;
  }
  const bool joint = !options.shared.empty();
  for (std::size_t k = 0; k < p; ++k) {
    if (L.fixed[k]) continue;
    if (L.info[k].linear && !L.shared[k]) {
      L.free_linear.push_back(k);
    } else if (!L.info[k].linear) {
      L.free_nonlinear.push_back(k);
    }
  }
  std::size_t free_count = 0, shared_free = 0;
  for (std::size_t k = 0; k < p; ++k) {
    if (!L.fixed[k]) {
      ++free_count;
      if (L.shared[k]) ++shared_free;
    }
  }
  const std::size_t local_free = free_count - shared_free;
  if (!joint && N < free_count) {
    throw InputError("cannot fit: " + std::to_string(N) + " geometries for " + std::to_string(free_count) +
                     " free parameters of '" + desc.name + "' (fix some with --fix, or measure more geometries)");
  }
  if (joint && (N < local_free || N * M < local_free * M + shared_free)) {
    throw InputError("cannot fit: " + std::to_string(N) + " geometries per wavelength for " + std::to_string(local_free) +
                     " free per-wavelength parameters (+" + std::to_string(shared_free) + " shared)");
  }
  if (joint && local_free + shared_free == 0) throw InputError("cannot fit: every parameter is fixed");

  // Prepare the data (wavelength-major) and multipliers.
  Prepared d;
  d.model = &model;
  d.p = p;
  d.n = N;
  d.m = M;
  d.loss = options.loss;
  d.robust = options.robust;
  d.robust_b = options.robust_scale * options.robust_scale;
  if (options.robust != RobustLoss::kNone && !(options.robust_scale > 0.0)) {
    throw InputError("the robust loss scale must be positive");
  }
  d.geometries = data.geometries.data();
  d.prepared_geometries = model.prepare(d.geometries, N);
  d.y.resize(N * M);
  d.mult.resize(N * M);
  d.lin_weight.resize(N * M);
  d.cos_i.resize(N);
  for (std::size_t g = 0; g < N; ++g) d.cos_i[g] = data.geometries[g].cos_theta_i();
  const std::vector<double> sa = options.solid_angle_weights ? solid_angle_weights(data.geometries)
                                                             : std::vector<double>(N, 1.0);
  const bool use_sigma = options.use_sigma && data.has_sigma();
  for (std::size_t w = 0; w < M; ++w) {
    for (std::size_t g = 0; g < N; ++g) {
      const double y = data.value(g, w);
      double m = std::sqrt(sa[g]);
      if (use_sigma) {
        const double s = data.sigma[g * M + w];
        if (!(s > 0.0) || !std::isfinite(s)) {
          throw InputError("cannot fit: uncertainty at geometry " + std::to_string(g + 1) + ", wavelength " +
                           fmt_double(data.wavelengths[w]) + " nm is " + fmt_double(s) +
                           " (must be > 0; or fit without uncertainties)");
        }
        m /= s;
      }
      const double c = d.cos_i[g];
      double lin = m;
      switch (options.loss) {
        case FitLoss::kRelative:
          if (y == 0.0) {
            throw InputError("cannot use the relative loss: measured BRDF is 0 at geometry " + std::to_string(g + 1) +
                             ", wavelength " + fmt_double(data.wavelengths[w]) + " nm");
          }
          m /= std::fabs(y);
          lin = m;
          break;
        case FitLoss::kCosine:
          m *= c;
          lin = m;
          break;
        case FitLoss::kLog:
          if (!(1.0 + y * c > 0.0)) {
            throw InputError("cannot use the log loss: 1 + f cos(theta_i) <= 0 at geometry " + std::to_string(g + 1) +
                             ", wavelength " + fmt_double(data.wavelengths[w]) + " nm");
          }
          lin = m * c / (1.0 + y * c);
          break;
        default:
          break;
      }
      d.y[w * N + g] = y;
      d.mult[w * N + g] = m;
      d.lin_weight[w * N + g] = lin;
    }
  }

  FitResult result;
  result.model = desc.name;
  result.options = desc.option_values;
  for (const auto& q : desc.parameters) {
    result.parameter_names.push_back(q.name);
    result.parameter_units.push_back(q.unit);
  }
  for (std::size_t k = 0; k < p; ++k) {
    if (L.fixed[k]) result.fixed.push_back(L.info[k].name);
    if (L.shared[k]) result.shared.push_back(L.info[k].name);
  }
  result.settings = options;
  result.settings.progress = nullptr;
  result.joint = joint;

  if (joint) {
    fit_joint(d, L, options, result);
  } else {
    fit_per_wavelength(d, L, options, result);
  }

  // Totals.
  double ss = 0.0, sum_abs = 0.0, ll = 0.0;
  std::vector<double> f(N);
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = result.wavelengths[w];
    out.wavelength = data.wavelengths[w];
    ss += out.rmse * out.rmse * static_cast<double>(N);
    for (std::size_t g = 0; g < N; ++g) sum_abs += std::fabs(d.y[w * N + g]);
    result.max_relative_error_total = std::max(result.max_relative_error_total, out.max_relative_error);
    result.chi2_total += out.chi2;
    ll += static_cast<double>(N) * std::log(std::max(out.chi2 / static_cast<double>(N), std::numeric_limits<double>::min()));
    if (out.converged) ++result.converged_count;
    if (!out.at_bounds.empty()) ++result.at_bound_count;
    if (!out.covariance_ok) ++result.covariance_failures;
  }
  result.points_total = N * M;
  result.free_parameters_total = joint ? shared_free + M * local_free : M * free_count;
  const double nt = static_cast<double>(result.points_total);
  result.rmse_total = std::sqrt(ss / nt);
  result.relative_rmse_total = sum_abs > 0.0 ? result.rmse_total / (sum_abs / nt) : kNaN;
  const double kt = static_cast<double>(result.free_parameters_total);
  result.aic_total = ll + 2.0 * kt;
  result.bic_total = ll + kt * std::log(static_cast<double>(N));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  result.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  return result;
}

std::vector<double> fitted_values(const Model& model, const SpectralDataset& data, const FitResult& fit) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  if (fit.wavelengths.size() != M) throw InputError("fit and dataset have different wavelengths");
  std::vector<double> out(N * M), col(N);
  for (std::size_t w = 0; w < M; ++w) {
    model.evaluate_batch(data.geometries.data(), N, fit.wavelengths[w].parameters.data(), 1, col.data());
    for (std::size_t g = 0; g < N; ++g) out[g * M + w] = col[g];
  }
  return out;
}

std::vector<std::size_t> select_wavelengths(const std::vector<double>& available, const std::string& spec) {
  std::vector<double> wanted;
  auto number = [&](const std::string& t) {
    std::size_t used = 0;
    double v = kNaN;
    try {
      v = std::stod(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (t.empty() || used != t.size() || !std::isfinite(v)) {
      throw InputError("--wavelengths: '" + t + "' is not a number (use START:STOP:STEP or a comma list, in nm)");
    }
    return v;
  };
  if (spec.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : spec) {
      if (c == ':') {
        parts.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    parts.push_back(cur);
    if (parts.size() != 3) throw InputError("--wavelengths expects START:STOP:STEP in nm, got '" + spec + "'");
    const double a = number(parts[0]), b = number(parts[1]), s = number(parts[2]);
    if (!(s > 0.0) || b < a) throw InputError("--wavelengths: need START <= STOP and STEP > 0, got '" + spec + "'");
    for (long i = 0;; ++i) {
      const double v = a + static_cast<double>(i) * s;
      if (v > b + 1e-9 * std::max(1.0, std::fabs(b))) break;
      wanted.push_back(v);
    }
  } else {
    std::string cur;
    for (char c : spec + ",") {
      if (c == ',') {
        wanted.push_back(number(cur));
        cur.clear();
      } else if (c != ' ') {
        cur += c;
      }
    }
  }
  std::vector<std::size_t> idx;
  for (double v : wanted) {
    const auto it = std::min_element(available.begin(), available.end(),
                                     [v](double a, double b) { return std::fabs(a - v) < std::fabs(b - v); });
    if (it == available.end() || std::fabs(*it - v) > 1e-6) {
      throw InputError("--wavelengths: " + fmt_double(v) + " nm is not a wavelength of the dataset (resample first)");
    }
    idx.push_back(static_cast<std::size_t>(it - available.begin()));
  }
  std::sort(idx.begin(), idx.end());
  if (std::adjacent_find(idx.begin(), idx.end()) != idx.end()) throw InputError("--wavelengths lists a wavelength twice");
  return idx;
}

SpectralDataset subset_wavelengths(const SpectralDataset& data, const std::vector<std::size_t>& indices) {
  SpectralDataset out;
  out.geometries = data.geometries;
  out.convention = data.convention;
  out.metadata = data.metadata;
  const std::size_t N = data.geometry_count(), M = data.wavelength_count(), K = indices.size();
  for (std::size_t i : indices) out.wavelengths.push_back(data.wavelengths[i]);
  out.brdf.resize(N * K);
  if (data.has_sigma()) out.sigma.resize(N * K);
  for (std::size_t g = 0; g < N; ++g) {
    for (std::size_t j = 0; j < K; ++j) {
      out.brdf[g * K + j] = data.brdf[g * M + indices[j]];
      if (data.has_sigma()) out.sigma[g * K + j] = data.sigma[g * M + indices[j]];
    }
  }
  return out;
}

}  // namespace roadbrdf
