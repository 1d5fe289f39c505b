#include "roadbrdf/fitting/small_solve.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "roadbrdf/fitting/cost_functions.h"

namespace roadbrdf::fitting {

namespace {

// Ceres' Levenberg-Marquardt constants (ceres::Solver::Options defaults), so that the steps start
// and grow as those of the full Ceres solve: regularisation D / mu with D = diag(J^T J) clamped to
// [kMinDiagonal, kMaxDiagonal], mu from kInitialRadius, a step accepted when the cost falls by at
// least kMinRelativeDecrease of the decrease the quadratic model predicted.
constexpr double kInitialRadius = 1e4;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMinRelativeDecrease = 1e-3;

// One wavelength's problem over its free parameters: the cost 1/2 |r|^2, the Gauss-Newton matrix
// A = J^T J and the gradient g = J^T r at a point, from the residuals and the row-major Jacobian that
// FreeWavelengthCost writes (the model's values and gradients are computed together at each point).
// A and g are summed row by row in plain loops whose sizes are known at compile time for K free
// parameters (unrolled and vectorised), instead of a general matrix product of the N x K Jacobian.
template <int K>
class WavelengthProblem {
 public:
  using Vector = Eigen::Matrix<double, K, 1>;
  using Matrix = Eigen::Matrix<double, K, K>;

  // A point's cost, J^T J and J^T r, and its N x K row-major Jacobian (kept for the covariance).
  struct Point {
    Vector x;
    double cost = 0.0;
    Matrix A;
    Vector g;
    std::vector<double> jacobian;
  };

  WavelengthProblem(const FitData& d, std::size_t w, const std::vector<double>& x, const std::vector<std::size_t>& free)
      : cost_(d, w, x, free), n_(d.n), nf_(free.size()), residuals_(d.n) {}

  // Fills `p` at p.x; false where the model or the loss is undefined.
  bool evaluate(Point& p) const {
    p.jacobian.resize(n_ * nf_);
    const double* x = p.x.data();
    double* rows = p.jacobian.data();
    if (!cost_.Evaluate(&x, residuals_.data(), &rows)) return false;
    const auto m = static_cast<Eigen::Index>(nf_);
    p.A.setZero(m, m);
    p.g.setZero(m);
    double rr = 0.0;
    if constexpr (K == Eigen::Dynamic) {
      for (std::size_t n = 0; n < n_; ++n) {
        const double* row = rows + n * nf_;
        for (Eigen::Index a = 0; a < m; ++a) {
          for (Eigen::Index b = 0; b <= a; ++b) p.A(a, b) += row[a] * row[b];
          p.g(a) += row[a] * residuals_[n];
        }
        rr += residuals_[n] * residuals_[n];
      }
    } else {
      // The lower triangle of [J r]^T [J r] in a flat array of sums.
      constexpr auto k = static_cast<std::size_t>(K);
      std::array<double, (k + 1) * (k + 2) / 2> sum{};
      for (std::size_t n = 0; n < n_; ++n) {
        std::array<double, k + 1> v;
        for (std::size_t a = 0; a < k; ++a) v[a] = rows[n * k + a];
        v[k] = residuals_[n];
        std::size_t i = 0;
        for (std::size_t a = 0; a <= k; ++a) {
          for (std::size_t b = 0; b <= a; ++b) sum[i++] += v[a] * v[b];
        }
      }
      std::size_t i = 0;
      for (int a = 0; a < K; ++a) {
        for (int b = 0; b <= a; ++b) p.A(a, b) = sum[i++];
      }
      for (int b = 0; b < K; ++b) p.g(b) = sum[i++];
      rr = sum[i];
    }
    p.A.template triangularView<Eigen::StrictlyUpper>() = p.A.transpose();
    p.cost = 0.5 * rr;
    return std::isfinite(p.cost);
  }

 private:
  FreeWavelengthCost cost_;
  std::size_t n_, nf_;
  mutable std::vector<double> residuals_;
};

// Bounded Levenberg-Marquardt by projection with an active set (a projected Levenberg-Marquardt as in
// Kanzow, Yamashita & Fukushima, J. Comput. Appl. Math. 172 (2004) 375, with Ceres' trust-region
// update of the regularisation):
//  - a free parameter on a bound whose gradient component (or step, below) points out of the box is
//    held there for the iteration (active); the step of the others solves (A_FF + D_FF / mu) s_F = -g_F;
//  - the trial point is the step projected onto the box, and the step's quality compares the actual
//    decrease with the decrease the quadratic model predicts for the PROJECTED step, so a projection
//    that spoils the step is rejected and followed by a shorter one. As mu -> 0 the step tends to the
//    projected scaled gradient step, a descent direction on a box (D diagonal), so the iteration
//    reaches a point satisfying the bound-constrained optimality conditions;
//  - it stops, as Ceres does, when the projected gradient |x - P(x - g)|_inf is below the gradient
//    tolerance, when a successful step changes the cost by less than the function tolerance times
//    the cost, or when a step is shorter than parameter_tolerance (|x| + parameter_tolerance).
// The Ceres solve this replaces projected its steps onto the box too, but measured their quality
// with the unprojected step and had no active set: on data whose optimum lies on a bound it
// stalled away from the optimum (costs up to 13 % above scipy's 'trf' at half the wavelengths of
// bench/fit_bench_plain.sh's bounded case).
template <int K>
bool solve_sized(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                 const std::vector<std::size_t>& free, std::vector<double>& x, ceres::Solver::Summary& summary,
                 std::vector<double>& free_jacobian) {
  using Problem = WavelengthProblem<K>;
  using Vector = typename Problem::Vector;
  using Matrix = typename Problem::Matrix;
  const auto m = static_cast<Eigen::Index>(free.size());
  const Problem problem(d, w, x, free);
  Vector lower(m), upper(m);
  typename Problem::Point current, trial;
  current.x.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const std::size_t k = free[static_cast<std::size_t>(i)];
    lower(i) = L.info[k].lower;
    upper(i) = L.info[k].upper;
    current.x(i) = std::clamp(x[k], lower(i), upper(i));
  }
  if (!problem.evaluate(current)) return false;  // the full Ceres solve reports the undefined start
  const double initial_cost = current.cost;
  double radius = kInitialRadius, decrease_factor = 2.0;
  int iterations = 0;
  const char* message = nullptr;
  bool done = false;
  while (!done) {
    const Vector projected_gradient_step = current.x - (current.x - current.g).cwiseMax(lower).cwiseMin(upper);
    if (projected_gradient_step.template lpNorm<Eigen::Infinity>() <= o.gradient_tolerance) {
      message = "Gradient tolerance reached (bounded Levenberg-Marquardt).";
      break;
    }
    if (iterations >= o.max_iterations) {
      message = nullptr;
      break;
    }
    // The regularised normal equations over the inactive parameters; the active rows and columns
    // are replaced by the identity with a zero right-hand side (their step is 0). A parameter on a
    // bound whose step (not its gradient) points out of the box joins the active set, and the step
    // is solved again: otherwise the projection would cut it to zero and stop the iteration there.
    std::array<bool, 64> active{};
    if (m > static_cast<Eigen::Index>(active.size())) return false;  // the full Ceres solve
    for (Eigen::Index i = 0; i < m; ++i) {
      active[static_cast<std::size_t>(i)] =
          (current.x(i) <= lower(i) && current.g(i) > 0.0) || (current.x(i) >= upper(i) && current.g(i) < 0.0);
    }
    Vector step;
    for (bool again = true; again;) {
      Matrix H = current.A;
      Vector rhs = -current.g;
      for (Eigen::Index i = 0; i < m; ++i) {
        if (active[static_cast<std::size_t>(i)]) {
          H.row(i).setZero();
          H.col(i).setZero();
          H(i, i) = 1.0;
          rhs(i) = 0.0;
        } else {
          H(i, i) += std::clamp(current.A(i, i), kMinDiagonal, kMaxDiagonal) / radius;
        }
      }
      step = H.ldlt().solve(rhs);
      again = false;
      for (Eigen::Index i = 0; i < m; ++i) {
        const bool out = (current.x(i) <= lower(i) && step(i) < 0.0) || (current.x(i) >= upper(i) && step(i) > 0.0);
        if (out && !active[static_cast<std::size_t>(i)]) active[static_cast<std::size_t>(i)] = again = true;
      }
    }
    trial.x = (current.x + step).cwiseMax(lower).cwiseMin(upper);
    const Vector s = trial.x - current.x;
    // A singular Gauss-Newton matrix at a large radius gives no finite step: rejected, as a step to
    // an undefined point, so that the next one is more regularised.
    const bool finite = s.allFinite();
    ++iterations;
    if (finite && s.norm() <= (current.x.norm() + o.parameter_tolerance) * o.parameter_tolerance) {
      message = "Parameter tolerance reached (bounded Levenberg-Marquardt).";
      break;
    }
    double quality = -std::numeric_limits<double>::infinity();
    if (finite) {
      const double predicted = -(current.g.dot(s) + 0.5 * s.dot(current.A * s));
      if (problem.evaluate(trial) && predicted > 0.0) quality = (current.cost - trial.cost) / predicted;
    }
    if (quality > kMinRelativeDecrease) {
      const double change = current.cost - trial.cost;
      done = change <= o.function_tolerance * current.cost;
      if (done) message = "Function tolerance reached (bounded Levenberg-Marquardt).";
      std::swap(current, trial);
      const double t = 2.0 * quality - 1.0;
      radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - t * t * t));
      decrease_factor = 2.0;
    } else {
      radius /= decrease_factor;
      decrease_factor *= 2.0;
      if (radius < kMinRadius) {
        message = "Minimum trust region radius reached (bounded Levenberg-Marquardt).";
        break;
      }
    }
  }
  summary = ceres::Solver::Summary{};
  summary.initial_cost = initial_cost;
  summary.final_cost = current.cost;
  summary.iterations.resize(static_cast<std::size_t>(iterations) + 1);
  if (message != nullptr) {
    summary.termination_type = ceres::CONVERGENCE;
    summary.message = message;
  } else {
    summary.termination_type = ceres::NO_CONVERGENCE;
    summary.message = "Maximum number of iterations reached (bounded Levenberg-Marquardt).";
  }
  free_jacobian = std::move(current.jacobian);
  for (Eigen::Index i = 0; i < m; ++i) x[free[static_cast<std::size_t>(i)]] = current.x(i);
  return true;
}

}  // namespace

bool solve_small(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                 const std::vector<std::size_t>& free, std::vector<double>& x, ceres::Solver::Summary& summary,
                 std::vector<double>& free_jacobian) {
  switch (free.size()) {
    case 1:
      return solve_sized<1>(d, L, o, w, free, x, summary, free_jacobian);
    case 2:
      return solve_sized<2>(d, L, o, w, free, x, summary, free_jacobian);
    case 3:
      return solve_sized<3>(d, L, o, w, free, x, summary, free_jacobian);
    case 4:
      return solve_sized<4>(d, L, o, w, free, x, summary, free_jacobian);
    case 5:
      return solve_sized<5>(d, L, o, w, free, x, summary, free_jacobian);
    case 6:
      return solve_sized<6>(d, L, o, w, free, x, summary, free_jacobian);
    default:
      return solve_sized<Eigen::Dynamic>(d, L, o, w, free, x, summary, free_jacobian);
  }
}

}  // namespace roadbrdf::fitting
