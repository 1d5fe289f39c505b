// How much of an albedo lies outside the directions a fit was fitted to, and non-physical albedo
// values.
//
// The fraction outside the coverage (core/coverage.h) of a directional albedo at sun zenith
// theta_s is  int_{w_r not covered} |f| cos(theta_r) dw_r / int |f| cos(theta_r) dw_r , and of the
// white-sky albedo the same over (w_i, w_r) with the weight cos(theta_i) dw_i: the share of the
// integral the model supplies where nothing was measured. Both on a midpoint grid (2 deg in
// zenith, 5 deg in azimuth, incidence azimuth 0: isotropic surfaces), at one parameter set.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadbrdf/core/coverage.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::albedo {

struct OutsideFraction {
  double fraction = 0.0;             // of the integral outside the coverage, in [0, 1]
  std::size_t negative_samples = 0;  // grid points where the BRDF is negative
  std::size_t samples = 0;
};

OutsideFraction black_sky_outside(const Model& model, const double* params, double theta_s_rad,
                                  const AngularCoverage& coverage);
OutsideFraction white_sky_outside(const Model& model, const double* params, const AngularCoverage& coverage);

// The "coverage" object of the albedo report: the fit's coverage, the fractions outside it per sun
// zenith and for white-sky at `wavelength_nm` (parameter set `params`), a note on the coverage, and
// warnings when a result is mostly, > 50 %, extrapolation ("mostly_extrapolated") or the BRDF is
// negative somewhere ("negative_brdf").
nlohmann::json albedo_coverage(const Model& model, const double* params, double wavelength_nm,
                               const std::vector<double>& sun_zenith_deg, const AngularCoverage& coverage,
                               std::vector<std::string>& notes, Diagnostics& diagnostics);

// White-sky albedos below this are warned about: darker than any natural material (docs/data.md,
// "Implausible values"; physical range taken as 0.005-1).
inline constexpr double kImplausibleAlbedo = 0.005;

// Warnings on non-physical values: a directional (black-sky) or white-sky albedo above 1
// ("albedo_above_one"); and on implausible ones: a white-sky albedo below kImplausibleAlbedo
// ("implausibly_dark").
void flag_non_physical(const std::vector<double>& sun_zenith_deg, const std::vector<double>& wavelengths,
                       const std::vector<std::vector<double>>& black_sky, const std::vector<double>& white_sky,
                       Diagnostics& diagnostics);

nlohmann::json coverage_json(const AngularCoverage& coverage);

}  // namespace roadbrdf::albedo
