// Virtual gonioreflectometer: Monte Carlo path tracing of a virtual road sample.
//
// Set-up. The sample is a periodic height field (height_field.h) lit by a collimated source in the
// direction w_i = (theta_i, phi_i) giving irradiance E_perp on a plane perpendicular to the beam,
// i.e. E = E_perp cos(theta_i) per unit area of the mean plane. A far-field detector looks from the
// direction w_r = (theta_r, phi_r) with a finite acceptance cone of half-angle Delta (solid angle
// Omega = 2 pi (1 - cos Delta)). Because the sample is periodic, the footprint is the whole
// period: every point of it is equivalent and there are no edges (this replaces the "central
// footprint away from the edges" of a finite sample).
//
// Quantity estimated. The detector reports the radiance leaving the sample averaged over the
// footprint A (mean-plane area) and uniformly over the directions of its cone,
//     Lbar = (1/Omega) int_cone (1/A) int_A L(x(y), w) dA(y) dw,
// where x(y) is the first surface point seen along -w through the mean-plane point y (the parallel
// beam of sight lines through A covers each projected surface point once, because the sample is
// periodic). The virtual measurement is
//     f_est(w_i, w_r) = Lbar / (E_perp cos theta_i),
// which is the cone-averaged BRDF (1/Omega) int_cone f_eff(w_i, w) dw of the sample. For a flat
// sample of one material it is exactly the cone average of that material's BRDF; for Delta -> 0 it
// is the BRDF. Cone directions below the horizon see nothing (contribute 0; keep theta_r + Delta
// <= 90 deg for a meaningful value).
//
// Estimator. One sample = one path started from the detector: w uniform in the cone (pdf 1/Omega),
// y uniform in the period (pdf 1/A), so (Omega A) Lbar / (Omega A) = E[L(x, w)] and
//     f_est = E[ L(x, w) / (E_perp cos theta_i) ].
// L(x, w) is expanded along the path x_1 = x, x_2, ... (normals n_k, materials m_k):
//   - next-event estimation towards the source at every vertex: the collimated source is a delta
//     light, its reflected radiance at x_k is f_mk(w_i, w_out) E_perp (n_k . w_i)^+ V(x_k, w_i), so
//     the contribution per unit E_perp cos theta_i is beta_k f_mk(w_i, w_out) (n_k . w_i)^+ V / cos theta_i
//     (V: shadow ray along w_i, 1 if it escapes the height field);
//   - continuation: w_new drawn with density p(w_new) over the hemisphere of n_k, throughput
//     beta_{k+1} = beta_k f_mk(w_new, w_out) (n.w_new) / p(w_new). Two choices (RenderSettings::sampling):
//       cosine: p = (n.w)/pi, so beta_{k+1} = beta_k pi f;
//       brdf (default): with probability c (brdf_sampling_fraction, 0.5) from the material's tabulated
//         sampler (brdf_sampler.h: piecewise-constant density ~ wavelength-averaged f cos tabulated
//         over theta_o bins), otherwise cosine-weighted; whichever was used, p is the mixture
//         c p_table + (1 - c)(n.w)/pi evaluated at w_new: the one-sample model of multiple importance
//         sampling with the balance heuristic (Veach 1997, PhD thesis, sec. 9.2.4). It is the exact
//         density of the drawn direction and > 0 wherever f cos > 0 (cosine part), so the estimator
//         stays unbiased whatever the table's accuracy; c < 1 is required;
//     a material with an ideal specular (delta) part R takes the mirror direction with probability
//     1/2 (weight R / (1/2)) and the smooth branch above otherwise (weight f cos / (p/2));
//   - Russian roulette from vertex `rr_start_bounce` on: survival q = min(0.95, max_lambda |beta|),
//     beta /= q (unbiased; the 0.95 cap guarantees termination for non-absorbing materials).
// The source can never be hit by a continuation ray (delta light), so the estimator has no
// double counting. One geometric path serves every wavelength: the sampling does not depend on
// wavelength and the throughput is carried per wavelength (spectral estimates are correlated,
// which is fine for a BRDF dataset).
// Delta parts: a path whose reflection next to the source is an ideal mirror cannot be found from
// the detector (next-event estimation evaluates the smooth part; a mirror sends a continuation
// towards the delta source with probability 0). When a material has a delta part, each sample
// therefore adds one source-side light path (path_integrator.cpp, source_delta_paths): y uniform, first hit
// x_1 along -w_i; if x_1 has a delta part R the beam (flux fraction R) leaves along the mirror
// direction and is followed: escaping after a mirror it scores beta 1[w_s in cone] / (Omega cos theta_s)
// (the single-bounce spike needs a cone, Delta > 0), and at every later vertex x_j it is connected to
// the detector through x_j's smooth part (beta f_j(w_in, w) (n_j.w) V / cos theta_w, w uniform in the
// cone; albedo: w cosine-weighted, times pi), then continues through the mirror (probability 1/2) or a
// cosine-weighted smooth direction, with the same Russian roulette. Detector paths count the paths whose
// vertex next to the source reflects through its smooth part, light paths those whose vertex next to
// the source is a mirror: no path is counted twice or missed (white furnace of a rough, non-absorbing
// Simonot sample: albedo 1 within noise; without the light paths it was 0.97-0.98).
//
// Uncertainty: the standard error of the mean of the N per-path values, sqrt(s^2 / N), per
// wavelength. Seeds: every block of `paths_per_block` (256) paths of geometry g has its own random
// stream derived from (seed, g, block), so results do not depend on the number of threads.
// Path count: fixed (`samples`), or adaptive (target_relative_error > 0): min_blocks (4, i.e. 1024
// paths) blocks first, then rounds that add the blocks predicted to reach
//     sigma_lambda <= max(target |mean_lambda|, absolute_error_floor)   at every wavelength
// (paths needed ~ N (sigma / tolerance)^2, at most 3x the blocks done per round), until it holds or
// max_samples paths are used (then Estimate::converged = false; reported, never hidden). Decisions
// use only completed blocks merged in block order, so the result is deterministic and independent
// of the thread count. Stopping on an estimated error biases the mean slightly (a run whose mean
// fluctuated up looks relatively more precise and stops earlier): the bias is of the order of
// target^2 relative (1e-4 at 1 %), and the minimum of 1024 paths keeps the error estimate itself
// from stopping on a lucky first block.
// Ray traversal: exact, over the periodic grid (2-D DDA, skipping blocks of cells the ray passes
// above; tracer.h), with the two planar triangles of each cell; the height along the ray is piecewise
// linear in each cell, so hits are found exactly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/materials.h"
#include "roadbrdf/surface/tracer.h"

namespace roadbrdf::surface {

// How continuation directions are drawn (see the header comment).
enum class Sampling {
  cosine,  // cosine-weighted about the facet normal (pdf cos/pi)
  brdf,    // one-sample MIS mixture of the material's tabulated BRDF sampler and cosine sampling
};
inline constexpr EnumName<Sampling> kSamplingNames[] = {
    {Sampling::brdf, "brdf", "tabulated BRDF mixed with cosine, MIS"},
    {Sampling::cosine, "cosine", "cosine-weighted about the facet normal"},
};
constexpr std::span<const EnumName<Sampling>> enum_names(Sampling) { return kSamplingNames; }

// The most paths per geometry a render takes (samples, max_samples): 2^30 paths of ~1 us each are
// about 20 min of one core per geometry, beyond any use of the estimate (its standard error falls as
// 1/sqrt(paths)). Memory does not grow with the count (the blocks are scheduled in bounded rounds).
inline constexpr long kMaxPathsPerGeometry = 1L << 30;

struct RenderSettings {
  long samples = 4096;                     // paths per geometry (when target_relative_error == 0)
  double acceptance_half_angle_deg = 1.0;  // detector cone half-angle Delta; 0 = ideal direction
  std::uint64_t seed = 1;
  int threads = 0;             // 0 = hardware concurrency
  int rr_start_bounce = 3;     // Russian roulette from this vertex on (1-based)
  int max_bounces = 0;         // 0 = unlimited; 1 = single scattering (direct light only)
  long paths_per_block = 256;  // one random stream per (geometry, block)
  Sampling sampling = Sampling::brdf;
  double brdf_sampling_fraction = 0.5;  // probability of drawing from the BRDF table (brdf sampling)
  // Adaptive sampling (on when target_relative_error > 0): blocks are added until, at every
  // wavelength, standard_error <= max(target_relative_error |mean|, absolute_error_floor), with at
  // least min_blocks blocks and at most max_samples paths.
  double target_relative_error = 0.0;
  double absolute_error_floor = 1e-5;  // [sr^-1]
  long max_samples = 1L << 20;
  int min_blocks = 4;
  // Memory for the sums of the blocks run at once (2 doubles per wavelength per block): a round of
  // more blocks runs in chunks. The results do not depend on it.
  std::size_t chunk_bytes = std::size_t{64} << 20;
  // Blocks of paths done out of those scheduled so far (adaptive rounds add to the total);
  // render_albedo reports estimates (sun zeniths and white-sky nodes) instead.
  ProgressCallback progress;
};

struct Estimate {
  std::vector<double> mean;            // per wavelength
  std::vector<double> standard_error;  // per wavelength
  long paths = 0;
  bool converged = true;  // adaptive: the target was reached (false: stopped at max_samples)
  // Largest standard_error / |mean| over wavelengths (infinity when a mean is 0 with a non-zero error).
  double worst_relative_error() const;
};

class Renderer {
 public:
  Renderer(const HeightField& field, std::vector<RenderMaterial> materials, std::size_t wavelength_count);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Cone-averaged BRDF [sr^-1] at one geometry (see above); `stream` selects the random streams
  // (the geometry's index in a dataset).
  Estimate brdf(const Geometry& g, const RenderSettings& settings, std::uint64_t stream = 0) const;
  // Directional-hemispherical reflectance (albedo) for incidence (theta_i, phi_i) [rad]: the same
  // path estimator with the detector direction drawn cosine-weighted over the hemisphere, value pi * f.
  Estimate directional_albedo(double theta_i, double phi_i, const RenderSettings& settings,
                              std::uint64_t stream = 0) const;
  // Many geometries, in parallel (blocks of paths over threads).
  std::vector<Estimate> brdf(const std::vector<Geometry>& geometries, const RenderSettings& settings) const;

  using Hit = SurfaceHit;
  // First intersection of the ray o + t d (t > 0, d unit) with the surface; false if it escapes.
  bool intersect(const Vec3& o, const Vec3& d, Hit& hit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Render a dataset: geometries x wavelengths, sigma = Monte Carlo standard error, metadata
// describing the virtual instrument.
// `estimates` (optional) receives the per-geometry estimates (paths, convergence).
SpectralDataset render_dataset(const HeightField& field, const std::vector<Geometry>& geometries,
                               const std::vector<double>& wavelengths, const RenderSettings& settings,
                               std::vector<Estimate>* estimates = nullptr);

}  // namespace roadbrdf::surface
