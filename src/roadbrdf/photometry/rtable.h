// Road-surface r-tables (reduced luminance coefficients) from any BRDF, and their summary figures
// Q0, S1, S2, Qd and class. Definitions: CIE 144:2001 / CIE 30-2, van Bommel "Road Lighting" ch. 12;
// see docs/photometry.md.
//
// Geometry (core/geometry.h road angles): luminance coefficient q(beta, gamma) = f_r at
//   theta_i = gamma, theta_r = 90 deg - alpha (alpha = 1 deg by convention), dphi = phi_r - phi_i = 180 deg - beta,
// so beta = 0 is the forward (specular) side. Reduced coefficient r = q cos^3(gamma) [sr^-1].
// Standard grid: 20 beta columns (0, 2, 5, 10, ..., 45, 60, ..., 180 deg) x 29 tan(gamma) rows
// (0 to 2 by 0.25, 2.5 to 12 by 0.5).
//
// Scaling: an RTable holds R = 1e4 * r, the number every r-table file stores, so that files
// round-trip bit for bit; r() divides by 1e4. JSON output and the summary figures are plain sr^-1.
//
// Missing cells: cells outside the defined region of a table (the files store 0 there) are NaN,
// never zero reflectance. Summary figures skip them (see q0()). A computed table has every cell.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/model.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::photometry {

inline constexpr std::size_t kRows = 29;     // tan(gamma) values
inline constexpr std::size_t kColumns = 20;  // beta values
inline constexpr double kRScale = 1e4;       // files store R = 1e4 r

const std::array<double, kColumns>& standard_beta_deg();
const std::array<double, kRows>& standard_tan_gamma();
// gamma = atan(tan_gamma) [deg] of a row.
double gamma_deg(std::size_t row);

// Number of defined beta columns per row in the CIE standard tables (R1-R4, C1-C2 as bundled in
// data/third-party/rtables, identical in all six): all 20 up to tan(gamma) = 5, then for tan(gamma) =
// 5.5, 6, ..., 12: 10, 9, 8, 8, 7, 7, 7, 6, 6, 6, 6, 6, 5, 5 columns (beta up to 40, 35, 30, 30, 25, 25, 25,
// 20, ..., 20, 15, 15 deg); 396 cells. This is the region over which Q0 is averaged by default.
const std::array<std::size_t, kRows>& standard_region_columns();
inline bool in_standard_region(std::size_t row, std::size_t column) { return column < standard_region_columns()[row]; }

struct RTable {
  std::string name;            // free text ("CIE R3", model name...)
  double alpha_deg = 1.0;      // observation angle above the road plane [deg]
  std::vector<double> scaled;  // R = 1e4 r, kRows x kColumns, row (tan gamma) major; NaN = missing

  RTable() : scaled(kRows * kColumns, std::nan("")) {}
  double& at(std::size_t row, std::size_t column) { return scaled[row * kColumns + column]; }
  double at(std::size_t row, std::size_t column) const { return scaled[row * kColumns + column]; }
  bool defined(std::size_t row, std::size_t column) const { return !std::isnan(at(row, column)); }
  // Plain reduced luminance coefficient r [sr^-1] (NaN if missing).
  double r(std::size_t row, std::size_t column) const { return at(row, column) / kRScale; }
  // Luminance coefficient q = r / cos^3(gamma) [sr^-1] (NaN if missing).
  double q(std::size_t row, std::size_t column) const;
  std::size_t defined_count() const;
};

// The 580 road geometries of the standard grid (row major) at observation angle alpha [deg],
// 0 < alpha < 90.
std::vector<Geometry> rtable_geometries(double alpha_deg);

// How a spectral BRDF is reduced to one number per geometry.
struct SpectralWeighting {
  enum class Kind { photometric, wavelength, band };
  Kind kind = Kind::photometric;
  // photometric: f = int f(l) V(l) S(l) dl / int V(l) S(l) dl over the model's wavelength range
  // (1 nm trapezoid, parameters interpolated linearly between the fit's wavelengths as
  // SpectralModel::parameters_at does; the range must hold >= 99% of int V S dl).
  std::optional<spectra::Spectrum> illuminant;  // default: CIE illuminant A
  double wavelength_nm = 0.0;                   // wavelength: the BRDF at that wavelength
  double band_lo_nm = 0.0, band_hi_nm = 0.0;    // band: unweighted mean over [lo, hi] (1 nm trapezoid)
};

// The weighting that applies to `model`: a model with a single wavelength has no spectrum to weigh
// photometrically, so the photometric weighting becomes "at that wavelength". `note` (if given)
// receives a one-line explanation when the weighting was changed, else "".
SpectralWeighting effective_weighting(const SpectralModel& model, const SpectralWeighting& requested,
                                      std::string* note = nullptr);

// r-table of a model with one parameter set (wavelength independent). The ideal specular (delta)
// part of a model never reaches the grid at alpha = 1 deg (its mirror direction is gamma = 89 deg,
// beyond tan(gamma) = 12) and is not included.
RTable compute_rtable(const Model& model, const std::vector<double>& parameters, double alpha_deg = 1.0);
// r-table of a spectral model (fit file); a wavelength-independent SpectralModel ignores `weighting`;
// a single-band one is taken at its wavelength (effective_weighting).
RTable compute_rtable(const SpectralModel& model, const SpectralWeighting& weighting, double alpha_deg = 1.0);

// The r-table from a BRDF given at rtable_geometries(alpha_deg), in their order: what compute_rtable
// does with the values it evaluates, for a caller that has them another way.
RTable rtable_from_brdf(const std::vector<double>& brdf, double alpha_deg, std::string name);

// The wavelengths [nm] a spectral reduction evaluates the model at, with their weights (summing to
// 1; wavelengths of zero weight, V = 0 outside 340-830 nm, left out): f = sum_k weights[k] f(l_k).
// A wavelength-independent model has none. Throws InputError as compute_rtable.
struct WeightedWavelengths {
  std::vector<double> wavelengths, weights;
};
WeightedWavelengths weighted_wavelengths(const SpectralModel& model, const SpectralWeighting& weighting);

// Per-geometry weighted BRDF of a spectral model (the reduction above), for any geometries.
std::vector<double> weighted_brdf(const SpectralModel& model, const SpectralWeighting& weighting,
                                  const std::vector<Geometry>& geometries);

// ---- summary figures ------------------------------------------------------------------------
enum class Q0Region {
  standard,  // cells defined in the table and inside the CIE standard-table region (default)
  table,     // every defined cell of the table
};
inline constexpr EnumName<Q0Region> kQ0RegionNames[] = {
    {Q0Region::standard, "standard", "cells of the CIE standard tables"},
    {Q0Region::table, "table", "all defined cells"},
};
constexpr std::span<const EnumName<Q0Region>> enum_names(Q0Region) { return kQ0RegionNames; }

// Q0 = (1/Omega0) int_{Omega0} q dOmega. With t = tan(gamma): dOmega = sin(gamma) dgamma dbeta and
// dgamma = cos^2(gamma) dt, so q dOmega = r t dt dbeta and dOmega = t cos^3(gamma) dt dbeta:
//   Q0 = sum_cells r t w / sum_cells t cos^3(gamma) w,
// w = product of trapezoid weights in t and beta on the full standard grid, summed over the defined
// cells of the region. Using the same discrete rule in numerator and denominator makes Q0 exact for
// a constant q (Lambertian surface: Q0 = rho/pi to rounding); for a smooth non-constant q the
// trapezoid error is a few 1e-3 relative (tested against closed forms: docs/photometry.md).
// With Q0Region::standard this reproduces the nominal Q0 of the six CIE standard tables to their
// published 2 decimals. Throws InputError if no cell of the region is defined.
double q0(const RTable& table, Q0Region region = Q0Region::standard);
// S1 = r(beta 0, tan gamma 2) / r(0, 0); S2 = Q0 / r(0, 0). Throw InputError if a needed cell is missing.
double s1(const RTable& table);
double s2(const RTable& table, Q0Region region = Q0Region::standard);
// Qd = (1/pi) int_hemisphere q cos(gamma) dOmega, the luminance coefficient under uniform diffuse
// illumination. q cos(gamma) dOmega = r sin(gamma) dt dbeta; as for Q0 the integral is the average over
// the defined cells weighted by cos(gamma) dOmega (= cos^3 sin dt dbeta), i.e.
//   Qd = sum r sin(gamma) w / sum cos^3(gamma) sin(gamma) w,
// which equals the hemispherical definition when the defined cells are representative of the rest
// of the hemisphere (exact for a Lambertian surface; the grid stops at tan(gamma) = 12, 85.2 deg).
double qd(const RTable& table);

enum class ClassSystem { R, N, C };
inline constexpr EnumName<ClassSystem> kClassSystemNames[] = {
    {ClassSystem::R, "R", ""},
    {ClassSystem::N, "N", ""},
    {ClassSystem::C, "C", ""},
};
constexpr std::span<const EnumName<ClassSystem>> enum_names(ClassSystem) { return kClassSystemNames; }
struct RoadClass {
  std::string name;          // "R3", "N2", "C1"...
  double standard_q0 = 0.0;  // Q0 of the standard table of the class [sr^-1]
  double s1_lower = 0.0;     // class S1 limits [lower, upper)
  double s1_upper = 0.0;     // +inf for the last class
};
// Class from S1 (van Bommel, Road Lighting, Table 12.2; CIE 144):
//   R: R1 S1 < 0.42, R2 < 0.85, R3 < 1.35, R4 >= 1.35 (standard Q0 0.10, 0.07, 0.07, 0.08)
//   N: N1 S1 < 0.28, N2 < 0.60, N3 < 1.30, N4 >= 1.30 (0.10, 0.07, 0.07, 0.08)
//   C: C1 S1 < 0.40, C2 >= 0.40 (0.10, 0.07)
RoadClass classify(double s1_value, ClassSystem system = ClassSystem::R);
// The classes of a system in increasing S1, as classify() returns them (the first with s1_lower =
// -inf, the last with s1_upper = +inf): consecutive classes share their S1 limit.
const std::vector<RoadClass>& road_classes(ClassSystem system);
// A name of kClassSystemNames in either letter case; throws FieldError(field, ...).
ClassSystem class_system_from_name(const std::string& name, const std::string& field = "class_system");

struct RTableSummary {
  double q0 = 0.0, s1 = 0.0, s2 = 0.0, qd = 0.0;
  double r00 = 0.0;  // r(0, 0) [sr^-1]
  std::size_t defined_cells = 0;
  RoadClass r_class, n_class, c_class;
};
RTableSummary summarize(const RTable& table, Q0Region region = Q0Region::standard);

// ---- comparison -----------------------------------------------------------------------------
struct RTableComparison {
  // Relative differences |a - b| / |b| over the cells defined in both tables with b != 0.
  double max_relative = 0.0;
  double mean_relative = 0.0;
  std::size_t max_row = 0, max_column = 0;  // where the maximum is
  std::size_t compared_cells = 0;
  std::size_t only_in_a = 0, only_in_b = 0;  // cells defined in one table only
  double q0_difference = 0.0;                // Q0(a) - Q0(b) [sr^-1]
  double s1_difference = 0.0;                // S1(a) - S1(b)
};
// `b` is the reference. Throws InputError if no cell is defined in both.
RTableComparison compare(const RTable& a, const RTable& b, Q0Region region = Q0Region::standard);

}  // namespace roadbrdf::photometry
