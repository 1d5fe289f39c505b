// A fit as the front ends ask for it (`roadbrdf fit`, roadbrdf.fit in Python): the request with its
// one validation, the distribution of names over the models, and the result with its summary.
// The command line and the Python module only translate their arguments into a FitRequest.
//
// Names given once for all models (options, fixed, start, bounds, shared) apply to every model
// that declares them; a composite accepts a plain option name for each component that has it
// ("distribution" sets torrance-sparrow.distribution in lambert+torrance-sparrow) as well as
// "component.option". A name no model of the request declares is an error naming the field
// (`options.distributon: no model to fit has this option (did you mean 'distribution'?)`), as is a
// value a model does not accept. `shared` may hold "auto": every non-spectral parameter that is
// not fixed is shared by all wavelengths (joint mode).
//
// Errors are FieldError with the field names of FitRequest ("multistart", "fixed.roughness",
// "options.distribution", ...); the front ends spell them from the request's table (fields():
// the command line's flags and Python's keyword arguments, core/request_fields.h).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf {

// The dataset-reading fields (DatasetReadFields: delimiter, decimal, average_duplicates, quantity,
// columns, set) read `data`.
struct FitRequest : DatasetReadFields {
  // The measured dataset's file. Python may give the dataset itself instead (its values).
  std::string data;
  std::vector<std::string> models;                          // model names, e.g. "oren-nayar"
  OptionSet options;                                        // NAME or component.NAME -> value
  std::map<std::string, double> fixed;                      // held at a value at every wavelength
  std::map<std::string, double> start;                      // starting values
  std::map<std::string, std::pair<double, double>> bounds;  // narrower [lower, upper]
  std::vector<std::string> shared;                          // names, or "auto"
  // Subset of the dataset's [nm]; empty: all. One not on the grid is answered by the nearest band,
  // with a note in FitSummary::notes (select_wavelengths).
  std::vector<double> wavelengths;
  // Or bands [lower, upper] nm (not with `wavelengths`): each band's spectrum is the mean over the band
  // of the piecewise-linear measured spectrum (resample_dataset, io/resample.h; sigma propagated),
  // fitted and reported at the band's centre, with a note naming the measured bands it averages.
  std::vector<std::pair<double, double>> bands;
  // Geometries (io/geometry_selection.h): `where` selects ("theta_r<=70"), `group_by` fits each
  // group of equal angles separately ({"theta_i"}: one fit per incidence angle).
  std::string where;
  std::vector<std::string> group_by;
  std::string loss = "plain";   // a name of kFitLossNames (fitting/fit.h)
  std::string robust = "none";  // "none" or NAME:SCALE, NAME of kRobustLossNames (fitting/fit.h)
  bool use_sigma = true;
  // The measurement sigma from the dataset's duplicate rows (their repeatability) instead of a sigma
  // column: the duplicates are averaged, and each value's sigma is s_rel(lambda) |y| / sqrt(n), s_rel
  // the pooled relative standard deviation of one measurement at that wavelength
  // (Repeatability::pooled_relative_sd, io/dataset_io.h) and n the rows averaged into the value
  // (apply_duplicate_sigma). Needs the dataset's file (`data`); refused when the data carry sigma or
  // have no duplicates.
  bool sigma_from_duplicates = false;
  bool solid_angle_weights = false;
  int multistart = 1;
  int seed = 1;  // 0 or more
  int threads = 1;
  int max_iterations = 200;
  bool covariance = true;
  bool warm_start = true;
  bool solve_amplitudes = true;
  std::string joint_solver = "dense-schur";
  // Files written: the fit file (fitting/fit_file.h) and the residuals per geometry and wavelength
  // (write_fit_outputs); empty: not written.
  std::string output;
  std::string residuals;

  // The table of the fields: the command line's options and Python's keyword arguments.
  static RequestFields<FitRequest> fields();

  // Checks everything that does not need the dataset: model names and options, parameter names
  // and values, settings. Throws FieldError.
  void validate() const;
};

// One model of a request with the options that apply to it.
struct PlannedFit {
  std::shared_ptr<const Model> model;
  FitOptions options;
};
// The request validated and distributed over its models (no fitting). Throws FieldError.
std::vector<PlannedFit> plan_fits(const FitRequest& request);

struct FitSummary {
  // Without groups: one fit per model, in the request's order. With groups: for each group (in
  // group order), one fit per model; FitResult::group names the group.
  std::vector<std::shared_ptr<const Model>> models;  // aligned with fits
  std::vector<FitResult> fits;
  std::vector<std::size_t> ranking;    // indices into fits: by group, then lowest total BIC first
  std::size_t geometry_count = 0;      // geometries fitted (after `where`)
  std::size_t dataset_geometries = 0;  // geometries of the dataset
  std::string where;                   // as requested
  std::vector<std::string> notes;      // wavelengths answered by the nearest band (select_wavelengths)
  std::vector<std::string> group_by;   // as requested
  std::size_t group_count = 1;
  std::vector<double> wavelengths;  // fitted [nm]
  std::string loss, robust;         // as requested
  bool sigma_weights = false;       // 1/sigma^2 weights were used
  std::size_t missing_values = 0;   // missing (NaN) values, masked out at their wavelength

  // The best fit (of the first group when grouped).
  const FitResult& best() const { return fits.at(ranking.at(0)); }
  // The ranking table `roadbrdf fit` prints (models, k, RMSE, AIC, BIC, convergence...).
  std::string table() const;
  // Non-converged wavelengths, parameters on bounds, missing standard errors: one line each,
  // `where` naming the result (e.g. the output file).
  std::vector<std::string> warnings(const std::string& where) const;
};

// Called with a label ("fit MODEL (i/n)") for each model; returns the progress callback of that fit
// (or an empty function).
using FitProgress = std::function<std::function<void(std::size_t, std::size_t)>(const std::string& label)>;

// The spectra a request fits: the dataset, its selected wavelengths, or its band means (`bands`), with
// the notes on nearest bands and band means, and without the geometries that have a grazing direction
// (grazing_geometries: no irradiance or nothing in view), named in a note. run_fit and the residuals
// file both use it. Throws FieldError ("wavelengths", "bands"), InputError when every geometry is grazing.
SpectralDataset fitted_spectra(const FitRequest& request, const SpectralDataset& data,
                               std::vector<std::string>* notes = nullptr);
// The indices of the geometries with theta_i or theta_r = 90 deg (Geometry::grazing_i, grazing_r).
std::vector<std::size_t> grazing_geometries(const SpectralDataset& data);

// Whether the model `richer` ("a+b" for a composite) contains `simpler` (a different model): each
// component of `simpler` is a distinct component of `richer` or one it reduces to
// (ModelDescription::reduces_to). "oren-nayar+torrance-sparrow" contains "oren-nayar" and "lambert".
bool model_contains(const std::string& richer, const std::string& simpler);
// Sets FitResult::worse_than_nested of fits[first...] (one group of a request) from their total RMSE.
void flag_worse_than_nested(std::vector<FitResult>& fits, std::size_t first);

// Validate, select the wavelengths, and fit every model. Throws FieldError / InputError.
FitSummary run_fit(const FitRequest& request, const SpectralDataset& data, const FitProgress& progress = {});

// The request's dataset file read with its reading fields (FieldError `data` when none is named);
// with `sigma_from_duplicates`, its duplicates averaged and its sigma from their repeatability.
SpectralDataset read_fit_data(const FitRequest& request);
// Sets the sigma of `data` (read from `file` with duplicates averaged) from the repeatability of its
// duplicate rows: sigma = s_rel(lambda) |y| / sqrt(n) (FitRequest::sigma_from_duplicates), recorded in
// metadata `sigma_from_duplicates`. FieldError `sigma_from_duplicates` when the data carry sigma, have no
// duplicated geometry, a wavelength without a duplicated measured cell, or a value 0 (whose relative
// sigma would be 0).
void apply_duplicate_sigma(SpectralDataset& data, const Repeatability& repeatability, const std::string& file);
// Writes the request's `output` (the fit file) and `residuals` (measured, fitted and residual value
// per geometry and wavelength) of `summary`, fitted to `data`; a field left empty is not written.
// The front ends check the files first (check_request_files, before fitting).
void write_fit_outputs(const FitRequest& request, const FitSummary& summary, const SpectralDataset& data);

}  // namespace roadbrdf
