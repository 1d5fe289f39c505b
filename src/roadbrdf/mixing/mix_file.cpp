#include "roadbrdf/mixing/mix_file.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::mixing {

namespace {

using ordered = nlohmann::ordered_json;

ordered number_or_null(double x) { return std::isfinite(x) ? ordered(x) : ordered(nullptr); }

ordered weights_object(const std::vector<std::string>& names, const std::vector<double>& weights) {
  ordered o = ordered::object();
  for (std::size_t k = 0; k < names.size() && k < weights.size(); ++k) o[names[k]] = number_or_null(weights[k]);
  return o;
}

// A mixture's parameter covariance (mixture_covariance.h) as a fit file stores a fit's: "stderr" per
// parameter and wavelength, "correlation" per wavelength (0 off the diagonal for a parameter of
// standard error 0) and "fixed", the parameters of variance 0 at every wavelength (the weights, the
// end-members' fixed parameters). Nothing when the mixture has none.
void add_covariance(ordered& method, const SpectralModel& model) {
  const std::vector<double>& covariance = model.parameter_covariance();
  if (covariance.empty()) return;
  const ModelDescription& d = model.model().description();
  const std::size_t P = d.parameters.size(), L = model.wavelengths().size();
  auto c = [&](std::size_t l, std::size_t a, std::size_t b) { return covariance[(l * P + a) * P + b]; };
  ordered stderr_object = ordered::object(), fixed = ordered::array();
  for (std::size_t a = 0; a < P; ++a) {
    ordered column = ordered::array();
    bool always_zero = true;
    for (std::size_t l = 0; l < L; ++l) {
      column.push_back(number_or_null(std::sqrt(c(l, a, a))));
      always_zero = always_zero && c(l, a, a) == 0.0;
    }
    stderr_object[d.parameters[a].name] = column;
    if (always_zero) fixed.push_back(d.parameters[a].name);
  }
  ordered correlation = ordered::array();
  for (std::size_t l = 0; l < L; ++l) {
    ordered matrix = ordered::array();
    for (std::size_t a = 0; a < P; ++a) {
      ordered row = ordered::array();
      for (std::size_t b = 0; b < P; ++b) {
        const double s = std::sqrt(c(l, a, a) * c(l, b, b));
        row.push_back(s == 0.0 ? ordered(a == b ? 1.0 : 0.0) : number_or_null(c(l, a, b) / s));
      }
      matrix.push_back(row);
    }
    correlation.push_back(matrix);
  }
  method["stderr"] = stderr_object;
  method["correlation"] = correlation;
  method["fixed"] = fixed;
}

}  // namespace

nlohmann::ordered_json mix_file_json(const MixFileContent& content) {
  const MixInputs& inputs = *content.inputs;
  const Formulation& f = inputs.formulation;
  ordered j;
  j["format"] = "roadbrdf-mix";
  j["version"] = 1;
  j["units"] = {
      {"wavelengths", "nm"},
      {"weight", "1: area fraction (linear, shadowed) or normalised cross-section weight M/(rho D) (hapke)"},
      {"ssa", "1: single-scattering albedo (Hapke IMSA, H1)"},
      {"shadowing", "1: s in exp(-s (tan theta_i + tan theta_r))"},
      {"stderr", "standard uncertainty of each parameter, in its unit, from the end-members' fits"},
      {"correlation", "1: correlation matrix of the parameters per wavelength"},
      {"rmse", "sr^-1 (BRDF)"},
      {"relative_rmse", "1: rmse / mean |measured BRDF|"},
      {"chi2_reduced", "1: mean of ((predicted - measured) / sigma)^2 over the held-out values (null without sigma)"},
      {"albedo", "1: white-sky (bi-hemispherical) albedo, mean over the wavelengths"},
      {"d_eff_mm", "mm"},
      {"density_g_cm3", "g/cm^3"},
      {"mass_percent", "% of the total mass"}};
  ordered components = ordered::array();
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    const Component& c = f.components[i];
    std::string member;
    for (const auto& e : inputs.end_members) {
      for (std::size_t k : e.components) {
        if (k == i) member = e.name;
      }
    }
    ordered d_eff = nullptr;
    try {
      d_eff = effective_diameter_mm(f, c);
    } catch (const InputError&) {
    }
    components.push_back({{"name", c.name},
                          {"kind", name_of(c.kind)},
                          {"mass_percent", c.mass_percent},
                          {"density_g_cm3", c.density},
                          {"d_eff_mm", d_eff},
                          {"coarse", is_coarse(f, c)},
                          {"end_member", member}});
  }
  j["formulation"] = {{"name", f.name}, {"file", f.path}, {"components", components}};
  ordered members = ordered::array();
  for (const auto& e : inputs.end_members) {
    ordered options = ordered::object();
    for (const auto& [key, value] : e.model->model().description().option_values) options[key] = value;
    members.push_back({{"name", e.name},
                       {"fit", e.fit_path},
                       {"fit_model", e.fit_model},
                       {"model", e.model->model().name()},
                       {"options", options},
                       {"is_mastic", e.is_mastic}});
  }
  j["end_members"] = members;
  j["data"] = content.data_path.empty() ? ordered(nullptr) : ordered(content.data_path);
  j["folds"] = content.comparisons.empty() ? ordered(nullptr) : ordered(content.folds);
  ordered best = nullptr;
  if (!content.comparisons.empty()) {
    std::size_t b = 0;
    for (std::size_t i = 1; i < content.comparisons.size(); ++i) {
      if (content.comparisons[i].rmse < content.comparisons[b].rmse) b = i;
    }
    best = name_of(content.comparisons[b].method);
  }
  j["best"] = best;
  ordered methods = ordered::array();
  for (std::size_t r = 0; r < content.results.size(); ++r) {
    const MixResult& res = content.results[r];
    const SpectralModel& model = *res.model;
    const ModelDescription& d = model.model().description();
    ordered m;
    m["method"] = name_of(res.method);
    m["description"] = res.description;
    m["model"] = d.name;
    m["end_members"] = res.end_members;
    m["coarse"] = res.mixture->coarse_flags();
    m["wavelengths"] = model.wavelengths();
    ordered params = ordered::object();
    const std::size_t n = d.parameters.size();
    const std::size_t rows = model.is_spectral() ? model.wavelengths().size() : 1;
    for (std::size_t q = 0; q < n; ++q) {
      std::vector<double> values(rows);
      for (std::size_t w = 0; w < rows; ++w) values[w] = model.parameter_table()[w * n + q];
      params[d.parameters[q].name] = values;
    }
    m["parameters"] = params;
    add_covariance(m, model);
    m["weights"] = weights_object(res.end_members, res.weights);
    m["formulation_weights"] =
        res.formulation_weights.empty() ? ordered(nullptr) : weights_object(res.end_members, res.formulation_weights);
    m["weight_distance"] = number_or_null(res.weight_distance);
    m["weight_sum"] = number_or_null(res.weight_sum);
    ordered settings = ordered::object();
    for (const auto& [key, value] : res.settings) settings[key] = value;
    m["settings"] = settings;
    m["notes"] = res.notes;
    if (r < content.comparisons.size()) {
      const Comparison& c = content.comparisons[r];
      m["comparison"] = {{"folds", c.folds},
                         {"rmse", c.rmse},
                         {"relative_rmse", c.relative_rmse},
                         {"rmse_in_sample", c.rmse_in_sample},
                         {"relative_rmse_in_sample", c.relative_rmse_in_sample},
                         {"chi2_reduced", number_or_null(c.chi2_reduced)},
                         {"albedo", c.albedo},
                         {"albedo_reference", number_or_null(c.albedo_reference)},
                         {"albedo_difference", number_or_null(c.albedo_difference)}};
    } else {
      m["comparison"] = nullptr;
    }
    methods.push_back(m);
  }
  j["methods"] = methods;
  return j;
}

void write_mix_file(const std::string& path, const MixFileContent& content) {
  const nlohmann::ordered_json j = mix_file_json(content);
  AtomicFile out(path);
  write_json(out.stream(), j, 1);
  out.stream() << '\n';
  out.commit();
}

}  // namespace roadbrdf::mixing
