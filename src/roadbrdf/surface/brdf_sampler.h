// Tabulated importance sampler of a material's BRDF for the path tracer (render.h), generic over
// every model (the model is a black box: only its FixedSetEvaluator is called, as by the renderer).
//
// For an outgoing (viewer-side) direction w_o in the local frame of a facet (z = normal), the
// continuation direction w (the direction towards which the light path continues, i.e. the
// incoming direction of the BRDF f(w, w_o)) should be drawn with a density close to
// f(w, w_o) cos(theta). The sampler tabulates, for `theta_o_bins` bins of theta_o (uniform in
// theta_o over [0, 90 deg]), the wavelength-averaged g = f(w, w_o) cos(theta) at the centres of a
// `cos_theta_bins` x `delta_phi_bins` grid over (cos theta in [0, 1], |phi - phi_o| in [0, pi]),
// evaluated at the centre theta_o of the bin. Each table defines a piecewise-constant density in
// (cos theta, |delta phi|), made symmetric in the sign of delta phi:
//     pdf(w | w_o) = P_cell / (d_cos * d_phi) / 2   [sr^-1]  (d omega = d cos(theta) d phi),
// with P_cell the cell's share of the table's sum (stored as its row's and column's CDF interval widths). sample()
// draws the cell from the marginal (cos-theta rows) and conditional (delta-phi columns) cumulative tables, a uniform
// point inside the cell and a random sign of delta phi: pdf() is then exactly the density of sample() (inverse
// transform sampling of a piecewise-constant 2-D density, e.g. Pharr, Jakob & Humphreys, PBRT 3rd
// ed. sec. 13.6.7; written from that description). Nothing in the estimator assumes that the table
// matches f (isotropy, reciprocity, resolution only affect the variance): the renderer combines
// this density with cosine sampling (one-sample multiple importance sampling with the balance
// heuristic, Veach 1997 sec. 9.2.4: the mixture density), which is positive wherever f cos > 0.
// A material whose table is all zero (black) gets the uniform table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::surface {

struct BrdfSamplerSettings {
  int theta_o_bins = 18;    // bins of theta_o, uniform in angle (5 deg)
  int cos_theta_bins = 64;  // rows, uniform in cos(theta)
  int delta_phi_bins = 96;  // columns, uniform in |phi - phi_o| over [0, pi]
  int max_wavelengths = 4;  // the table averages f over at most this many evenly spread wavelengths
};

class BrdfSampler {
 public:
  // `parameters`: wavelength_count parameter sets of `model` (row-major), as in RenderMaterial.
  BrdfSampler(const Model& model, const std::vector<double>& parameters, std::size_t wavelength_count,
              const BrdfSamplerSettings& settings = {});

  // Draw a direction (local frame, upper hemisphere) for the outgoing direction w_o (local, z > 0)
  // from three uniform numbers in [0, 1); returns its density [sr^-1] in `pdf`.
  Vec3 sample(const Vec3& w_o, double u1, double u2, double u3, double& pdf) const;
  // Density [sr^-1] of sample() at w (0 for w.z <= 0).
  double pdf(const Vec3& w_o, const Vec3& w) const;

  const BrdfSamplerSettings& settings() const { return settings_; }

 private:
  int theta_o_bin(const Vec3& w_o) const;
  static double cell_probability(const float* row_cdf, const float* column_cdf, int r, int c);
  BrdfSamplerSettings settings_;
  // Per theta_o bin: the row CDF (cos_theta_bins + 1 values) and per row the column CDF
  // (cos_theta_bins x (delta_phi_bins + 1)), in float: the tables of three materials then take
  // 1.7 MB rather than 5.4 MB, which matters for the caches of a path tracer that reads them at every
  // vertex. A cell's probability is the product of its two interval widths (cell_probability), the
  // probability with which sample() draws it, so pdf() is exactly the density of sample() whatever
  // the rounding of the stored values.
  std::vector<float> row_cdf_, column_cdf_;
  // Guide tables of the row and column CDFs (brdf_sampler.cpp, fill_guide): an interval index per
  // interval, so at most kMaxBins bins per axis.
  static constexpr int kMaxBins = 256;
  std::vector<std::uint8_t> row_guide_, column_guide_;
};

}  // namespace roadbrdf::surface
