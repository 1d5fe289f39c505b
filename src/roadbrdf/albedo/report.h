// Everything `roadbrdf albedo` computes for one model or fit, as one JSON document: black-sky
// (per sun zenith), white-sky and blue-sky albedo per wavelength with error estimates, diffuse
// fractions, broadband (solar-weighted) and luminous values. Used by the command line and the
// Python module alike (report eqs. 2.19-2.22; keys documented in docs/albedo.md and under "units").
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::albedo {

struct AlbedoRequest {
  // The BRDF (modelfile/model_source.h resolve_model): a fit file, a MIX.json or a model name with
  // NAME=VALUE `parameters` and `options`; `fit` selects an entry of a file. Empty when the caller
  // passes the spectral model itself (compute_albedo).
  std::string model;
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::string fit;
  std::vector<double> sun_zenith_deg = {30.0};  // each in [0, 90)
  std::optional<double> sun_azimuth_deg;        // anisotropic models (default 0)
  bool azimuth_mean = false;                    // anisotropic models: average black-sky over the sun azimuth
  // Diffuse fraction D for blue-sky: "" (none), a number in [0, 1], or a CSV wavelength_nm,diffuse_fraction.
  std::string diffuse_fraction;
  // "" or "spectrl2[:aod=...,water=...,...]" (D(lambda) and broadband weights from SPECTRL2).
  std::string atmosphere;
  // Broadband weighting: "" (ASTM G173 global, or SPECTRL2 with an atmosphere), "astm-g173-global",
  // "astm-g173-direct" or a CSV file wavelength_nm,irradiance.
  std::string spectrum;
  std::vector<double> wavelengths;  // [nm] of a fit file; empty: its own
  std::string illuminant;           // "" or A, D65, a file: also the luminous (V(lambda)-weighted) albedo
  double tolerance = 1e-5;          // absolute quadrature tolerance per value (and per standard uncertainty)
  // Standard uncertainties from a fit's parameter covariance (albedo/uncertainty.h); false: values only.
  bool uncertainty = true;
  // Threads for the integrals (one task per sun zenith and for the white-sky one, and the white-sky
  // outer nodes); 0: all cores. The results do not depend on it.
  int threads = 0;
  // Integrals done: one black-sky integral per sun zenith (all wavelengths at once), then the
  // white-sky one.
  ProgressCallback progress;

  // One row per field (core/request_fields.h): the command line's options, Python's keywords.
  static std::span<const RequestField<AlbedoRequest>> fields();
  // Throws FieldError naming the request's field (tolerance, sun_zenith, diffuse_fraction,
  // atmosphere) for a request that is invalid whatever the model; compute_albedo calls it.
  void validate() const;
};

// What albedo() returns: the document of compute_albedo (keys in docs/albedo.md; its "warnings" are
// `diagnostics.warnings`), and its summary, the table of albedo_table.
struct AlbedoResult {
  nlohmann::json report;
  Diagnostics diagnostics;

  const nlohmann::json& to_json() const { return report; }
  std::string summary_text() const;
};

// The request's task: resolves `model` (resolve_model), then compute_albedo. Throws FieldError
// (`model` when none is given), FileError, InputError.
AlbedoResult albedo(const AlbedoRequest& request);

// The hemispherical integrals compute_albedo starts from, for n_sets parameter sets of a model at once:
// black-sky at sun zenith theta_s [rad] (at sun azimuth phi_s [rad], or averaged over it) and white-sky.
// The default is the adaptive quadrature of hemisphere.h. A caller that knows the integrals another way
// supplies its own: a mixture linear in its end-members' BRDFs has the same linear combination of their
// integrals (mixing/end_member_cache.h); every later stage (sky, broadband, luminous) is the same.
class HemisphericalIntegrals {
 public:
  virtual ~HemisphericalIntegrals() = default;
  virtual SpectralIntegral black_sky(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                     double phi_s, bool azimuth_mean, const QuadratureSettings& settings) const;
  virtual SpectralIntegral white_sky(const Model& model, const double* params, std::size_t n_sets,
                                     const QuadratureSettings& settings) const;
};

// The albedos of `model` (the request's model source fields are not used). The document carries
// "notes" (text) and "warnings" ({"kind", "message"}: "not_converged", "partial_solar_spectrum",
// "mostly_extrapolated", "negative_brdf", "albedo_above_one", "implausibly_dark").
// Throws FieldError for a request that is invalid (validate(), and what depends on the model:
// wavelengths of a model without any, a diffuse-fraction table for it), InputError or FileError for
// unreadable spectra.
nlohmann::json compute_albedo(const SpectralModel& model, const AlbedoRequest& request);
// The same with the hemispherical integrals from `integrals` (the uncertainty stage, which needs
// derivatives of the integrals, keeps the quadrature of hemisphere.h).
nlohmann::json compute_albedo(const SpectralModel& model, const AlbedoRequest& request,
                              const HemisphericalIntegrals& integrals);

// The CSV table `roadbrdf albedo` prints without --json (per wavelength, then broadband lines).
std::string albedo_table(const nlohmann::json& report);

// Writes a report as `roadbrdf albedo` does: the JSON document (indent 2) or the table, to `path`
// atomically ("-": standard output). The one writer of the command line and of Python.
void write_albedo_report(const nlohmann::json& report, const std::string& path, bool as_json);

}  // namespace roadbrdf::albedo
