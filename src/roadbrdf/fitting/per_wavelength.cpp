#include "roadbrdf/fitting/per_wavelength.h"

#include <ceres/ceres.h>

#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <thread>

#include "roadbrdf/core/progress.h"
#include "roadbrdf/fitting/cost_functions.h"
#include "roadbrdf/fitting/covariance.h"
#include "roadbrdf/fitting/small_solve.h"
#include "roadbrdf/fitting/statistics.h"

namespace roadbrdf::fitting {

namespace {

// Wavelengths per warm-start chain (see fit_per_wavelength).
constexpr std::size_t kChainLength = 32;

struct SingleSolve {
  std::vector<double> x;
  ceres::Solver::Summary summary;
  std::vector<double> free_jacobian;  // at x, N x free row-major, when the solver provides it
};

SingleSolve solve_one(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                      std::vector<double> x) {
  if (d.robust != RobustLoss::kNone) {
    // A robust loss is not convex: start it from the plain least-squares solution.
    FitData plain = d;
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
  // The plain loss is solved by the small bounded Levenberg-Marquardt of small_solve.h; the full
  // Ceres solve (robust losses, an undefined start) when that does not apply.
  if (d.robust == RobustLoss::kNone && solve_small(d, L, o, w, free, s.x, s.summary, s.free_jacobian)) return s;
  std::vector<double> block(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) block[i] = x[free[i]];
  ceres::Problem::Options po;
  po.enable_fast_removal = false;
  ceres::Problem problem(po);
  problem.AddResidualBlock(new FreeWavelengthCost(d, w, x, free), nullptr, block.data());
  add_bounds(problem, block.data(), free, L.info);
  ceres::Solve(solver_options(o), &problem, &s.summary);
  for (std::size_t i = 0; i < free.size(); ++i) s.x[free[i]] = block[i];
  return s;
}

// Solves wavelength w from the warm start (and the other candidates of the multi-start), fills
// `out` and returns the winning parameters. `chain_start`: w is the first wavelength of its chain,
// whose warm start is the given start itself.
std::vector<double> fit_wavelength(const FitData& d, const ParameterLayout& L, const FitOptions& o, std::size_t w,
                                   const std::vector<double>& warm, bool chain_start,
                                   const std::vector<std::vector<double>>& lhs, std::size_t n_free,
                                   WavelengthFit& out) {
  std::vector<std::vector<double>> candidates;
  candidates.push_back(warm);
  if (o.multistart >= 2 && !chain_start && o.warm_start) candidates.push_back(L.start);
  for (const auto& q : lhs) candidates.push_back(q);
  while (candidates.size() > static_cast<std::size_t>(std::max(1, o.multistart))) candidates.pop_back();
  SingleSolve best;
  double best_cost = std::numeric_limits<double>::infinity();
  int best_index = 0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    throw_if_interrupted();  // a multi-start of thousands of solves stops at Ctrl-C (core/progress.h)
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
    wavelength_covariance(d, L, w, out, best.free_jacobian);
  } else {
    no_covariance(L, out, "not computed");
  }
  return std::move(best.x);
}

}  // namespace

// Warm-start chains of fixed length, independent of the thread count (so are the results): the
// wavelengths are cut into chains of kChainLength; the first wavelength of each chain (its anchor)
// starts from the previous anchor's solution, the others from the previous wavelength's. The
// anchors are solved in order by the calling thread, which hands each chain's remainder to a TBB
// task as soon as its anchor is solved; progress is reported by the calling thread only.
void fit_per_wavelength(const FitData& d, const ParameterLayout& L, const FitOptions& o, FitResult& result) {
  const std::size_t M = d.m;
  result.wavelengths.assign(M, WavelengthFit{});
  std::size_t n_free = 0;
  for (std::size_t k = 0; k < d.p; ++k) {
    if (!L.fixed[k]) ++n_free;
  }
  const auto lhs = latin_hypercube(L, L.start, std::max(0, o.multistart - 2), o.seed);
  const std::size_t chains = (M + kChainLength - 1) / kChainLength;
  std::vector<std::vector<double>> anchor_solution(chains);
  std::atomic<std::size_t> done{0};
  const std::thread::id caller = std::this_thread::get_id();
  auto count_done = [&] {
    const std::size_t count = done.fetch_add(1) + 1;
    if (o.progress && std::this_thread::get_id() == caller) o.progress(count, M);
  };
  auto run_chain_rest = [&](std::size_t c) {
    std::vector<double> warm = anchor_solution[c];
    for (std::size_t w = c * kChainLength + 1; w < std::min(M, (c + 1) * kChainLength); ++w) {
      std::vector<double> x =
          fit_wavelength(d, L, o, w, o.warm_start ? warm : L.start, false, lhs, n_free, result.wavelengths[w]);
      if (o.warm_start) warm = std::move(x);
      count_done();
    }
  };
  // More threads than the machine runs at once would only make TBB warn: the results do not depend on it.
  tbb::task_arena arena(std::clamp(o.threads, 1, tbb::info::default_concurrency()));
  arena.execute([&] {
    tbb::task_group chain_tasks;
    try {
      std::vector<double> warm = L.start;
      for (std::size_t c = 0; c < chains; ++c) {
        const std::size_t w = c * kChainLength;
        anchor_solution[c] =
            fit_wavelength(d, L, o, w, o.warm_start ? warm : L.start, c == 0, lhs, n_free, result.wavelengths[w]);
        warm = anchor_solution[c];
        count_done();
        chain_tasks.run([&run_chain_rest, c] { run_chain_rest(c); });
      }
    } catch (...) {
      chain_tasks.cancel();
      chain_tasks.wait();
      throw;
    }
    chain_tasks.wait();
  });
  if (o.progress) o.progress(M, M);
}

}  // namespace roadbrdf::fitting
