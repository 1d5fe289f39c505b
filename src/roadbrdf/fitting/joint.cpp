#include "roadbrdf/fitting/joint.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/fitting/cost_functions.h"
#include "roadbrdf/fitting/covariance.h"
#include "roadbrdf/fitting/statistics.h"

namespace roadbrdf::fitting {

namespace {

class ProgressCallback final : public ceres::IterationCallback {
 public:
  explicit ProgressCallback(const FitOptions& o) : o_(o) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    // An interrupt ends the solve here (Ceres is not unwound by an exception); the caller throws.
    if (interrupt_requested()) return ceres::SOLVER_ABORT;
    if (o_.progress) {
      o_.progress(static_cast<std::size_t>(s.iteration), static_cast<std::size_t>(std::max(1, o_.max_iterations)));
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FitOptions& o_;
};

}  // namespace

void fit_joint(const FitData& d, const ParameterLayout& L, const FitOptions& o, FitResult& result) {
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
    throw_if_interrupted();  // core/progress.h
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
        problem.AddResidualBlock(new JointCost(d, w, block_of, index, S, Lc), nullptr, shared.data(), lb);
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
    switch (o.joint_solver) {
      case JointSolver::kDenseSchur:
        so.linear_solver_type = ceres::DENSE_SCHUR;
        break;
      case JointSolver::kSparseSchur:
        so.linear_solver_type = ceres::SPARSE_SCHUR;
        break;
      case JointSolver::kIterativeSchur:
        so.linear_solver_type = ceres::ITERATIVE_SCHUR;
        so.preconditioner_type = ceres::JACOBI;
        break;
    }
    std::string why;
    if (!so.IsValid(&why)) {
      throw InputError("joint solver '" + name_of(o.joint_solver) + "' is not available: " + why);
    }
    so.linear_solver_ordering.reset(ordering);
    // One thread: Ceres' multi-threaded Schur elimination sums the blocks in a thread-dependent
    // order, which changed the last digits of the result with the thread count.
    so.num_threads = 1;
    ProgressCallback cb(o);
    so.callbacks.push_back(&cb);  // also polls the interrupt request
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    throw_if_interrupted();
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
    fill_statistics(d, w, out);
    // Cost of this wavelength (robust function included).
    out.cost = 0.5 * d.chi2(w, out.parameters.data(), true);
    flag_bounds(L, out);
  }

  // Covariance by the block (Schur) formula on H = J^T J (robust function not applied).
  if (!o.compute_covariance) {
    for (auto& out : result.wavelengths) no_covariance(L, out, "not computed");
    return;
  }
  joint_covariance(d, L, result.wavelengths);
}

}  // namespace roadbrdf::fitting
