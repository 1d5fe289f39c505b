// Fit files (JSON) and residual tables written by `roadbrdf fit`.
//
// The fit file (read back as a model by modelfile/fit_file_read.h read_fit_file):
// {
//   "format": "roadbrdf-fit", "version": 1 (2 when grouped: "group_by" [columns] at the top level,
//   and each fit has "group" {column: deg}),
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

#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/modelfile/fit_file_read.h"  // the reader of this format
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// The SpectralModel of a fit held in memory, the same as read_fit_file gives for it from the file:
// parameters per wavelength, the data's angular coverage and the parameter covariance per wavelength
// (cov_ab = r_ab s_a s_b; 0 for a fixed parameter, NaN where undefined), so that albedo and r-table
// uncertainties of a Python FitResult equal those of its fit file. `model` is the fitted model
// (FitResult holds its name and options only).
SpectralModel spectral_model_of(const FitResult& fit, std::shared_ptr<const Model> model);

nlohmann::json fit_to_json(const FitResult& fit);

// Index of the fit with the lowest total BIC (ties: the first). Throws InputError if empty.
std::size_t best_fit_index(const std::vector<FitResult>& fits);

// The fit file's content (what write_fit_file writes). `notes` (FitSummary::notes: wavelengths answered by
// the nearest band, band means) are kept in the file's "notes" so a fit at 600 nm made of the 590-610 nm mean
// says so wherever the file goes.
nlohmann::json fit_file_json(const std::vector<FitResult>& fits, const std::vector<std::string>& notes = {});

// Write the fit file atomically.
void write_fit_file(const std::string& path, const std::vector<FitResult>& fits,
                    const std::vector<std::string>& notes = {});

// Residual table (long CSV): theta_i,phi_i,theta_r,phi_r [deg],wavelength [nm],model,[group,]measured,fitted,
// residual [sr^-1], for the geometries each fit used: those of `where` (io/geometry_selection.h) in its group.
void write_residuals(std::ostream& out, const SpectralDataset& data, const std::vector<const Model*>& models,
                     const std::vector<FitResult>& fits, const std::string& where = "");

}  // namespace roadbrdf
