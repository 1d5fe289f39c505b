// Scheduling of the Monte Carlo paths of many estimates (geometries) over threads, with a fixed or
// adaptive number of paths per estimate (render.h, RenderSettings).
//
// Blocks of paths are the unit of work: block k of an estimate holds paths [k B, min((k+1) B, N_max))
// and has its own random stream (seed, estimate's stream, k). Fixed mode runs all blocks of every
// estimate in one round. Adaptive mode runs min_blocks blocks per estimate, then in rounds adds blocks
// to the estimates that have not reached the target; after each round the statistics of the completed
// blocks are merged in block order and the decision (stop, or how many blocks to add) depends only on
// them, so the result does not depend on the number of threads or on timing. The blocks of a round
// run in parallel on TBB (tbb::parallel_for in a task_arena of RenderSettings::threads threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "roadbrdf/core/random.h"

namespace roadbrdf::surface {

struct RenderSettings;
struct Estimate;

// What the scheduler runs: independent paths of estimate `job`, each giving one value per wavelength.
class PathSource {
 public:
  // Scratch space of the thread running a block (made once per block, reused by its paths).
  class Workspace {
   public:
    virtual ~Workspace() = default;
  };

  virtual ~PathSource() = default;
  virtual std::size_t wavelength_count() const = 0;
  // Random-stream index of estimate `job` (the geometry's index in a dataset).
  virtual std::uint64_t stream(std::size_t job) const = 0;
  virtual std::unique_ptr<Workspace> workspace() const = 0;
  // One path of estimate `job`: values[w], w < wavelength_count().
  virtual void path(std::size_t job, Rng& rng, Workspace& workspace, double* values) const = 0;
};

// Checks the sampling settings (block size, adaptive target, limits); throws InputError, or
// FieldError("samples" / "max_samples") for a path count beyond [2, kMaxPathsPerGeometry].
void validate_sampling(const RenderSettings& s);

// Estimates (mean and standard error per wavelength) of `job_count` estimates of `source`.
std::vector<Estimate> run_estimates(const PathSource& source, std::size_t job_count, const RenderSettings& s);

}  // namespace roadbrdf::surface
