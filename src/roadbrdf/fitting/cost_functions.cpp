#include "roadbrdf/fitting/cost_functions.h"

#include <cmath>
#include <utility>

namespace roadbrdf::fitting {

FreeWavelengthCost::FreeWavelengthCost(const FitData& d, std::size_t w, std::vector<double> full,
                                       std::vector<std::size_t> free)
    : d_(d), w_(w), full_(std::move(full)), free_(std::move(free)), f_(d.n), j_(d.n * d.p) {
  set_num_residuals(static_cast<int>(d.n));
  mutable_parameter_block_sizes()->push_back(static_cast<int>(free_.size()));
}

bool FreeWavelengthCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  for (std::size_t i = 0; i < free_.size(); ++i) full_[free_[i]] = parameters[0][i];
  double* jac = (jacobians != nullptr && jacobians[0] != nullptr) ? jacobians[0] : nullptr;
  if (d_.loss != FitLoss::kLog && d_.robust == RobustLoss::kNone) {
    // Fast path of FitData::residuals for the losses r = m (f - y): the same arithmetic, written
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

JointCost::JointCost(const FitData& d, std::size_t w, const std::vector<int>& block_of,
                     const std::vector<int>& index_in_block, int shared_size, int local_size)
    : d_(d), w_(w), block_of_(block_of), index_(index_in_block), f_(d.n), j_(d.n * d.p), full_(d.p), r_jac_(d.n * d.p) {
  set_num_residuals(static_cast<int>(d.n));
  mutable_parameter_block_sizes()->push_back(shared_size);
  mutable_parameter_block_sizes()->push_back(local_size);
}

bool JointCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  for (std::size_t k = 0; k < d_.p; ++k) full_[k] = parameters[block_of_[k]][index_[k]];
  const bool want = jacobians != nullptr && (jacobians[0] != nullptr || jacobians[1] != nullptr);
  // As in FreeWavelengthCost: Ceres evaluates a candidate point without the Jacobian and asks for it
  // at the same point once it accepts the step, so values and gradients are computed together at
  // each new point and kept.
  if (!cached_ || cached_full_ != full_) {
    d_.model->evaluate_prepared_with_gradient(*d_.prepared_geometries, full_.data(), f_.data(), j_.data());
    cached_full_ = full_;
    cached_ = true;
  }
  if (!d_.residuals_of_values(w_, f_.data(), want ? j_.data() : nullptr, residuals, want ? r_jac_.data() : nullptr,
                              true)) {
    return false;
  }
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

void add_bounds(ceres::Problem& problem, double* block, const std::vector<std::size_t>& indices,
                const std::vector<ParameterInfo>& info) {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    problem.SetParameterLowerBound(block, static_cast<int>(i), info[indices[i]].lower);
    problem.SetParameterUpperBound(block, static_cast<int>(i), info[indices[i]].upper);
  }
}

void fix_coordinates(ceres::Problem& problem, double* block, int size, const std::vector<int>& constant) {
  if (size == 0) return;
  if (static_cast<int>(constant.size()) == size) {
    problem.SetParameterBlockConstant(block);
  } else if (!constant.empty()) {
    problem.SetManifold(block, new ceres::SubsetManifold(size, constant));
  }
}

}  // namespace roadbrdf::fitting
