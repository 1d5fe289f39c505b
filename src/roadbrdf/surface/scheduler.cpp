#include "roadbrdf/surface/scheduler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/surface/render.h"

namespace roadbrdf::surface {

void validate_sampling(const RenderSettings& s) {
  // Checked whether or not the path count is adaptive, so that a request is refused the same way
  // in both modes (render_settings checks a request through this function).
  if (s.max_samples < 2) throw FieldError("max_samples", fmt::format("{} is below 2", s.max_samples));
  if (s.max_samples > kMaxPathsPerGeometry) {
    throw FieldError("max_samples", fmt::format("{} is above the limit of {} paths per geometry", s.max_samples,
                                                kMaxPathsPerGeometry));
  }
  if (s.target_relative_error == 0.0 && s.samples > kMaxPathsPerGeometry) {
    throw FieldError("samples",
                     fmt::format("{} is above the limit of {} paths per geometry", s.samples, kMaxPathsPerGeometry));
  }
  if (s.paths_per_block < 1) throw InputError("render: paths_per_block must be >= 1");
  if (!(s.brdf_sampling_fraction >= 0.0 && s.brdf_sampling_fraction < 1.0)) {
    throw InputError("render: brdf_sampling_fraction must be in [0, 1) (cosine sampling keeps the estimator unbiased)");
  }
  if (!(s.target_relative_error >= 0.0) || !std::isfinite(s.target_relative_error)) {
    throw InputError("render: the target relative error must be >= 0");
  }
  if (s.target_relative_error > 0.0) {
    if (s.min_blocks < 1) throw InputError("render: min_blocks must be >= 1");
    if (!(s.absolute_error_floor >= 0.0)) throw InputError("render: the absolute error floor must be >= 0");
  } else {
    if (s.samples < 2) throw InputError("render: at least 2 paths per geometry are needed for a standard error");
  }
}

namespace {

// Mean and sum of squared deviations of the paths of one block (Welford's update), then of all the
// blocks of an estimate (the pairwise formula of Chan, Golub & LeVeque, 1979). No cancellation, so a
// deterministic estimator (e.g. a flat sample seen by an ideal detector) has exactly 0 error.
struct Accumulator {
  std::vector<double> mean, m2;
  double n = 0.0;
  long blocks = 0;
};

// Runs one block of paths into its statistics (mean, m2: m values each).
void run_block(const PathSource& source, std::size_t job, std::uint64_t seed, long block, long count, double* mean,
               double* m2, std::vector<double>& values, PathSource::Workspace& workspace) {
  const std::size_t m = source.wavelength_count();
  Rng rng(stream_seed(seed, source.stream(job), static_cast<std::uint64_t>(block)));
  for (long k = 0; k < count; ++k) {
    source.path(job, rng, workspace, values.data());
    const double inv = 1.0 / static_cast<double>(k + 1);
    for (std::size_t w = 0; w < m; ++w) {
      const double delta = values[w] - mean[w];
      mean[w] += delta * inv;
      m2[w] += delta * (values[w] - mean[w]);
    }
  }
}

}  // namespace

std::vector<Estimate> run_estimates(const PathSource& source, std::size_t job_count, const RenderSettings& s) {
  validate_sampling(s);
  const bool adaptive = s.target_relative_error > 0.0;
  const std::size_t m = source.wavelength_count();
  const long max_paths = adaptive ? s.max_samples : s.samples;
  const long B = s.paths_per_block;
  const long max_blocks = (max_paths + B - 1) / B;
  const long min_blocks = std::min<long>(adaptive ? s.min_blocks : max_blocks, max_blocks);

  std::vector<Accumulator> acc(job_count);
  for (auto& a : acc) {
    a.mean.assign(m, 0.0);
    a.m2.assign(m, 0.0);
  }
  std::vector<long> extra(job_count, min_blocks);  // blocks still to do in each job's current round
  std::vector<Estimate> out(job_count);
  tbb::task_arena arena(s.threads > 0 ? s.threads : tbb::task_arena::automatic);
  ProgressCounter progress(s.progress, 0);  // blocks done / scheduled
  // A round is run in chunks of at most max_items blocks (their sums take 2 m doubles each), so that
  // memory does not grow with the path count. A job's estimate and its next round are decided only
  // once its round is complete, and blocks are merged in (job, block) order: the chunking changes
  // no result.
  progress.add_total(static_cast<std::size_t>(min_blocks) * job_count);
  const std::size_t max_items =
      std::max<std::size_t>(1, s.chunk_bytes / (2 * std::max<std::size_t>(m, 1) * sizeof(double)));

  for (;;) {
    std::vector<std::pair<std::size_t, long>> items;  // (job, block)
    std::vector<long> taken(job_count, 0);
    for (std::size_t g = 0; g < job_count && items.size() < max_items; ++g) {
      for (; taken[g] < extra[g] && items.size() < max_items; ++taken[g])
        items.emplace_back(g, acc[g].blocks + taken[g]);
    }
    if (items.empty()) break;
    // Per block: mean and m2 (m values each) and the number of paths.
    std::vector<double> sums(items.size() * 2 * m, 0.0);
    std::vector<long> counts(items.size(), 0);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items.size(), 1),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          std::vector<double> values(m);
                          const std::unique_ptr<PathSource::Workspace> workspace = source.workspace();
                          for (std::size_t item = range.begin(); item != range.end(); ++item) {
                            const auto [job, block] = items[item];
                            const long count = std::min(B, max_paths - block * B);
                            double* mean = sums.data() + item * 2 * m;
                            run_block(source, job, s.seed, block, count, mean, mean + m, values, *workspace);
                            counts[item] = count;
                            progress.add();
                          }
                        });
    });
    // Merge in (job, block) order.
    for (std::size_t item = 0; item < items.size(); ++item) {
      Accumulator& a = acc[items[item].first];
      const double* bm = sums.data() + item * 2 * m;
      const double nb = static_cast<double>(counts[item]);
      const double nt = a.n + nb;
      for (std::size_t w = 0; w < m; ++w) {
        const double delta = bm[w] - a.mean[w];
        a.mean[w] += delta * (nb / nt);
        a.m2[w] += bm[m + w] + delta * delta * (a.n * nb / nt);
      }
      a.n = nt;
      a.blocks += 1;
    }
    // Estimates and the next round of the jobs whose round is complete.
    for (std::size_t g = 0; g < job_count; ++g) {
      extra[g] -= taken[g];
      if (taken[g] == 0 || extra[g] > 0) continue;
      const Accumulator& a = acc[g];
      Estimate& e = out[g];
      e.paths = static_cast<long>(a.n);
      e.mean = a.mean;
      e.standard_error.resize(m);
      for (std::size_t w = 0; w < m; ++w) e.standard_error[w] = std::sqrt(std::max(0.0, a.m2[w] / (a.n - 1.0)) / a.n);
      if (!adaptive) continue;
      // Ratio of the standard error to the tolerance; the paths needed scale with its square.
      double ratio = 0.0;
      for (std::size_t w = 0; w < m; ++w) {
        const double tol = std::max(s.target_relative_error * std::fabs(e.mean[w]), s.absolute_error_floor);
        if (e.standard_error[w] <= tol) continue;
        ratio = std::max(ratio, tol > 0.0 ? e.standard_error[w] / tol : std::numeric_limits<double>::infinity());
      }
      e.converged = ratio == 0.0;
      if (e.converged || a.blocks >= max_blocks) continue;
      // Blocks predicted to reach the target, at least 1, at most 3x those done (a noisy early error
      // estimate cannot launch a huge round), at most up to max_samples.
      const double needed = std::ceil(a.n * std::min(ratio * ratio, 1e12) / static_cast<double>(B));
      long add = static_cast<long>(std::min(needed, 1e15)) - a.blocks;
      add = std::clamp(add, 1L, 3 * a.blocks);
      extra[g] = std::min(add, max_blocks - a.blocks);
      progress.add_total(static_cast<std::size_t>(extra[g]));
    }
  }
  progress.finish();
  return out;
}

}  // namespace roadbrdf::surface
