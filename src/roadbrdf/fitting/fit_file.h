// Fit files (JSON) and residual tables written by `roadbrdf fit`.
//
// The fit file (read back as a model by read_fit_file):
// {
//   "format": "roadbrdf-fit", "version": 1,
//   "best": model name with the lowest total BIC, "best_criterion": "bic_total",
//   "units": { key: unit/description, ... },
//   "fits": [ {
//     "model", "options" {name: value}, "wavelengths" [nm],
//     "parameters" {name: [per wavelength]}, "stderr" {name: [per wavelength, null = undefined]},
//     "parameter_units" {name: unit}, "fixed" [names], "shared" [names], "mode": "per-wavelength" | "joint",
//     "loss", "robust", "robust_scale", "sigma_weights", "solid_angle_weights", "multistart", "seed",
//     "bounds" {name: [lower, upper]} (only when narrower bounds were asked for),
//     "correlation" [per wavelength: p x p nested lists, null = undefined],
//     "rmse", "relative_rmse", "max_relative_error", "r_squared", "chi2", "aic", "bic", "cost",
//     "iterations", "converged", "status", "covariance_ok", "covariance_message", "at_bounds",
//     "points", "free_parameters", "start_index"   (all per wavelength),
//     "rmse_total", "relative_rmse_total", "max_relative_error_total", "chi2_total", "aic_total",
//     "bic_total", "points_total" (measured values fitted), "missing_values" (NaN values masked out),
//     "free_parameters_total", "converged_count", "wavelength_count",
//     "at_bound_count", "covariance_failures", "stayed_at_start_count" (converged wavelengths whose
//     nonlinear parameters never left their start),
//     "coverage" {"theta_i_deg": [min, max], "theta_r_deg": [min, max], "azimuth_planes_deg": [...],
//                 "geometries": N} (core/coverage.h: the measured directions; optional when read),
//     "seconds" } ]
// }
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// A fit file as a spectral model: the fit named `model_name` (default: the file's "best").
// Throws FileError / InputError.
SpectralModel read_fit_file(const std::string& path, const std::string& model_name = "");

// True if `argument` names a fit file rather than a model (ends in ".json").
bool is_fit_file_argument(const std::string& argument);

nlohmann::json fit_to_json(const FitResult& fit);

// Index of the fit with the lowest total BIC (ties: the first). Throws InputError if empty.
std::size_t best_fit_index(const std::vector<FitResult>& fits);

// The fit file's content (what write_fit_file writes).
nlohmann::json fit_file_json(const std::vector<FitResult>& fits);

// Write the fit file atomically.
void write_fit_file(const std::string& path, const std::vector<FitResult>& fits);

// Residual table (long CSV): theta_i,phi_i,theta_r,phi_r [deg],wavelength [nm],model,measured,fitted,residual [sr^-1].
void write_residuals(std::ostream& out, const SpectralDataset& data, const std::vector<const Model*>& models,
                     const std::vector<FitResult>& fits);

}  // namespace roadbrdf
