#include "roadbrdf/fitting/fit_file.h"

#include <fmt/core.h>

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

// The "coverage" object of a fit (fit_to_json): ranges [min, max] within [0, 90] deg, planes within
// [0, 180] deg, a positive geometry count.
AngularCoverage read_coverage(const JsonNode& node) {
  AngularCoverage c;
  auto range = [&](const char* key, double& lo, double& hi) {
    const JsonNode r = node.at(key);
    const auto v = r.numbers();
    if (v.size() != 2 || !(v[0] >= 0.0 && v[0] <= v[1] && v[1] <= 90.0)) r.fail("expected [min, max] in [0, 90] deg");
    lo = v[0];
    hi = v[1];
  };
  range("theta_i_deg", c.theta_i_min_deg, c.theta_i_max_deg);
  range("theta_r_deg", c.theta_r_min_deg, c.theta_r_max_deg);
  const JsonNode planes = node.at("azimuth_planes_deg");
  c.azimuth_planes_deg = planes.numbers();
  for (std::size_t k = 0; k < c.azimuth_planes_deg.size(); ++k) {
    const double b = c.azimuth_planes_deg[k];
    if (!(b >= 0.0 && b <= 180.0) || (k > 0 && !(b > c.azimuth_planes_deg[k - 1]))) {
      planes[k].fail("azimuth planes must be increasing, in [0, 180] deg");
    }
  }
  c.geometries = static_cast<std::size_t>(node.at("geometries").integer(1, 1LL << 40));
  return c;
}

// The parameter covariance per wavelength (SpectralModel::parameter_covariance) from "stderr" and
// "correlation": cov_ab = r_ab s_a s_b, 0 for a fixed parameter, NaN where either is null (undefined).
// Empty when the file has neither, or orders its parameters otherwise than the model.
std::vector<double> read_covariance(const JsonNode& fit, const ModelDescription& d, std::size_t m) {
  const auto stderr_node = fit.find("stderr");
  const auto correlation_node = fit.find("correlation");
  if (!stderr_node || !correlation_node) return {};
  const std::size_t p = d.parameters.size();
  if (const auto order = fit.find("parameter_order")) {
    const std::vector<std::string> names = order->strings();
    if (names.size() != p) return {};
    for (std::size_t k = 0; k < p; ++k) {
      if (names[k] != d.parameters[k].name) return {};
    }
  }
  std::vector<bool> fixed(p, false);
  if (const auto f = fit.find("fixed")) {
    for (const std::string& name : f->strings()) {
      if (const auto k = d.parameter_index(name)) fixed[*k] = true;
    }
  }
  constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  auto value_or_undefined = [](const JsonNode& v) { return v.is_null() ? kUndefined : v.number(); };
  std::vector<double> se(p * m, kUndefined);
  for (std::size_t k = 0; k < p; ++k) {
    const auto column = stderr_node->find(d.parameters[k].name);
    if (!column) return {};
    if (column->size() != m) column->fail("expected one value per wavelength");
    for (std::size_t w = 0; w < m; ++w) se[k * m + w] = value_or_undefined((*column)[w]);
  }
  if (correlation_node->size() != m) correlation_node->fail("expected one matrix per wavelength");
  std::vector<double> covariance(m * p * p, kUndefined);
  for (std::size_t w = 0; w < m; ++w) {
    const JsonNode matrix = (*correlation_node)[w];
    if (!matrix.is_null() && matrix.size() != p) matrix.fail("expected a p x p matrix");
    for (std::size_t a = 0; a < p; ++a) {
      const std::optional<JsonNode> row = matrix.is_null() ? std::nullopt : std::optional<JsonNode>(matrix[a]);
      if (row && !row->is_null() && row->size() != p) row->fail("expected a p x p matrix");
      for (std::size_t b = 0; b < p; ++b) {
        double& c = covariance[(w * p + a) * p + b];
        if (fixed[a] || fixed[b]) {
          c = 0.0;
        } else if (row && !row->is_null()) {
          c = value_or_undefined((*row)[b]) * se[a * m + w] * se[b * m + w];
        }
      }
    }
  }
  return covariance;
}

}  // namespace

nlohmann::json fit_to_json(const FitResult& fit) {
  using nlohmann::json;
  json j;
  j["model"] = fit.model;
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
  j["loss"] = to_string(fit.settings.loss);
  j["robust"] = to_string(fit.settings.robust);
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
  std::size_t best = 0;
  for (std::size_t i = 1; i < fits.size(); ++i) {
    if (fits[i].bic_total < fits[best].bic_total) best = i;
  }
  return best;
}

nlohmann::json fit_file_json(const std::vector<FitResult>& fits) {
  using nlohmann::json;
  json j;
  j["format"] = "roadbrdf-fit";
  j["version"] = 1;
  j["best"] = fits[best_fit_index(fits)].model;
  j["best_criterion"] = "bic_total";
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
      {"cost", "Ceres final cost 1/2 sum rho(r^2)"},
      {"seconds", "s, wall time of the fit"},
      {"cpu_seconds", "s, process CPU time of the fit (all threads)"},
  };
  j["fits"] = json::array();
  for (const auto& f : fits) j["fits"].push_back(fit_to_json(f));
  return j;
}

void write_fit_file(const std::string& path, const std::vector<FitResult>& fits) {
  const nlohmann::json j = fit_file_json(fits);
  AtomicFile out(path);
  out.stream() << dump_json(j, 1) << '\n';
  out.commit();
}

void write_residuals(std::ostream& out, const SpectralDataset& data, const std::vector<const Model*>& models,
                     const std::vector<FitResult>& fits) {
  out << "# roadbrdf fit residuals: angles in degrees, wavelength in nm, BRDF in sr^-1; residual = fitted - measured\n";
  out << "theta_i,phi_i,theta_r,phi_r,wavelength,model,measured,fitted,residual\n";
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const std::vector<double> f = fitted_values(*models[i], data, fits[i]);
    for (std::size_t g = 0; g < N; ++g) {
      const Geometry& geo = data.geometries[g];
      const std::string angles = fmt::format("{:.10g},{:.10g},{:.10g},{:.10g}", rad_to_deg(geo.theta_i),
                                             rad_to_deg(geo.phi_i), rad_to_deg(geo.theta_r), rad_to_deg(geo.phi_r));
      for (std::size_t w = 0; w < M; ++w) {
        const double y = data.value(g, w), v = f[g * M + w];
        out << angles << ',' << fmt::format("{:.10g}", data.wavelengths[w]) << ',' << fits[i].model << ','
            << fmt::format("{:.17g},{:.17g},{:.17g}", y, v, v - y) << '\n';
      }
    }
  }
}

bool is_fit_file_argument(const std::string& argument) {
  return argument.size() > 5 && argument.compare(argument.size() - 5, 5, ".json") == 0;
}

SpectralModel read_fit_file(const std::string& path, const std::string& model_name) {
  const Json document = parse_json_file(path);
  const JsonNode root(document, input_display_name(path));
  if (!root.is_object() || root.string_or("format", "") != "roadbrdf-fit") {
    throw FileError(root.file(), 0, 0, "not a roadbrdf fit file (format key)");
  }
  const std::string wanted = model_name.empty() ? root.at("best").string() : model_name;
  const JsonNode fits = root.at("fits");
  for (const JsonNode& fit : fits.elements()) {
    const JsonNode model_node = fit.at("model");
    if (model_node.string() != wanted) continue;
    OptionSet options;
    if (const auto o = fit.find("options")) options = o->string_map();
    std::shared_ptr<const Model> model;
    try {
      model = make_model(wanted, options);
    } catch (const FileError&) {
      throw;
    } catch (const InputError& e) {
      model_node.fail(e.what());
    }
    const JsonNode wavelength_node = fit.at("wavelengths");
    const auto wavelengths = wavelength_node.numbers();
    if (wavelengths.empty()) wavelength_node.fail("no wavelengths");
    for (std::size_t w = 1; w < wavelengths.size(); ++w) {
      if (!(wavelengths[w] > wavelengths[w - 1])) wavelength_node[w].fail("wavelengths must be strictly increasing");
    }
    const auto table =
        read_parameter_table(fit.at("parameters"), model->description(), wavelengths.size(), wavelengths);
    SpectralModel spectral(model, wavelengths, table);
    if (const auto c = fit.find("coverage")) spectral.set_coverage(read_coverage(*c));
    spectral.set_parameter_covariance(read_covariance(fit, model->description(), wavelengths.size()));
    return spectral;
  }
  fits.fail("no fit of model '" + wanted + "' in this file");
}

}  // namespace roadbrdf
