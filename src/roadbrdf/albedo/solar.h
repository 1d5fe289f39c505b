// Solar spectra for broadband (solar-weighted) albedo: ASTM G173-03 reference spectra, a user's
// spectrum file, and the SPECTRL2 clear-sky spectral model (Bird & Riordan 1986), plus the
// spectral weighting  alpha = int E(l) alpha(l) dl / int E(l) dl  over the BRDF's wavelength range.
// Units: wavelengths in nm, spectral irradiance in W m^-2 nm^-1.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/spectra/spectrum.h"

namespace roadbrdf::albedo {

// A solar spectrum is a spectra::Spectrum of spectral irradiance [W m^-2 nm^-1] (or any unit: only
// ratios matter for weighting), linearly interpolated, with no value outside its range.

// ASTM G173-03 (data/third-party/solar/astm-g173-03.csv): "global" (hemispherical on a 37 deg
// sun-facing tilt), "direct" (direct normal + circumsolar) or "extraterrestrial", 280-4000 nm.
spectra::Spectrum astm_g173(const std::string& which);

// A user's spectrum (spectra/spectrum_file.h) with two columns, wavelength [nm] and spectral
// irradiance [W m^-2 nm^-1]: at least two rows, irradiance >= 0 with a finite, positive integral.
// Throws FileError with line and column.
spectra::Spectrum read_solar_spectrum(const std::string& path);

// "astm-g173-global", "astm-g173-direct" or a file path.
spectra::Spectrum solar_spectrum_from_name(const std::string& name_or_file);

// Trapezoid integral of E over its own grid [W m^-2] (spectra::trapezoid_integral).
double integrate_spectrum(const spectra::Spectrum& e);

// ---- SPECTRL2 -------------------------------------------------------------------------------
// Bird & Riordan (1986), "Simple solar spectral model for direct and diffuse irradiance on horizontal
// and tilted planes at the earth's surface for cloudless atmospheres", J. Clim. Appl. Meteorol. 25,
// 87-97 (SERI/TR-215-2436), as implemented in NREL's spectrl2_2.c: Rayleigh 1.3366 (eq. 2-4), mixed
// gases 118.3 (eq. 2-11), Tu' in eq. 3-8, Cs applied once to the sum of eq. 3-1, Kasten & Young
// (1989) air mass, primed (air mass 1.8) transmittances without a pressure correction, and the
// Spencer (1971) Earth-Sun distance factor. Horizontal surface.
struct Spectrl2Input {
  double zenith_deg = 30.0;        // apparent solar zenith [deg], < 90
  double relative_airmass = -1.0;  // < 0: Kasten & Young (1989) from the zenith angle
  double pressure_pa = 101325.0;   // surface pressure [Pa]
  double water_cm = 1.42;          // precipitable water [cm]
  double ozone_atm_cm = 0.344;     // ozone column [atm-cm]
  double aod500 = 0.1;             // aerosol optical depth at 500 nm (base e)
  double alpha = 1.14;             // Angstrom exponent (rural aerosol)
  double asymmetry = 0.65;         // aerosol asymmetry factor
  double omega400 = 0.945;         // single-scattering albedo at 400 nm
  double omega_prime = 0.095;      // wavelength variation factor of the single-scattering albedo
  double ground_albedo = 0.2;      // ground reflectance for the ground-sky multiple reflection
  int day_of_year = 81;            // 1-366
};

struct Spectrl2Output {
  std::vector<double> wavelengths;       // nm (122 values, 300-4000 nm)
  std::vector<double> extraterrestrial;  // W m^-2 nm^-1, corrected for the Earth-Sun distance
  std::vector<double> direct_normal;     // W m^-2 nm^-1
  std::vector<double> diffuse;           // diffuse horizontal, W m^-2 nm^-1
  std::vector<double> global;            // global horizontal = direct_normal cos Z + diffuse
  double cos_zenith = 1.0;
};

// Throws InputError for inputs outside their physical ranges.
Spectrl2Output spectrl2(const Spectrl2Input& input);

// Kasten & Young (1989) relative optical air mass for an apparent zenith angle [deg].
double kasten_young_airmass(double zenith_deg);

// Parse "spectrl2[:aod=...,water=...,ozone=...,pressure=...,alpha=...,ground=...,day=...]" (pressure
// in Pa); the zenith is set separately. Throws FieldError("atmosphere").
Spectrl2Input parse_spectrl2_spec(const std::string& spec);

// ---- Spectral weighting ---------------------------------------------------------------------
struct WeightedValue {
  double value = 0.0;             // int_{lo}^{hi} E a dl / int_{lo}^{hi} E dl
  double error = 0.0;             // same weighting of the per-wavelength error estimates
  double fraction_outside = 0.0;  // 1 - int_{lo}^{hi} E dl / int E dl (solar energy outside the BRDF's range)
  // The mean is linear in the tabulated values: value = sum_k first[k] a1[k] + second[k] a2[k]
  // (second empty with one weight). Used to propagate per-wavelength uncertainties.
  std::vector<double> first, second;
};

// Weighted mean of a(l) (tabulated on `wavelengths`, strictly increasing, >= 2 values) with the
// weight E(l), on the union of both grids inside [wavelengths.front(), wavelengths.back()], both
// linearly interpolated (trapezoid). `errors` may be empty. Throws InputError if the ranges do not
// overlap or the weight integrates to 0 there.
WeightedValue spectral_weighted_mean(const std::vector<double>& wavelengths, const std::vector<double>& values,
                                     const std::vector<double>& errors, const spectra::Spectrum& weight);

// Same with two weights (blue-sky with SPECTRL2: direct horizontal on the black-sky values, diffuse
// on the white-sky values):  int (E1 a1 + E2 a2) / int (E1 + E2).
WeightedValue spectral_weighted_mean2(const std::vector<double>& wavelengths, const std::vector<double>& values1,
                                      const std::vector<double>& errors1, const spectra::Spectrum& weight1,
                                      const std::vector<double>& values2, const std::vector<double>& errors2,
                                      const spectra::Spectrum& weight2);

}  // namespace roadbrdf::albedo
