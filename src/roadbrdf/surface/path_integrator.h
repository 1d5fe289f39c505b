// The path estimator of the virtual gonioreflectometer: one sample = one detector path (with
// next-event estimation towards the collimated source) plus, when a material has an ideal specular
// part, one source-side light path. The estimator, its weights and why it is unbiased are described
// at the top of render.h; this is its implementation for one sample.
#pragma once

#include <cstdint>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/surface/materials.h"
#include "roadbrdf/surface/tracer.h"

namespace roadbrdf::surface {

struct RenderSettings;

// One kind of estimate: the detector cone around w_center (cos_delta = cosine of its half-angle;
// 1 = ideal detector), or the whole hemisphere cosine-weighted (albedo).
struct PathJob {
  bool hemisphere = false;
  Vec3 w_center, t_center, b_center;  // cone axis and two unit vectors across it
  double cos_delta = 1.0;
  Vec3 wi;  // towards the source
  double inv_cos_i = 1.0;
  std::uint64_t stream = 0;  // random streams: the geometry's index
};

class PathIntegrator {
 public:
  PathIntegrator(const HeightFieldTracer& tracer, const MaterialSet& materials)
      : tracer_(tracer), materials_(materials), m_(materials.wavelength_count()) {}

  // Scratch space of one thread: the per-wavelength throughput and BRDF values of a path.
  struct Scratch {
    explicit Scratch(std::size_t wavelengths) : beta(wavelengths), f(wavelengths) {}
    std::vector<double> beta, f;
  };

  // One sample of f_est (render.h) for every wavelength: contrib[w], w < wavelength count.
  void sample(const PathJob& job, const RenderSettings& s, Rng& rng, double* contrib, Scratch& scratch) const;

 private:
  // Detector direction of a sample: uniform in the cone (the axis for an ideal detector), or
  // cosine-weighted over the hemisphere for the albedo (then `scale` = pi, the 1/pdf factor of the
  // cosine-weighted albedo integral; else 1).
  Vec3 detector_direction(const PathJob& job, Rng& rng, double& scale) const;
  void source_delta_paths(const PathJob& job, const RenderSettings& s, Rng& rng, double* contrib,
                          Scratch& scratch) const;
  // Continuation direction (local frame) for the smooth part at a vertex with outgoing direction
  // wo_l; returns false if none (direction at or below the horizon). `weight` = cos / pdf.
  bool continue_direction(int material, const Vec3& wo_l, const RenderSettings& s, Rng& rng, Vec3& wl,
                          double& weight) const;

  const HeightFieldTracer& tracer_;
  const MaterialSet& materials_;
  std::size_t m_;
};

}  // namespace roadbrdf::surface
