#include "roadbrdf/core/coverage.h"

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

double azimuth_plane_deg(const Geometry& g) {
  double d = std::fmod(std::fabs(rad_to_deg(g.phi_r - g.phi_i)), 360.0);
  if (d > 180.0) d = 360.0 - d;
  return 180.0 - d;
}

AngularCoverage angular_coverage(const std::vector<Geometry>& geometries) {
  if (geometries.empty()) throw InputError("angular coverage of no geometry");
  AngularCoverage c;
  c.geometries = geometries.size();
  c.theta_i_min_deg = c.theta_r_min_deg = 90.0;
  for (const Geometry& g : geometries) {
    const double ti = rad_to_deg(g.theta_i), tr = rad_to_deg(g.theta_r);
    c.theta_i_min_deg = std::min(c.theta_i_min_deg, ti);
    c.theta_i_max_deg = std::max(c.theta_i_max_deg, ti);
    c.theta_r_min_deg = std::min(c.theta_r_min_deg, tr);
    c.theta_r_max_deg = std::max(c.theta_r_max_deg, tr);
    if (ti > 0.0 && tr > 0.0) c.azimuth_planes_deg.push_back(std::round(azimuth_plane_deg(g) * 10.0) / 10.0);
  }
  auto& p = c.azimuth_planes_deg;
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return c;
}

bool AngularCoverage::covers(const Geometry& g) const {
  const double t = kToleranceDeg;
  const double ti = rad_to_deg(g.theta_i), tr = rad_to_deg(g.theta_r);
  if (ti < theta_i_min_deg - t || ti > theta_i_max_deg + t) return false;
  if (tr < theta_r_min_deg - t || tr > theta_r_max_deg + t) return false;
  if (ti <= t || tr <= t) return true;  // near the normal the azimuth plane does not matter
  const double b = azimuth_plane_deg(g);
  const auto it = std::lower_bound(azimuth_planes_deg.begin(), azimuth_planes_deg.end(), b - t);
  return it != azimuth_planes_deg.end() && *it <= b + t;
}

}  // namespace roadbrdf
