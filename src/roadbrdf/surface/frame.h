// Local frames of the path tracer: a facet's orthonormal basis, directions in it, the Geometry a
// model is evaluated at, and cosine-weighted directions.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::surface {

// Orthonormal basis (t, b, n) around a unit vector n (Duff et al., JCGT 6(1) 2017, the
// branchless construction; written from the paper's formulas).
inline void make_basis(const Vec3& n, Vec3& t, Vec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

inline Vec3 to_local(const Vec3& w, const Vec3& t, const Vec3& b, const Vec3& n) {
  return {dot(w, t), dot(w, b), dot(w, n)};
}

// Geometry from two local unit vectors (z = facet normal); both must be in the upper hemisphere.
// With `angles` false the angle fields are left NaN, for a material whose model reads only the
// vectors and cos_delta_phi (Model::reads_angles).
inline Geometry local_geometry(Vec3 wi, Vec3 wr, bool angles) {
  wi.z = std::clamp(wi.z, 0.0, 1.0);
  wr.z = std::clamp(wr.z, 0.0, 1.0);
  Geometry g;
  g.wi = wi;
  g.wr = wr;
  if (angles) {
    g.theta_i = std::acos(wi.z);
    g.theta_r = std::acos(wr.z);
    g.phi_i = std::atan2(wi.y, wi.x);
    g.phi_r = std::atan2(wr.y, wr.x);
  } else {
    g.theta_i = g.theta_r = g.phi_i = g.phi_r = std::numeric_limits<double>::quiet_NaN();
  }
  const double si = std::sqrt(wi.x * wi.x + wi.y * wi.y), sr = std::sqrt(wr.x * wr.x + wr.y * wr.y);
  g.cos_delta_phi = (si > 1e-12 && sr > 1e-12) ? std::clamp((wi.x * wr.x + wi.y * wr.y) / (si * sr), -1.0, 1.0) : 0.0;
  return g;
}

// Cosine-weighted direction about +z (pdf cos(theta)/pi) from two uniform numbers.
inline Vec3 cosine_direction(double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

}  // namespace roadbrdf::surface
