// Gonioreflectometer calibration against a reference panel (report section 5.2):
//   f(geometry, lambda) = (L_sample - L_dark) / (L_ref - L_dark) * rho_ref(lambda) / pi
// optionally with the panel's measured reflectance factor instead of the Lambertian rho_ref:
//   f = (L_sample - L_dark) / (L_ref - L_dark) * BRF_panel(lambda) / pi
// (the correction factor BRF_panel / rho_ref is recorded in the metadata).
// rho_ref (and BRF_panel) are interpolated onto the sample wavelengths as their spectra say (files:
// linearly, extrapolation refused beyond rounding; spectra/spectrum_file.h).
// First-order uncertainty propagation with independent inputs, written with c = rho/pi, N = L_s - L_d,
// D = L_ref - L_d:  df/dL_s = c/D,  df/dL_ref = -c N/D^2,  df/dL_d = c (N - D)/D^2,  df/drho = N/(pi D).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/io/dataset.h"
#include "roadbrdf/spectra/spectrum.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf {

// A panel's reflectance (or BRF) file is a spectrum file (spectra::read_spectrum with its default
// options): "wavelength value [sigma]" lines, or values alone on a stated grid. It must be a regular
// file of at most kPanelFileMaxBytes (a calibrated panel's table holds a few thousand lines).
inline constexpr std::uintmax_t kPanelFileMaxBytes = std::uintmax_t{64} << 20;
spectra::SpectrumReadOptions panel_read_options();
// The panel reflectance rho_ref (CalibrationInput::panel_reflectance) read with panel_read_options().
spectra::Spectrum read_panel_reflectance(const std::string& path);

// The optional measured BRF of the reference panel (CalibrationInput::panel_brf) as the front ends
// give it: a file (`path`, "" = none) and, for a one-column file (e.g. BRF_i10_e0.txt), its first
// wavelength and step [nm]. A first wavelength or step without a file is
// FieldError("panel_brf_start" / "panel_brf_step").
std::optional<spectra::Spectrum> read_panel_brf(const std::string& path, std::optional<double> first_wavelength,
                                                std::optional<double> step);

struct CalibrationInput {
  SpectralDataset sample;               // sample radiances (any unit), N geometries
  SpectralDataset reference;            // reference-panel radiances: same geometries, or a single row used for all
  std::optional<SpectralDataset> dark;  // dark signal: same geometries, or a single row; none = 0
  spectra::Spectrum panel_reflectance;  // rho_ref(lambda), dimensionless (e.g. Spectralon 8deg/h calibration)
  std::optional<spectra::Spectrum> panel_brf;  // optional measured BRF of the panel at the measurement geometry
};

// The calibrated BRDF [sr^-1] with propagated uncertainties. Throws InputError (mismatched
// wavelengths or geometries, reference not above dark, extrapolation).
SpectralDataset calibrate(const CalibrationInput& input);

}  // namespace roadbrdf
