// Ceres cost functions of the fitter (one residual block per wavelength, N residuals) and the
// solver settings shared by both modes. Internal to fitting/.
#pragma once

#include <ceres/ceres.h>

#include <cstddef>
#include <vector>

#include "roadbrdf/core/parameters.h"
#include "roadbrdf/fitting/losses.h"

namespace roadbrdf::fitting {

// Per-wavelength cost over the free parameters only: one block holding the free parameters
// (indices `free` of the full vector), the fixed ones taken from `full`. Ceres then works with an
// N x (free count) Jacobian instead of N x p projected through a SubsetManifold.
class FreeWavelengthCost final : public ceres::CostFunction {
 public:
  FreeWavelengthCost(const FitData& d, std::size_t w, std::vector<double> full, std::vector<std::size_t> free);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  const FitData& d_;
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
  JointCost(const FitData& d, std::size_t w, const std::vector<int>& block_of, const std::vector<int>& index_in_block,
            int shared_size, int local_size);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  const FitData& d_;
  std::size_t w_;
  const std::vector<int>& block_of_;
  const std::vector<int>& index_;
  mutable std::vector<double> f_, j_, full_, r_jac_;
  mutable std::vector<double> cached_full_;  // parameters of the values in f_ and gradients in j_
  mutable bool cached_ = false;
};

// Levenberg-Marquardt settings of both modes (see the comments in the definition).
ceres::Solver::Options solver_options(const FitOptions& o);

// Bounds of the block's coordinates from the metadata of parameters `indices`.
void add_bounds(ceres::Problem& problem, double* block, const std::vector<std::size_t>& indices,
                const std::vector<ParameterInfo>& info);

// Fix coordinates `constant` (indices inside the block) of a block of size `size`.
void fix_coordinates(ceres::Problem& problem, double* block, int size, const std::vector<int>& constant);

inline bool converged(const ceres::Solver::Summary& s) { return s.termination_type == ceres::CONVERGENCE; }

}  // namespace roadbrdf::fitting
