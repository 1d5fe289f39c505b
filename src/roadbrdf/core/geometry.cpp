#include "roadbrdf/core/geometry.h"

#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

Vec3 Geometry::half_vector() const {
  const Vec3 h = wi + wr;
  const double len = length(h);
  if (len <= 1e-300) return {0.0, 0.0, 1.0};
  return (1.0 / len) * h;
}

Geometry Geometry::swapped() const {
  Geometry g = *this;
  g.wi = wr;
  g.wr = wi;
  g.theta_i = theta_r;
  g.theta_r = theta_i;
  g.phi_i = phi_r;
  g.phi_r = phi_i;
  return g;
}

namespace {
void check_zenith(double theta, const char* name) {
  if (!std::isfinite(theta)) throw InputError(std::string(name) + " is not a finite number");
  // Allow the rounding error of a degree -> radian conversion of exactly 90 degrees.
  if (theta < -1e-12 || theta > kPi / 2 + 1e-12) {
    throw InputError(std::string(name) + " = " + std::to_string(rad_to_deg(theta)) +
                     " deg is outside the zenith range [0, 90] deg");
  }
}
void check_azimuth(double phi, const char* name) {
  if (!std::isfinite(phi)) throw InputError(std::string(name) + " is not a finite number");
}
}  // namespace

Geometry geometry_from_radians(double theta_i, double phi_i, double theta_r, double phi_r) {
  check_zenith(theta_i, "theta_i");
  check_zenith(theta_r, "theta_r");
  check_azimuth(phi_i, "phi_i");
  check_azimuth(phi_r, "phi_r");
  theta_i = std::fmin(std::fmax(theta_i, 0.0), kPi / 2);
  theta_r = std::fmin(std::fmax(theta_r, 0.0), kPi / 2);
  Geometry g;
  g.theta_i = theta_i;
  g.theta_r = theta_r;
  g.phi_i = phi_i;
  g.phi_r = phi_r;
  g.wi = spherical_direction(theta_i, phi_i);
  g.wr = spherical_direction(theta_r, phi_r);
  // cos(90 deg) evaluates to 6e-17; make grazing exactly grazing.
  if (theta_i == kPi / 2) g.wi.z = 0.0;
  if (theta_r == kPi / 2) g.wr.z = 0.0;
  g.cos_delta_phi = (theta_i > 0.0 && theta_r > 0.0) ? std::cos(phi_r - phi_i) : 0.0;
  return g;
}

Geometry geometry_from_degrees(double theta_i, double phi_i, double theta_r, double phi_r) {
  auto exact = [](double deg) { return deg == 90.0 ? kPi / 2 : deg_to_rad(deg); };
  return geometry_from_radians(exact(theta_i), deg_to_rad(phi_i), exact(theta_r), deg_to_rad(phi_r));
}

Geometry geometry_from_road_angles(const RoadAngles& road) {
  // gamma = theta_i; alpha = 90 - theta_r; beta = 180 - (phi_r - phi_i); delta = phi_r - 180.
  const double theta_i = road.gamma;
  const double theta_r = 90.0 - road.alpha;
  const double phi_r = road.delta + 180.0;
  const double phi_i = phi_r - (180.0 - road.beta);
  return geometry_from_degrees(theta_i, phi_i, theta_r, phi_r);
}

RoadAngles road_angles_from_geometry(const Geometry& g) {
  RoadAngles road;
  road.gamma = rad_to_deg(g.theta_i);
  road.alpha = 90.0 - rad_to_deg(g.theta_r);
  road.beta = 180.0 - rad_to_deg(g.phi_r - g.phi_i);
  road.delta = rad_to_deg(g.phi_r) - 180.0;
  return road;
}

}  // namespace roadbrdf
