#include "roadbrdf/fitting/small_solve.h"

#include <ceres/tiny_solver.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "roadbrdf/fitting/cost_functions.h"

namespace roadbrdf::fitting {

namespace {

// The wavelength's residuals for TinySolver: FreeWavelengthCost (values and gradients computed
// together and kept, so the Jacobian request at an accepted point costs no model evaluation),
// its row-major Jacobian transposed into TinySolver's column-major one. A point outside the
// parameter box, or one where the model is undefined, gets infinite residuals: TinySolver then
// rejects the step and shortens the next one, as Ceres does with an undefined cost.
// `FreeCount`: the number of free parameters when known at compile time (Eigen's fixed-size
// normal equations and LDLT are several times cheaper than the dynamic ones), else Eigen::Dynamic.
template <int FreeCount>
class BoxedResiduals {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = FreeCount };

  BoxedResiduals(const FitData& d, const ParameterLayout& L, std::size_t w, const std::vector<double>& x,
                 const std::vector<std::size_t>& free)
      : cost_(d, w, x, free), n_(d.n), nf_(free.size()), row_major_(d.n * free.size()) {
    for (std::size_t k : free) {
      lower_.push_back(L.info[k].lower);
      upper_.push_back(L.info[k].upper);
    }
  }

  int NumResiduals() const { return static_cast<int>(n_); }
  int NumParameters() const { return static_cast<int>(nf_); }

  bool operator()(const double* x, double* residuals, double* jacobian) const {
    bool inside = true;
    for (std::size_t i = 0; i < nf_; ++i) inside = inside && x[i] >= lower_[i] && x[i] <= upper_[i];
    if (!inside) left_box_ = true;
    double* rows = row_major_.data();
    if (!inside || !cost_.Evaluate(&x, residuals, jacobian != nullptr ? &rows : nullptr)) {
      if (jacobian != nullptr) undefined_ = true;  // at the start or an accepted point: not recoverable
      for (std::size_t g = 0; g < n_; ++g) residuals[g] = std::numeric_limits<double>::infinity();
      return false;
    }
    if (jacobian != nullptr) {
      for (std::size_t i = 0; i < nf_; ++i) {
        for (std::size_t g = 0; g < n_; ++g) jacobian[i * n_ + g] = row_major_[g * nf_ + i];
      }
    }
    return true;
  }

  // Row-major Jacobian of the last evaluation that asked for one.
  const std::vector<double>& row_major_jacobian() const { return row_major_; }
  bool left_box() const { return left_box_; }
  bool undefined() const { return undefined_; }

 private:
  FreeWavelengthCost cost_;
  std::size_t n_, nf_;
  std::vector<double> lower_, upper_;
  mutable std::vector<double> row_major_;
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
  Eigen::VectorXd r0(static_cast<Eigen::Index>(d.n));
  if (!residuals(block.data(), r0.data(), nullptr)) return false;
  // Ceres stops when a successful step changes the cost by less than function_tolerance times the
  // cost before it; TinySolver compares the change of sum r^2 (twice the cost) with an absolute
  // tolerance. It is therefore run in rounds, each with the absolute tolerance of the relative one
  // at the round's initial cost, until a round ends with a cost at least half its initial one:
  // the stopping test was then at most twice as loose as Ceres' at the final cost.
  double reference_cost = 0.5 * r0.squaredNorm();
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
      summary.initial_cost = 0.5 * r0.squaredNorm();
      summary.final_cost = s.final_cost;
      summary.termination_type = ceres::CONVERGENCE;
      summary.message = termination_message<FreeCount>(s.status);
      summary.iterations.resize(static_cast<std::size_t>(iterations) + 1);
      break;
    }
    reference_cost = s.final_cost;
  }
  // The Jacobian at the solution: the model's values and gradients there are usually those kept
  // from the last evaluation, so this costs no model evaluation.
  Eigen::MatrixXd column_major(static_cast<Eigen::Index>(d.n), static_cast<Eigen::Index>(free.size()));
  if (!residuals(block.data(), r0.data(), column_major.data())) return false;
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
