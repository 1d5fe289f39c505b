// Directions and angle conventions (see README "Conventions").
//
// theta is the zenith angle from the surface normal (z axis), phi the azimuth. Both the incident
// direction w_i (towards the source) and the reflected direction w_r (towards the viewer) point
// *away* from the surface. Radians inside the library; degrees only at the edges.
// Relative azimuth dphi = phi_r - phi_i: 180 deg is the forward (specular) side, 0 the retro side.
//
// Road-photometry angles of gonioreflectometer files (report section 5.3.1):
//   gamma = theta_i,  alpha = 90 deg - theta_r,  beta = 180 deg - (phi_r - phi_i),  delta = phi_r - 180 deg.
#pragma once

#include <cmath>

namespace roadbrdf {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(const Vec3& a) { return (1.0 / length(a)) * a; }

// Unit vector of zenith theta and azimuth phi (radians).
inline Vec3 spherical_direction(double theta, double phi) {
  const double s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

// Mirror direction of w about the surface normal: (-x, -y, z) (report eq. 2.13).
inline Vec3 mirror_direction(const Vec3& w) { return {-w.x, -w.y, w.z}; }

// One measurement geometry: the pair of directions plus their angles, computed once so that
// models never repeat trigonometry in inner loops.
// A direction whose cos(theta) is at most this counts as exactly grazing (theta = 90 deg): 90 deg
// read from a file gives cos(theta) = 6.1e-17, not 0, and the next representable angles below
// 90 deg that anyone measures (89.99999 deg: cos = 1.7e-7) stay far above it. At such a direction
// there is no irradiance (incidence) or no projected area in view (viewing); the models define
// their value there as the limit or as 0 (docs/models.md, "Grazing directions").
inline constexpr double kGrazingCosine = 1e-12;

struct Geometry {
  Vec3 wi;               // towards the source
  Vec3 wr;               // towards the viewer
  double theta_i = 0.0;  // radians
  double phi_i = 0.0;    // radians
  double theta_r = 0.0;  // radians
  double phi_r = 0.0;    // radians
  // cos(phi_r - phi_i); set to 0 when either direction is the normal (azimuth undefined).
  double cos_delta_phi = 0.0;

  double cos_theta_i() const { return wi.z; }
  double cos_theta_r() const { return wr.z; }
  // Whether a direction is exactly grazing (theta = 90 deg): see kGrazingCosine.
  bool grazing_i() const;
  bool grazing_r() const;
  // Half vector (w_i + w_r)/|w_i + w_r| (report eq. 3.6). Returns the normal when w_r = -w_i,
  // which cannot happen for two upper-hemisphere directions unless both are grazing.
  Vec3 half_vector() const;

  // Geometry with incident and reflected directions exchanged (for reciprocity checks).
  Geometry swapped() const;
};

inline bool Geometry::grazing_i() const { return wi.z <= kGrazingCosine; }
inline bool Geometry::grazing_r() const { return wr.z <= kGrazingCosine; }

// Build a geometry from angles in radians. Throws InputError if a zenith angle is outside [0, pi/2]
// or an angle is not finite.
Geometry geometry_from_radians(double theta_i, double phi_i, double theta_r, double phi_r);
// Same from degrees (the file and command-line convention).
Geometry geometry_from_degrees(double theta_i, double phi_i, double theta_r, double phi_r);

// Road-photometry angles (degrees).
struct RoadAngles {
  double gamma = 0.0;  // = theta_i
  double alpha = 0.0;  // = 90 - theta_r (observation angle above the road plane)
  double beta = 0.0;   // = 180 - (phi_r - phi_i)
  double delta = 0.0;  // = phi_r - 180
};

Geometry geometry_from_road_angles(const RoadAngles& road);
RoadAngles road_angles_from_geometry(const Geometry& g);

}  // namespace roadbrdf
