// The field table of FitRequest (core/request_fields.h): `roadbrdf fit`'s options and the keyword
// arguments of Python's roadbrdf.fit, and the request's files read and written the same way by both.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

RequestFields<FitRequest> FitRequest::fields() {
  using R = FitRequest;
  // Helps listing the names a field accepts, kept for the table's string views.
  static const std::string loss_help = "Residual: " + described_names_text<FitLoss>();
  static const std::string robust_help =
      "Robust loss, none or NAME:SCALE (SCALE in residual units): " + described_names_text<RobustLoss>();
  static const std::string solver_help =
      "Joint mode linear solver (per-wavelength blocks eliminated first): " + described_names_text<JointSolver>();
  static const std::vector<RequestField<R>> table = [] {
    std::vector<RequestField<R>> rows = {
        {"data", "DATA", "", "Dataset CSV (wide or long, BRDF in sr^-1, angles in degrees)", &R::data, FileRole::input},
    };
    for (const RequestField<R>& row : dataset_read_fields<R>()) rows.push_back(row);
    const std::vector<RequestField<R>> own = {
        {"models", "-m,--model", "", "Model to fit (repeatable), e.g. oren-nayar or oren-nayar+torrance-sparrow",
         &R::models},
        {"options", "--option", "", "Model option NAME=VALUE (repeatable), for every model declaring it", &R::options},
        {"shared", "--shared", "",
         "Parameters shared across wavelengths, comma-separated (joint spectral fit); 'auto' = the parameters "
         "declared non-spectral",
         &R::shared, FileRole::none, false, true},
        {"fixed", "--fix", "", "Hold a parameter NAME=VALUE at every wavelength (repeatable)", &R::fixed},
        {"start", "--start", "", "Starting value NAME=VALUE (repeatable); model defaults otherwise", &R::start},
        {"bounds", "--bound,--bounds", "",
         "Bounds NAME=LOWER:UPPER replacing a parameter's default fitting range, narrower or wider inside its "
         "physical range (the physical_bounds of `roadbrdf models`) (repeatable); a default start outside them "
         "moves to their middle",
         &R::bounds},
        {"loss", "--loss", "", loss_help, &R::loss},
        {"robust", "--robust", "", robust_help, &R::robust},
        {"solid_angle_weights", "--solid-angle-weights", "",
         "Weight each geometry by its solid-angle cell (nearest-neighbour estimate, fitting/fit.h)",
         &R::solid_angle_weights},
        {"use_sigma", "--no-sigma-weights", "",
         "Weights 1/sigma^2 from the dataset's uncertainties (on by default; the switch ignores them)", &R::use_sigma},
        {"sigma_from_duplicates", "--sigma-from-duplicates", "",
         "Sigma of each value from the repeatability of the dataset's duplicate rows (averaged): the pooled "
         "relative standard deviation of one measurement per wavelength times |value| / sqrt(rows averaged); "
         "for data without a sigma column (docs/fitting.md)",
         &R::sigma_from_duplicates},
        {"multistart", "--multistart", "",
         "Starting points per fit (1 to 10000): the start, then a Latin hypercube over the nonlinear parameters",
         &R::multistart},
        {"seed", "--seed", "", "Seed of the multi-start points", &R::seed},
        {"wavelengths", "--wavelengths", "nm", "Wavelengths to fit: START:STOP:STEP or a list", &R::wavelengths},
        {"bands", "--band", "nm",
         "Fit the mean of the measured spectrum over LOWER:UPPER, at the band's centre (repeatable; e.g. 590:610 on "
         "a 20 nm grid; not with the wavelengths field)",
         &R::bands},
        {"where", "--where", "",
         "Fit only the geometries where every comparison holds: COLUMN OP DEGREES joined by ',' or 'and', e.g. "
         "'theta_r<=70'; OP < <= > >= = !=; columns theta_i phi_i theta_r phi_r gamma alpha beta delta",
         &R::where},
        {"group_by", "--group-by", "",
         "Fit each group of geometries with equal angles separately, e.g. theta_i (one fit per incidence) or "
         "theta_i,phi_i; the fit file holds every group (select one as MODEL,theta_i=40)",
         &R::group_by, FileRole::none, false, true},
        {"threads", "--threads", "", "Threads (per-wavelength mode; the results do not depend on it)", &R::threads},
        {"joint_solver", "--joint-solver", "", solver_help, &R::joint_solver},
        {"max_iterations", "--max-iterations", "", "Iteration limit per problem", &R::max_iterations},
        {"covariance", "--no-covariance", "", "Standard errors and correlations (on by default; the switch skips them)",
         &R::covariance},
        {"warm_start", "--no-warm-start", "",
         "Start each wavelength from the previous wavelength's solution (on by default; the switch starts every "
         "wavelength from the given start)",
         &R::warm_start},
        {"solve_amplitudes", "--no-amplitude-solve", "",
         "Solve the linear amplitudes (parameters flagged linear) before each start (on by default; the switch "
         "does not)",
         &R::solve_amplitudes},
        {"residuals", "--residuals", "", "Write measured, fitted and residual values per geometry and wavelength (CSV)",
         &R::residuals, FileRole::output},
        {"output", "-o,--output", "", "Fit file to write (JSON)", &R::output, FileRole::output},
    };
    rows.insert(rows.end(), own.begin(), own.end());
    return rows;
  }();
  return table;
}

SpectralDataset read_fit_data(const FitRequest& request) {
  if (request.data.empty()) throw FieldError("data", "give the measured dataset");
  DatasetReadOptions options = request.options_for(request.data);
  if (!request.sigma_from_duplicates) return read_dataset(request.data, options);
  options.average_duplicates = true;  // the duplicates are what the sigma is estimated from
  DatasetReadStats stats;
  SpectralDataset data = read_dataset(request.data, options, stats);
  apply_duplicate_sigma(data, stats.repeatability, request.data);
  return data;
}

void apply_duplicate_sigma(SpectralDataset& data, const Repeatability& repeatability, const std::string& file) {
  const std::string field = "sigma_from_duplicates";
  if (data.has_sigma()) {
    throw FieldError(field, fmt::format("{} has a sigma column: its uncertainties are used as they are (leave "
                                        "`sigma_from_duplicates` off, or `use_sigma` off to ignore them)",
                                        file));
  }
  const std::size_t m = data.wavelengths.size();
  if (repeatability.geometries == 0 || repeatability.cell_counts.size() != data.brdf.size()) {
    throw FieldError(field, fmt::format("{} has no repeated geometry (no two rows with the same four angles), so "
                                        "there is no repeatability to estimate the sigma from",
                                        file));
  }
  for (std::size_t j = 0; j < m; ++j) {
    if (repeatability.degrees_of_freedom.at(j) == 0) {
      throw FieldError(field, fmt::format("{}: no duplicated geometry has two measured nonzero values at {} nm, so "
                                          "the repeatability there is unknown",
                                          file, data.wavelengths[j]));
    }
  }
  data.sigma.assign(data.brdf.size(), 0.0);
  for (std::size_t n = 0; n < data.geometry_count(); ++n) {
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t idx = n * m + j;
      const double y = data.brdf[idx];
      if (std::isnan(y)) {
        data.sigma[idx] = y;  // missing stays missing
        continue;
      }
      if (y == 0.0) {
        const Geometry& g = data.geometries[n];
        throw FieldError(field, fmt::format("{}: the value at {} nm of geometry {} (theta_i {:.6g}, phi_i {:.6g}, "
                                            "theta_r {:.6g}, phi_r {:.6g} deg) is 0, whose relative sigma would be 0 "
                                            "(an infinite weight)",
                                            file, data.wavelengths[j], n + 1, rad_to_deg(g.theta_i),
                                            rad_to_deg(g.phi_i), rad_to_deg(g.theta_r), rad_to_deg(g.phi_r)));
      }
      const double rows = std::max<double>(1.0, repeatability.cell_counts[idx]);
      data.sigma[idx] = repeatability.pooled_relative_sd[j] * std::fabs(y) / std::sqrt(rows);
    }
  }
  const auto [lo, hi] =
      std::minmax_element(repeatability.pooled_relative_sd.begin(), repeatability.pooled_relative_sd.end());
  data.metadata["sigma_from_duplicates"] = fmt::format(
      "pooled relative standard deviation of {} duplicated geometries, {:.4g} to {:.4g} over the "
      "wavelengths",
      repeatability.geometries, *lo, *hi);
}

void write_fit_outputs(const FitRequest& request, const FitSummary& summary, const SpectralDataset& data) {
  if (!request.output.empty()) write_fit_file(request.output, summary.fits, summary.notes);
  if (request.residuals.empty()) return;
  std::vector<const Model*> models;
  for (const auto& m : summary.models) models.push_back(m.get());
  AtomicFile out(request.residuals);
  const SpectralDataset fitted = fitted_spectra(request, data);  // its notes are the summary's
  write_residuals(out.stream(), fitted, models, summary.fits, request.where);
  out.commit();
}

}  // namespace roadbrdf
