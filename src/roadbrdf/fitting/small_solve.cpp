#include "roadbrdf/fitting/small_solve.h"

#include <ceres/tiny_solver.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>

#include "roadbrdf/fitting/cost_functions.h"

namespace roadbrdf::fitting {

namespace {

// The wavelength's problem for TinySolver, in compressed form. Levenberg-Marquardt needs, at an
// accepted point, only J^T J, J^T r and |r|^2, and at a trial point only |r|^2. So, instead of the
// N residuals and the N x free Jacobian, TinySolver is given free + 1 "residuals": at an accepted
// point the columns of R, the upper triangular factor of the Gram matrix G = [J r]^T [J r] = R^T R
// (free + 1 square: J' = R's first free columns, r' = its last), for which J'^T J' = J^T J,
// J'^T r' = J^T r and |r'|^2 = |r|^2; at a trial point (0, ..., 0, |r|). The normal equations and
// steps are those of the full problem (to rounding), while TinySolver's products J^T J and J^T r
// shrink from N x free (which Eigen computed by its general matrix product, ~11 % of a 2-parameter
// wavelength fit's instructions) to free + 1 rows. G is summed from the model's row-major Jacobian
// as it comes, R is its Cholesky factor; when G is singular (an exact fit: r in the span of J; or a
// rank-deficient J) R comes from a Householder QR of [J r] instead, which exists for any rank.
// The full residuals and row-major Jacobian of the last evaluation are kept (final cost,
// covariance). A point outside the parameter box, or one where the model is undefined, gets
// infinite residuals: TinySolver then rejects the step and shortens the next one, as Ceres does
// with an undefined cost.
// `FreeCount`: the number of free parameters when known at compile time (Eigen's fixed-size
// normal equations and LDLT are several times cheaper than the dynamic ones), else Eigen::Dynamic.
template <int FreeCount>
class BoxedResiduals {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = FreeCount == Eigen::Dynamic ? Eigen::Dynamic : FreeCount + 1, NUM_PARAMETERS = FreeCount };

  BoxedResiduals(const FitData& d, const ParameterLayout& L, std::size_t w, const std::vector<double>& x,
                 const std::vector<std::size_t>& free)
      : cost_(d, w, x, free), n_(d.n), nf_(free.size()), residuals_(d.n), row_major_(d.n * free.size()) {
    for (std::size_t k : free) {
      lower_.push_back(L.info[k].lower);
      upper_.push_back(L.info[k].upper);
    }
  }

  int NumResiduals() const { return static_cast<int>(nf_ + 1); }
  int NumParameters() const { return static_cast<int>(nf_); }

  // `residuals`: free + 1 values; `jacobian`: free + 1 x free, column-major (TinySolver's layout).
  bool operator()(const double* x, double* residuals, double* jacobian) const {
    bool inside = true;
    for (std::size_t i = 0; i < nf_; ++i) inside = inside && x[i] >= lower_[i] && x[i] <= upper_[i];
    if (!inside) left_box_ = true;
    double* rows = row_major_.data();
    if (!inside || !cost_.Evaluate(&x, residuals_.data(), jacobian != nullptr ? &rows : nullptr)) {
      if (jacobian != nullptr) undefined_ = true;  // at the start or an accepted point: not recoverable
      for (std::size_t i = 0; i <= nf_; ++i) residuals[i] = std::numeric_limits<double>::infinity();
      return false;
    }
    if (jacobian == nullptr) {
      for (std::size_t i = 0; i < nf_; ++i) residuals[i] = 0.0;
      residuals[nf_] = std::sqrt(squared_norm());
      return true;
    }
    const Factor R = factor();
    const auto m = static_cast<Eigen::Index>(nf_);
    for (Eigen::Index i = 0; i <= m; ++i) residuals[i] = R(i, m);
    for (Eigen::Index c = 0; c < m; ++c) {
      for (Eigen::Index i = 0; i <= m; ++i) jacobian[c * (m + 1) + i] = R(i, c);
    }
    return true;
  }

  // 1/2 |r|^2 of the last evaluation, from the full residuals.
  double cost() const { return 0.5 * squared_norm(); }
  // Row-major Jacobian of the last evaluation that asked for one.
  const std::vector<double>& row_major_jacobian() const { return row_major_; }
  bool left_box() const { return left_box_; }
  bool undefined() const { return undefined_; }

 private:
  static constexpr int kSize = NUM_RESIDUALS;
  using Factor = Eigen::Matrix<double, kSize, kSize>;

  double squared_norm() const {
    double s = 0.0;
    for (double r : residuals_) s += r * r;
    return s;
  }

  // R (free + 1 square, upper triangular) with R^T R = [J r]^T [J r].
  Factor factor() const {
    const auto m = static_cast<Eigen::Index>(nf_);
    Factor G = Factor::Zero(m + 1, m + 1);
    if constexpr (FreeCount == Eigen::Dynamic) {
      for (std::size_t g = 0; g < n_; ++g) {
        const double* row = row_major_.data() + g * nf_;
        for (Eigen::Index a = 0; a < m; ++a) {
          for (Eigen::Index b = 0; b <= a; ++b) G(a, b) += row[a] * row[b];
          G(m, a) += residuals_[g] * row[a];
        }
        G(m, m) += residuals_[g] * residuals_[g];
      }
    } else {
      // Lower triangle of the Gram matrix in plain sums over the rows, the sizes known at compile
      // time (unrolled; the Eigen element access in the loop was 20 k instructions per call).
      constexpr int k = FreeCount;
      std::array<double, (k + 1) * (k + 2) / 2> sum{};
      for (std::size_t g = 0; g < n_; ++g) {
        std::array<double, k + 1> v;
        for (int a = 0; a < k; ++a) v[static_cast<std::size_t>(a)] = row_major_[g * k + static_cast<std::size_t>(a)];
        v[k] = residuals_[g];
        std::size_t i = 0;
        for (int a = 0; a <= k; ++a) {
          for (int b = 0; b <= a; ++b) sum[i++] += v[static_cast<std::size_t>(a)] * v[static_cast<std::size_t>(b)];
        }
      }
      std::size_t i = 0;
      for (int a = 0; a <= k; ++a) {
        for (int b = 0; b <= a; ++b) G(a, b) = sum[i++];
      }
    }
    const Eigen::LLT<Factor> llt(G);  // reads the lower triangle
    if (llt.info() == Eigen::Success) return Factor(llt.matrixU());
    Eigen::Matrix<double, Eigen::Dynamic, kSize> A(static_cast<Eigen::Index>(n_), m + 1);
    for (std::size_t g = 0; g < n_; ++g) {
      const auto gi = static_cast<Eigen::Index>(g);
      for (Eigen::Index a = 0; a < m; ++a) A(gi, a) = row_major_[g * nf_ + static_cast<std::size_t>(a)];
      A(gi, m) = residuals_[g];
    }
    const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, kSize>> qr(A);
    const auto k = std::min<Eigen::Index>(m + 1, A.rows());
    Factor R = Factor::Zero(m + 1, m + 1);
    R.topRows(k) = qr.matrixQR().topRows(k).template triangularView<Eigen::Upper>();
    return R;
  }

  FreeWavelengthCost cost_;
  std::size_t n_, nf_;
  std::vector<double> lower_, upper_;
  mutable std::vector<double> residuals_, row_major_;
  mutable bool left_box_ = false, undefined_ = false;
};

template <int FreeCount>
using Solver = ceres::TinySolver<BoxedResiduals<FreeCount>, Eigen::LDLT<Eigen::Matrix<double, FreeCount, FreeCount>>>;

template <int FreeCount>
const char* termination_message(typename Solver<FreeCount>::Status s) {
  switch (s) {
    case Solver<FreeCount>::GRADIENT_TOO_SMALL:
      return "Gradient tolerance reached (ceres::TinySolver).";
    case Solver<FreeCount>::RELATIVE_STEP_SIZE_TOO_SMALL:
      return "Parameter tolerance reached (ceres::TinySolver).";
    case Solver<FreeCount>::COST_CHANGE_TOO_SMALL:
      return "Function tolerance reached (ceres::TinySolver).";
    default:
      return "Converged (ceres::TinySolver).";
  }
}

template <int FreeCount>
bool solve_sized(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                 const std::vector<std::size_t>& free, std::vector<double>& x, ceres::Solver::Summary& summary,
                 std::vector<double>& free_jacobian) {
  using SizedSolver = Solver<FreeCount>;
  const BoxedResiduals<FreeCount> residuals(d, L, w, x, free);
  typename SizedSolver::Parameters block(static_cast<Eigen::Index>(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) block[static_cast<Eigen::Index>(i)] = x[free[i]];
  Eigen::VectorXd r0(static_cast<Eigen::Index>(free.size() + 1));
  if (!residuals(block.data(), r0.data(), nullptr)) return false;
  const double initial_cost = residuals.cost();
  // Ceres stops when a successful step changes the cost by less than function_tolerance times the
  // cost before it; TinySolver compares the change of sum r^2 (twice the cost) with an absolute
  // tolerance. It is therefore run in rounds, each with the absolute tolerance of the relative one
  // at the round's initial cost, until a round ends with a cost at least half its initial one:
  // the stopping test was then at most twice as loose as Ceres' at the final cost.
  double reference_cost = initial_cost;
  int iterations = 0;
  SizedSolver solver;
  solver.options.gradient_tolerance = o.gradient_tolerance;
  solver.options.parameter_tolerance = o.parameter_tolerance;
  solver.options.cost_threshold = 0.0;  // Ceres has no such test: an exact fit ends by the gradient
  for (;;) {
    solver.options.function_tolerance = 2.0 * o.function_tolerance * reference_cost;
    solver.options.max_num_iterations = o.max_iterations - iterations + 1;
    const typename SizedSolver::Summary& s = solver.Solve(residuals, &block);
    if (residuals.left_box() || residuals.undefined() || s.status == SizedSolver::HIT_MAX_ITERATIONS) return false;
    iterations += s.iterations;
    if (s.status != SizedSolver::COST_CHANGE_TOO_SMALL || s.final_cost >= 0.5 * reference_cost ||
        iterations >= o.max_iterations) {
      summary = ceres::Solver::Summary{};
      summary.initial_cost = initial_cost;
      summary.termination_type = ceres::CONVERGENCE;
      summary.message = termination_message<FreeCount>(s.status);
      summary.iterations.resize(static_cast<std::size_t>(iterations) + 1);
      break;
    }
    reference_cost = s.final_cost;
  }
  // The Jacobian at the solution: the model's values and gradients there are usually those kept
  // from the last evaluation, so this costs no model evaluation.
  Eigen::MatrixXd compressed(static_cast<Eigen::Index>(free.size() + 1), static_cast<Eigen::Index>(free.size()));
  if (!residuals(block.data(), r0.data(), compressed.data())) return false;
  summary.final_cost = residuals.cost();
  free_jacobian = residuals.row_major_jacobian();
  for (std::size_t i = 0; i < free.size(); ++i) x[free[i]] = block[static_cast<Eigen::Index>(i)];
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
    default:
      return solve_sized<Eigen::Dynamic>(d, L, o, w, free, x, summary, free_jacobian);
  }
}

}  // namespace roadbrdf::fitting
