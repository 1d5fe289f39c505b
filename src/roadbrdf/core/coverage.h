// The angular coverage of a set of measured geometries: what a fit was fitted to,
// recorded in the fit file, so that albedo and r-tables can say how much of their result lies
// outside the measured directions (extrapolation by the model).
//
// Covered: a geometry whose theta_i and theta_r lie in the measured ranges widened by
// kToleranceDeg, and whose azimuth plane (beta = 180 deg - |phi_r - phi_i| folded into [0, 180],
// isotropic surfaces) lies within kToleranceDeg of a measured plane. Within kToleranceDeg of the
// normal (theta_i or theta_r) the azimuth plane does not matter.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/core/geometry.h"

namespace roadbrdf {

struct AngularCoverage {
  static constexpr double kToleranceDeg = 5.0;
  double theta_i_min_deg = 0.0, theta_i_max_deg = 0.0;
  double theta_r_min_deg = 0.0, theta_r_max_deg = 0.0;
  std::vector<double> azimuth_planes_deg;  // distinct beta [deg], 0.1 deg resolution, increasing
  std::size_t geometries = 0;              // measured geometries

  bool covers(const Geometry& g) const;
};

// beta = 180 - |phi_r - phi_i| folded into [0, 180] [deg].
double azimuth_plane_deg(const Geometry& g);

// Coverage of `geometries` (at least one). Throws InputError when empty.
AngularCoverage angular_coverage(const std::vector<Geometry>& geometries);

}  // namespace roadbrdf
