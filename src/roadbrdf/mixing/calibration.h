// Calibrated intimate mixing: effective cross-section factors per end-member, fitted on a
// set of measured mixtures and then used to predict others (what a lab does with a few mastic
// dosages before predicting a new formulation).
//
// Physics (Hapke 1981, JGR 86:3039, eq. 17; Hapke 2012, "Theory of Reflectance and Emittance
// Spectroscopy", 2nd ed., chapter 10 on mixtures; Mustard & Pieters 1989, JGR 94:13619, the relative
// geometric cross-section of each mineral): the single-scattering albedo of an intimate mixture is the
// cross-section weighted mean of the end-members' albedos,
//   w_mix(lambda) = sum_i c_i w_i(lambda) / sum_i c_i,   c_i = M_i / (rho_i D_i)   (Q_E = 1),
// with M the mass fraction, rho the solid density and D the effective grain diameter (method "hapke",
// mixing.h). The uncalibrated method takes D from the formulation's size classes (for the USGS
// series: one class for every component, so all D_i are equal). What the formulation cannot know is
// the *effective* optical cross-section per unit volume: grain shape, internal fractures, fines
// clinging to coarse grains, a clay that disperses into sub-micron platelets. The calibration
// multiplies each end-member's weight by a factor k_i (k_i ~ D_formulation / D_effective):
//   c_i = k_i M_i / (rho_i D_i).
// Only ratios of the c_i enter w_mix, so one end-member (the reference) has k = 1. The factors are
// fitted by least squares to the measured mixtures:
//   min over ln k  sum_mixtures sum_geometries sum_wavelengths (R_pred - R_meas)^2,  R = pi f
// (reflectance factor; unweighted, so the cost is the reflectance RMS the predictions are judged by),
// R_pred being the library's hapke mixture (MixtureModel kind "hapke", mixture_model.h) with the
// end-members' single-scattering albedos inverted from their white-sky albedos. Solved with Ceres
// (Levenberg-Marquardt, central-difference Jacobian) in u = ln k, started from k = 1, bounded to
// k in [1e-4, 1e4].
//
// Standard errors: from the Jacobian at the optimum, cov(u) = s^2 (J^T J)^-1, s^2 = SSR / (N - p),
// SE(k) = k SE(u). They assume independent residuals; real spectra have residuals that are strongly
// correlated across wavelength (model error, not noise), so these SEs understate the uncertainty: the
// leave-one-out spread of the factors (examples/usgs_mixtures.sh) is the honest measure.
//
// Identifiability: the factors of end-members that never share a mixture, directly or through a
// chain of mixtures, are not determined by the data; calibrate_cross_sections refuses them.
//
// Wavelengths: each mixture is compared at its data's wavelengths inside the common range of its
// end-members' fits (no extrapolation); missing values (NaN) are left out.
#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing {

struct CalibrationMixture {
  std::string name;                       // shown in errors and the report (e.g. the formulation's name)
  const MixInputs* inputs = nullptr;      // formulation and end-members
  const SpectralDataset* data = nullptr;  // measured BRDF of the mixture [sr^-1]
};

struct CrossSectionCalibration {
  std::string reference;                     // end-member with k = 1
  std::vector<std::string> end_members;      // in order of first appearance over the mixtures
  std::vector<std::string> end_member_fits;  // resolved fit paths, same order
  std::vector<double> factors;               // k_i (reference: 1)
  std::vector<double> standard_errors;       // SE(k_i) (reference: 0; NaN when J^T J is singular)
  std::vector<std::string> mixtures;         // names, input order
  std::vector<double> rms_uncalibrated;      // per mixture: reflectance-factor RMS with k = 1
  std::vector<double> rms_calibrated;        // per mixture: with the fitted k
  double rms_uncalibrated_all = std::numeric_limits<double>::quiet_NaN();  // over every residual
  double rms_calibrated_all = std::numeric_limits<double>::quiet_NaN();
  std::size_t residual_count = 0;
  int iterations = 0;
  std::vector<std::string> notes;  // e.g. a factor at its bound
};

// Fit the factors (see the header comment). `reference` names the end-member fixed at k = 1 ("" = the
// first end-member of the first mixture). End-members are matched across mixtures by name (the fit
// file's name, mixing.h); the same name must be the same fit file. Throws FieldError with fields
// "mixtures" (none given, a mixture without data or end-members, the same end-member name for two fit
// files, no wavelength in range, end-members not linked by mixtures, fewer than two end-members) and
// "reference" (not an end-member), InputError from the mixing itself.
CrossSectionCalibration calibrate_cross_sections(const std::vector<CalibrationMixture>& mixtures,
                                                 const std::string& reference = "");

// Reflectance-factor RMS, sqrt(mean (pi f_pred - pi f_meas)^2), of the hapke mixture of `inputs` with
// the factors of `settings` (MixSettings::cross_section_factors) against `data`, under the rules above.
double hapke_reflectance_rms(const MixInputs& inputs, const MixSettings& settings, const SpectralDataset& data);

// The factor MixSettings gives end-member `name`: 1 when the map is empty; InputError when the map is
// not empty and has no entry for it.
double cross_section_factor(const MixSettings& settings, const std::string& name);

// Checks a set of factors (positive, finite, non-empty names). Throws FieldError(field, ...).
void validate_cross_section_factors(const std::map<std::string, double>& factors, const std::string& field);

// ---- Calibration file (JSON, written by `roadbrdf mix-calibrate`) ---------------------------------
// {
//   "format": "roadbrdf-cross-sections", "version": 1, "roadbrdf_version": "0.1.0",
//   "method": "hapke", "reference": "calcite",
//   "end_members": [ {"name": "calcite", "fit": "...", "cross_section_factor": 1, "standard_error": 0}, ...],
//   "mixtures": [ {"name": "GDS310", "formulation": "...", "data": "...",
//                  "rms_uncalibrated": 0.05, "rms_calibrated": 0.01}, ...],
//   "rms_uncalibrated": 0.05, "rms_calibrated": 0.01, "residuals": 20010, "iterations": 7,
//   "notes": ["..."]
// }
// Only "format", "version" and "end_members[].name / cross_section_factor" are needed to use it; the
// rest documents the calibration. Unknown keys are errors.
struct CrossSectionFile {
  CrossSectionCalibration calibration;
  std::vector<std::string> formulations;  // per mixture, as given
  std::vector<std::string> data;          // per mixture, as given
};

// Writes atomically (AtomicFile). Throws FileError.
void write_cross_section_file(const std::string& path, const CrossSectionFile& content);

// The factors of a calibration file, by end-member name. Throws FileError naming the file and the key
// path ("CAL.json: end_members[1].cross_section_factor: must be > 0").
std::map<std::string, double> read_cross_section_factors(const std::string& path);

// ---- Request (front ends: `roadbrdf mix-calibrate`, Python) ----------------------------------------
// The dataset-reading fields (DatasetReadFields: delimiter, decimal, average_duplicates, quantity,
// columns, set) read every measured mixture.
struct CrossSectionRequest : DatasetReadFields {
  // The measured mixtures as pairs of files: each formulation followed by its measured BRDF (CSV).
  std::vector<std::string> mixtures;
  std::string reference;  // "" = first end-member
  std::string output;     // the calibration file; "" = none written

  std::size_t mixture_count() const { return mixtures.size() / 2; }
  const std::string& formulation_file(std::size_t m) const { return mixtures.at(2 * m); }
  const std::string& data_file(std::size_t m) const { return mixtures.at(2 * m + 1); }
  // Checks what needs no file. Throws FieldError ("mixtures", the dataset-reading fields).
  void validate() const;
  // One row per field (core/request_fields.h): `roadbrdf mix-calibrate` and roadbrdf.mix_calibrate.
  static RequestFields<CrossSectionRequest> fields();
};

struct CrossSectionRun {
  CrossSectionFile content;
  // Per mixture: name, uncalibrated and calibrated RMS; then the factors with their SEs.
  std::string table() const;
};

// Validate, check the inputs against `output` (check_distinct_files), read every formulation and
// dataset and calibrate; the calibration file is written to `output` when given. Throws FieldError /
// InputError / FileError.
CrossSectionRun run_cross_section_calibration(const CrossSectionRequest& request);

}  // namespace roadbrdf::mixing
