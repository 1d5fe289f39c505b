// Road-marking photometry (EN 1436, ASTM E1710): the coefficient of retroreflected luminance R_L,
// the luminance coefficient under diffuse illumination Q_d, the luminance factor beta, and the
// EN 1436 classes they reach, from a BRDF model or from measured data.
//
// Geometry (EN 1436:2018 Annex B; ASTM E1710): the "30 m geometry" of a
// driver 30 m from the marking, eye 1.2 m and headlamp 0.65 m above the road: illumination angle
// epsilon = 1.24 deg and observation angle alpha = 2.29 deg above the road surface, source and observer
// in one vertical plane on the same side. In the directions of core/geometry.h:
//   theta_i = 90 - epsilon = 88.76 deg, theta_r = 90 - alpha = 87.71 deg, phi_r - phi_i = 0 (retro side).
//
// R_L = L / E_perp, E_perp the illuminance on a plane perpendicular to the light at the marking.
// The illuminance on the road plane is E = E_perp cos(theta_i) and L = f_r E, so
//   R_L = f_r(theta_i, theta_r, retro plane) cos(theta_i)                       [cd m^-2 lx^-1]
// (x 1000 in the standard's unit, mcd m^-2 lx^-1).
//
// Q_d = L / E under uniform diffuse illumination (EN 1436:2018 Annex A), observed at
// alpha = 2.29 deg: with a sky of uniform radiance L_s, E = pi L_s and L = L_s int f_r cos(theta_i) dw_i, so
//   Q_d = (1/pi) int_{2 pi} f_r(w_i, w_r) cos(theta_i) dw_i   at theta_r = 87.71 deg   [cd m^-2 lx^-1].
// It is the black-sky albedo of the model with its two directions exchanged (f(w_r, w_i)), at a "sun"
// zenith of theta_r, divided by pi: albedo/hemisphere.h's adaptive rule computes it to its absolute
// tolerance (1e-5 on the integral by default, 0.003 mcd m^-2 lx^-1 on Q_d). A Lambertian marking of
// albedo rho has Q_d = rho / pi.
//
// Luminance factor beta (EN 1436:2018, 45/0 geometry: illumination at 45 deg from the normal,
// observation along the normal): beta = L / L_perfect-diffuser = pi f_r(45 deg, 0 deg).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"

namespace roadbrdf::photometry {

inline constexpr double kMarkingIlluminationAngleDeg = 1.24;  // epsilon, above the road surface
inline constexpr double kMarkingObservationAngleDeg = 2.29;   // alpha, above the road surface
inline constexpr double kLuminanceFactorIncidenceDeg = 45.0;  // 45/0 geometry, from the normal
inline constexpr double kMillicandela = 1000.0;               // cd -> mcd

// The retroreflection geometry of illumination angle epsilon and observation angle alpha [deg] above the
// road surface, source and observer in one vertical plane on the same side (phi_i = phi_r = 0).
Geometry retroreflection_geometry(double illumination_angle_deg, double observation_angle_deg);
// The 45/0 geometry of the luminance factor.
Geometry luminance_factor_geometry();

// R_L [mcd m^-2 lx^-1] of a BRDF value f_r [sr^-1] at illumination angle epsilon [deg]: 1000 f_r sin(epsilon)
// (= cos theta_i, see above).
double rl_from_brdf(double brdf, double illumination_angle_deg);

// One class of an EN 1436 table: its name and the least value it requires (0 for the "no
// requirement" class R0 / Q0).
struct MarkingClass {
  std::string_view name;
  double minimum;  // mcd m^-2 lx^-1
};
// EN 1436:2018 Table 4 (R_L of dry road markings): R0 no requirement, R1 >= 80, R2 >= 100, R3 >= 150,
// R4 >= 200, R5 >= 300 mcd m^-2 lx^-1.
std::span<const MarkingClass> rl_classes();
// EN 1436:2018 Table 1 (Q_d, dry road markings): Q0 no requirement, Q1 >= 80, Q2 >= 100, Q3 >= 130,
// Q4 >= 160 mcd m^-2 lx^-1.
std::span<const MarkingClass> qd_classes();
// The highest class of `classes` whose minimum `value` reaches (the first, "no requirement", for
// any value below the second).
std::string_view marking_class(std::span<const MarkingClass> classes, double value);

// Q_d [mcd m^-2 lx^-1] of a model at observation angle alpha [deg], for n_sets parameter sets (one per
// wavelength), with the quadrature's absolute error estimate.
struct QdIntegral {
  std::vector<double> value;  // per parameter set [mcd m^-2 lx^-1]
  std::vector<double> error;  // absolute error estimate [mcd m^-2 lx^-1]
  bool converged = true;
};
QdIntegral qd_of_model(const Model& model, const double* params, std::size_t n_sets, double observation_angle_deg);

// The figures of a spectral model reduced by `weighting` (photometry/rtable.h: V(lambda) x illuminant,
// one wavelength, or none for a wavelength-independent model).
struct MarkingFigures {
  double rl = 0.0;        // [mcd m^-2 lx^-1]
  double qd = 0.0;        // [mcd m^-2 lx^-1]
  double qd_error = 0.0;  // quadrature error estimate [mcd m^-2 lx^-1]
  bool qd_converged = true;
  double beta = 0.0;        // luminance factor (45/0) [1]
  double brdf_retro = 0.0;  // f_r at the retroreflection geometry [sr^-1]
};
MarkingFigures marking_figures(const SpectralModel& model, const SpectralWeighting& weighting,
                               double illumination_angle_deg, double observation_angle_deg);

// A value of measured data at a geometry: the data within `tolerance_deg` of it (directions compared
// after turning every geometry to phi_i = 0, the data taken as isotropic; the distance is
// sqrt(angle(w_i, w_i')^2 + angle(w_r, w_r')^2)), combined by inverse-square-distance weights over the
// (at most 4) nearest; one at distance 0 is taken as it is. Values are reduced over the wavelengths
// with `wavelength_weights` (one per dataset wavelength, summing to 1); a geometry whose reduced value
// is missing (NaN at a weighted wavelength) is not used.
struct DataValue {
  double value = 0.0;  // [sr^-1]
  double nearest_distance_deg = 0.0;
  std::size_t points = 0;  // measured geometries combined
};
// nullopt when no usable measured geometry lies within tolerance_deg; `nearest_distance_deg` then
// receives the distance of the nearest usable one (infinity for none).
std::optional<DataValue> data_value_at(const SpectralDataset& data, const Geometry& target,
                                       const std::vector<double>& wavelength_weights, double tolerance_deg,
                                       double* nearest_distance_deg = nullptr);

}  // namespace roadbrdf::photometry
