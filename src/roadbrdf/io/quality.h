// Quality report of a spectral BRDF dataset (`roadbrdf check`).
//
// - Angular coverage: incidence zenith angles, viewing zenith angles (and road observation angles
//   alpha = 90 - theta_r), azimuth planes (beta = 180 - |dphi| folded to [0, 180]), forward
//   (cos dphi < 0) / backward (cos dphi > 0) / in-plane counts.
// - Negative and missing (NaN) values.
// - Reciprocity: pairs (a, b) with theta_i(a) = theta_r(b), theta_r(a) = theta_i(b) and the same
//   |dphi| (isotropic matching, default) or with w_i(a) = w_r(b), w_r(a) = w_i(b) (exact), within
//   `angle_tolerance_deg`; disagreement = |sum_j (f_a - f_b)| / sum_j (|f_a| + |f_b|)/2 (spectrally
//   integrated, so that random noise averages out), plus the largest per-wavelength value.
// - Noisy spectral bands: the noise of each spectrum is estimated from its roughness along
//   wavelength, r_j = f_j - (linear interpolation of f_(j-1), f_(j+1) at lambda_j); for white noise
//   of standard deviation s and equal steps, var(r_j) = 1.5 s^2. Per wavelength,
//   noise_j = 1.4826 * median_(geometries, +-window) |r| / sqrt(1.5) (robust), signal_j = median over
//   geometries of |f_j|, and wavelengths with signal/noise < `snr_threshold` are flagged; adjacent
//   flagged wavelengths form bands.
// - Outlier geometries: the log spectral mean of each geometry is predicted from its `neighbours`
//   nearest geometries in the isotropic angular coordinates (theta_i, theta_r cos dphi,
//   theta_r |sin dphi|) [deg] by a local least-squares fit (quadratic without cross terms with
//   >= 12 neighbours, linear with >= 5, else their median);
//   residual = log(f / prediction), score = |residual - median| / (1.4826 MAD, floored at 0.02), the
//   median and MAD of the residuals of the same neighbours (local in angle and scale-aware: where the
//   data are noisier, e.g. a ramp falling into the noise towards grazing angles, so is the spread; all
//   residuals with fewer than 5 neighbours); flagged when score > `outlier_threshold` and the ratio
//   exceeds `outlier_min_ratio`. Sharp physical peaks: a bright geometry within `specular_cone_deg`
//   (the specular window, an angle from the mirror direction) is listed as a specular peak instead,
//   and such geometries do not enter the other predictions. The text lists the first
//   `listed_outliers`, the JSON all. The residual is the smaller of two local fits' (quality_outliers.cpp):
//   the quadratic, and one linear in the offsets and in ln cos theta_i, ln cos theta_r (Minnaert's
//   law), which follows a BRDF steepening towards grazing where a quadratic fitted over neighbours on
//   one side falls short (a dense theta_i series 0-89 deg is not flagged at its grazing end).
// - Reference panel: with a panel reflectance rho(lambda), every value against rho/pi.
// - Plausibility of the scale (quality_plausibility.cpp): the Lambertian-equivalent albedo pi x median
//   BRDF per wavelength against [0.005, 1] (natural materials); values that look like BRDF x cos theta_i
//   (reciprocity pairs that disagree by the ratio of their incidence cosines and agree once divided
//   by cos theta_i); the repeatability of averaged duplicate rows (io/dataset_io.h, Repeatability).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/spectra/spectrum.h"

namespace roadbrdf {

struct QualityOptions {
  double angle_tolerance_deg = 0.5;
  bool exact_reciprocity = false;       // match directions, not (theta_i, theta_r, |dphi|)
  double reciprocity_threshold = 0.10;  // relative disagreement above which a pair is flagged
  double snr_threshold = 20.0;
  int noise_window = 2;  // +- wavelengths pooled in the noise estimate
  int neighbours = 16;
  double outlier_threshold = 6.0;
  double outlier_min_ratio = 1.6;
  double neighbour_max_distance_deg = 40.0;
  // The specular window: geometries whose w_r is within this angle [deg] of the mirror direction of
  // w_i. A bright value there is reported as a specular peak, not an outlier, and they are not used to
  // predict the others. (At theta_i = 89 deg, theta_r = 64 deg in the forward plane is 25 deg away.)
  double specular_cone_deg = 10.0;
  // The summary text lists this many outliers (all of them in the JSON report).
  int listed_outliers = 5;
  std::optional<spectra::Spectrum> panel_reflectance;  // validate a reference panel measured as a sample

  // Throws FieldError naming the request field of io/check_request.h (`tolerance`, `neighbours`, ...).
  void validate() const;
};

struct ReciprocityPair {
  std::size_t a = 0, b = 0;       // geometry indices
  double disagreement = 0.0;      // spectrally integrated relative difference
  double max_disagreement = 0.0;  // largest per-wavelength relative difference
  bool flagged = false;
};

struct OutlierGeometry {
  std::size_t index = 0;
  double ratio = 1.0;  // spectral mean / median of the neighbours' spectral means
  double score = 0.0;
  double from_mirror_deg = 0.0;  // angle between w_r and the mirror direction of w_i
};

// Lambertian-equivalent albedo pi x median over the geometries of the BRDF, per wavelength, against the
// range of natural materials [kPlausibleAlbedoMin, kPlausibleAlbedoMax].
inline constexpr double kPlausibleAlbedoMin = 0.005;
inline constexpr double kPlausibleAlbedoMax = 1.0;
struct ScalePlausibility {
  std::vector<double> equivalent_albedo;  // per wavelength (NaN without a measured value)
  std::size_t below = 0, above = 0;       // wavelengths outside the range
};

// Whether the values look like BRDF x cos theta_i: over the reciprocity pairs whose incidence cosines
// differ (by more than 5 %), the mean disagreement of the values as stored and divided by cos theta_i.
struct CosineFactorTest {
  std::size_t pairs = 0;
  double disagreement = 0.0;          // as stored
  double divided_disagreement = 0.0;  // after dividing every value by cos theta_i
  bool likely = false;                // clearly non-reciprocal as stored, reciprocal once divided
};

struct NoisyBand {
  double lower_nm = 0.0, upper_nm = 0.0;
  double min_snr = 0.0;
};

struct PanelValidation {
  std::vector<double> mean_relative_deviation;  // per geometry: mean over wavelengths of (f - rho/pi)/(rho/pi)
  std::vector<double> max_abs_relative_deviation;
  double overall_mean = 0.0;
  double overall_max_abs = 0.0;
};

struct QualityReport {
  std::size_t geometry_count = 0, wavelength_count = 0;
  double wavelength_min = 0.0, wavelength_max = 0.0;
  std::vector<double> incidence_angles_deg;  // distinct theta_i (0.01 deg)
  std::vector<double> viewing_angles_deg;    // distinct theta_r
  std::vector<double> azimuth_planes_deg;    // distinct beta = 180 - |dphi| in [0, 180]
  std::size_t forward = 0, backward = 0, perpendicular = 0, normal_or_grazing = 0, in_plane = 0;
  std::size_t negative_values = 0, missing_values = 0;
  std::vector<ReciprocityPair> reciprocity;
  std::size_t reciprocity_flagged = 0;
  std::vector<double> snr;  // per wavelength
  std::vector<NoisyBand> noisy_bands;
  std::vector<OutlierGeometry> outliers;
  std::vector<OutlierGeometry> specular_peaks;  // bright near-specular geometries (not outliers)
  std::optional<PanelValidation> panel;
  ScalePlausibility scale;
  CosineFactorTest cosine_factor;
  Repeatability repeatability;        // of the averaged duplicates (from the reading statistics)
  std::vector<std::string> warnings;  // implausible scale, BRDF x cos theta_i: one line each
  std::size_t listed_outliers = 5;    // from the options: outliers listed in the text
  double specular_window_deg = 10.0;  // from the options
};

QualityReport check_dataset(const SpectralDataset& dataset, const QualityOptions& options = {});
// The same with the statistics of reading the file (the repeatability of averaged duplicates).
QualityReport check_dataset(const SpectralDataset& dataset, const QualityOptions& options,
                            const DatasetReadStats& stats);

// The median of `values` (reordered in place; NaN when empty), shared by the checks (quality.cpp).
double median_of(std::vector<double>& values);

// The outlier check (quality_outliers.cpp): fills outliers and specular_peaks.
void check_outliers(const SpectralDataset& dataset, const QualityOptions& options, QualityReport& report);

// The plausibility checks (quality_plausibility.cpp), their JSON ("plausibility", "repeatability")
// and their lines of the text report.
void check_plausibility(const SpectralDataset& dataset, QualityReport& report);
void plausibility_json(const SpectralDataset& dataset, const QualityReport& report, nlohmann::json& j);
std::string plausibility_text(const SpectralDataset& dataset, const QualityReport& report);

nlohmann::json quality_report_json(const SpectralDataset& dataset, const QualityReport& report);
std::string quality_report_text(const SpectralDataset& dataset, const QualityReport& report);

}  // namespace roadbrdf
