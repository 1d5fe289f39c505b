#include "roadbrdf/fitting/fit_file.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/io/geometry_selection.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

namespace {

// NaN / inf are not JSON: write null.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

template <class F>
nlohmann::json per_wavelength(const FitResult& fit, F get) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& w : fit.wavelengths) a.push_back(get(w));
  return a;
}
}  // namespace

nlohmann::json fit_to_json(const FitResult& fit) {
  using nlohmann::json;
  json j;
  j["model"] = fit.model;
  if (!fit.group.empty()) {
    j["group"] = json::object();
    for (const auto& [column, value] : fit.group) j["group"][column] = value;
  }
  j["options"] = json::object();
  for (const auto& [k, v] : fit.options) j["options"][k] = v;
  j["mode"] = fit.joint ? "joint" : "per-wavelength";
  j["wavelengths"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.wavelength); });
  const std::size_t p = fit.parameter_names.size();
  j["parameters"] = json::object();
  j["stderr"] = json::object();
  j["parameter_units"] = json::object();
  for (std::size_t k = 0; k < p; ++k) {
    const std::string& name = fit.parameter_names[k];
    j["parameters"][name] = per_wavelength(fit, [k](const WavelengthFit& w) { return number(w.parameters[k]); });
    j["stderr"][name] = per_wavelength(fit, [k](const WavelengthFit& w) { return number(w.standard_errors[k]); });
    j["parameter_units"][name] = fit.parameter_units[k];
  }
  j["parameter_order"] = fit.parameter_names;
  j["correlation"] = per_wavelength(fit, [p](const WavelengthFit& w) {
    json m = json::array();
    for (std::size_t a = 0; a < p; ++a) {
      json row = json::array();
      for (std::size_t b = 0; b < p; ++b) row.push_back(number(w.correlation[a * p + b]));
      m.push_back(row);
    }
    return m;
  });
  j["fixed"] = fit.fixed;
  j["shared"] = fit.shared;
  j["loss"] = name_of(fit.settings.loss);
  j["robust"] = name_of(fit.settings.robust);
  j["robust_scale"] = fit.settings.robust == RobustLoss::kNone ? json(nullptr) : json(fit.settings.robust_scale);
  j["sigma_weights"] = fit.settings.use_sigma;
  j["solid_angle_weights"] = fit.settings.solid_angle_weights;
  j["multistart"] = fit.settings.multistart;
  j["seed"] = fit.settings.seed;
  if (!fit.settings.bounds.empty()) {
    json bounds = json::object();
    for (const auto& [name, range] : fit.settings.bounds) bounds[name] = {range.first, range.second};
    j["bounds"] = bounds;
  }
  j["rmse"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.rmse); });
  j["relative_rmse"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.relative_rmse); });
  j["max_relative_error"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.max_relative_error); });
  j["r_squared"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.r_squared); });
  j["chi2"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.chi2); });
  j["aic"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.aic); });
  j["bic"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.bic); });
  j["cost"] = per_wavelength(fit, [](const WavelengthFit& w) { return number(w.cost); });
  j["iterations"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.iterations); });
  j["converged"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.converged); });
  j["status"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.status); });
  j["covariance_ok"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.covariance_ok); });
  j["covariance_message"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.covariance_message); });
  j["at_bounds"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.at_bounds); });
  j["points"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.points); });
  j["free_parameters"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.free_parameters); });
  j["start_index"] = per_wavelength(fit, [](const WavelengthFit& w) { return json(w.start_index); });
  j["rmse_total"] = number(fit.rmse_total);
  j["relative_rmse_total"] = number(fit.relative_rmse_total);
  j["max_relative_error_total"] = number(fit.max_relative_error_total);
  j["chi2_total"] = number(fit.chi2_total);
  j["aic_total"] = number(fit.aic_total);
  j["bic_total"] = number(fit.bic_total);
  j["points_total"] = fit.points_total;
  j["missing_values"] = fit.missing_values;
  j["free_parameters_total"] = fit.free_parameters_total;
  j["wavelength_count"] = fit.wavelengths.size();
  j["converged_count"] = fit.converged_count;
  j["at_bound_count"] = fit.at_bound_count;
  j["covariance_failures"] = fit.covariance_failures;
  j["stayed_at_start_count"] = fit.stayed_at_start_count;
  j["worse_than_nested"] = fit.worse_than_nested;
  if (fit.joint) {
    j["joint_iterations"] = fit.joint_iterations;
    j["joint_status"] = fit.joint_status;
  }
  j["coverage"] = {{"theta_i_deg", {fit.coverage.theta_i_min_deg, fit.coverage.theta_i_max_deg}},
                   {"theta_r_deg", {fit.coverage.theta_r_min_deg, fit.coverage.theta_r_max_deg}},
                   {"azimuth_planes_deg", fit.coverage.azimuth_planes_deg},
                   {"geometries", fit.coverage.geometries}};
  j["seconds"] = fit.seconds;
  j["cpu_seconds"] = fit.cpu_seconds;
  return j;
}

std::size_t best_fit_index(const std::vector<FitResult>& fits) {
  if (fits.empty()) throw InputError("no fit to rank");
  // Groups are independent fits: a model's BIC is the sum over its groups (one term without groups).
  std::vector<std::string> models;
  std::vector<double> bic;
  std::vector<std::size_t> first;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const auto it = std::find(models.begin(), models.end(), fits[i].model);
    if (it == models.end()) {
      models.push_back(fits[i].model);
      bic.push_back(fits[i].bic_total);
      first.push_back(i);
    } else {
      bic[static_cast<std::size_t>(it - models.begin())] += fits[i].bic_total;
    }
  }
  std::size_t best = 0;
  for (std::size_t m = 1; m < models.size(); ++m) {
    if (bic[m] < bic[best]) best = m;
  }
  return first[best];
}

nlohmann::json fit_file_json(const std::vector<FitResult>& fits, const std::vector<std::string>& notes) {
  using nlohmann::json;
  json j;
  j["format"] = "roadbrdf-fit";
  // Version 2: fits of geometry groups, each with its "group"; the root's "group_by" names the columns.
  const bool grouped = !fits.empty() && !fits.front().group.empty();
  j["version"] = grouped ? 2 : 1;
  if (grouped) {
    j["group_by"] = json::array();
    for (const auto& [column, value] : fits.front().group) j["group_by"].push_back(column);
  }
  j["best"] = fits[best_fit_index(fits)].model;
  j["best_criterion"] = grouped ? "bic_total summed over the groups" : "bic_total";
  if (!notes.empty()) j["notes"] = notes;
  j["units"] = {
      {"wavelengths", "nm"},
      {"parameters", "see parameter_units"},
      {"stderr", "standard error, unit of the parameter; null = fixed or covariance undefined"},
      {"correlation", "1, p x p per wavelength in parameter_order"},
      {"rmse", "sr^-1, root mean square of fitted - measured BRDF"},
      {"relative_rmse", "1, rmse / mean |measured|"},
      {"max_relative_error", "1, max |fitted - measured| / |measured|"},
      {"r_squared", "1, coefficient of determination of the BRDF"},
      {"chi2", "sum of squared loss residuals (weights applied, no robust function)"},
      {"aic", "n ln(chi2/n) + 2k"},
      {"bic", "n ln(chi2/n) + k ln n"},
      {"group", "deg, the angles shared by the geometries of a group fit (fit option group_by)"},
      {"cost", "Ceres final cost 1/2 sum rho(r^2)"},
      {"seconds", "s, wall time of the fit"},
      {"cpu_seconds", "s, process CPU time of the fit (all threads)"},
  };
  j["fits"] = json::array();
  for (const auto& f : fits) j["fits"].push_back(fit_to_json(f));
  return j;
}

void write_fit_file(const std::string& path, const std::vector<FitResult>& fits,
                    const std::vector<std::string>& notes) {
  const nlohmann::json j = fit_file_json(fits, notes);
  AtomicFile out(path);
  write_json(out.stream(), j, 1);
  out.stream() << '\n';
  out.commit();
}

void write_residuals(std::ostream& out, const SpectralDataset& data, const std::vector<const Model*>& models,
                     const std::vector<FitResult>& fits, const std::string& where) {
  out << "# roadbrdf fit residuals: angles in degrees, wavelength in nm, BRDF in sr^-1; residual = fitted - measured\n";
  if (!where.empty()) out << "# geometries where " << where << "\n";
  const bool grouped = !fits.empty() && !fits.front().group.empty();
  out << "theta_i,phi_i,theta_r,phi_r,wavelength,model," << (grouped ? "group," : "") << "measured,fitted,residual\n";
  const GeometrySelection selection = where.empty() ? GeometrySelection{} : parse_geometry_selection(where, "where");
  const std::size_t M = data.wavelength_count();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    // The geometries of this fit: the selection, and its group.
    GeometryGroup group;
    group.key = fits[i].group;
    std::vector<std::size_t> indices;
    for (std::size_t g = 0; g < data.geometry_count(); ++g) {
      bool in = selection.matches(data.geometries[g]);
      for (const auto& [column, value] : group.key) {
        in = in && std::abs(geometry_column(data.geometries[g], column) - value) <= kAngleTolerance;
      }
      if (in) indices.push_back(g);
    }
    const SpectralDataset part = subset_geometries(data, indices);
    const std::vector<double> f = fitted_values(*models[i], part, fits[i]);
    const std::string label = grouped ? group.label() + "," : "";
    for (std::size_t g = 0; g < part.geometry_count(); ++g) {
      const Geometry& geo = part.geometries[g];
      const std::string angles = fmt::format("{:.10g},{:.10g},{:.10g},{:.10g}", rad_to_deg(geo.theta_i),
                                             rad_to_deg(geo.phi_i), rad_to_deg(geo.theta_r), rad_to_deg(geo.phi_r));
      for (std::size_t w = 0; w < M; ++w) {
        const double y = part.value(g, w), v = f[g * M + w];
        out << angles << ',' << fmt::format("{:.10g}", part.wavelengths[w]) << ',' << fits[i].model << ',' << label
            << fmt::format("{:.17g},{:.17g},{:.17g}", y, v, v - y) << '\n';
      }
    }
  }
}

SpectralModel spectral_model_of(const FitResult& fit, std::shared_ptr<const Model> model) {
  const std::size_t p = fit.parameter_names.size();
  if (model->parameter_count() != p) {
    throw InputError(
        fmt::format("spectral_model_of: the model has {} parameters, the fit {}", model->parameter_count(), p));
  }
  std::vector<bool> fixed(p, false);
  for (const std::string& name : fit.fixed) {
    if (const auto k = model->description().parameter_index(name)) fixed[*k] = true;
  }
  std::vector<double> wavelengths, table, covariance;
  for (const WavelengthFit& w : fit.wavelengths) {
    wavelengths.push_back(w.wavelength);
    table.insert(table.end(), w.parameters.begin(), w.parameters.begin() + static_cast<std::ptrdiff_t>(p));
    // As read_parameter_covariance builds it from the file's "stderr" and "correlation".
    for (std::size_t a = 0; a < p; ++a) {
      for (std::size_t b = 0; b < p; ++b) {
        covariance.push_back(
            fixed[a] || fixed[b] ? 0.0 : w.correlation[a * p + b] * w.standard_errors[a] * w.standard_errors[b]);
      }
    }
  }
  SpectralModel spectral(std::move(model), wavelengths, table);
  spectral.set_coverage(fit.coverage);
  spectral.set_parameter_covariance(std::move(covariance));
  spectral.set_shared_parameters(fit.shared);
  return spectral;
}

}  // namespace roadbrdf
