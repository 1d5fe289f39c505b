#include "roadbrdf/mixing/mix_file.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::mixing {

namespace {

using nlohmann::json;
using ordered = nlohmann::ordered_json;

ordered number_or_null(double x) { return std::isfinite(x) ? ordered(x) : ordered(nullptr); }

ordered weights_object(const std::vector<std::string>& names, const std::vector<double>& weights) {
  ordered o = ordered::object();
  for (std::size_t k = 0; k < names.size() && k < weights.size(); ++k) o[names[k]] = number_or_null(weights[k]);
  return o;
}

}  // namespace

void write_mix_file(const std::string& path, const MixFileContent& content) {
  const MixInputs& inputs = *content.inputs;
  const Formulation& f = inputs.formulation;
  ordered j;
  j["format"] = "roadbrdf-mix";
  j["version"] = 1;
  j["units"] = {{"wavelengths", "nm"},
                {"weight", "1: area fraction (linear, shadowed) or normalised cross-section weight M/(rho D) (hapke)"},
                {"ssa", "1: single-scattering albedo (Hapke IMSA, H1)"},
                {"shadowing", "1: s in exp(-s (tan theta_i + tan theta_r))"},
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
                          {"kind", to_string(c.kind)},
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
    best = to_string(content.comparisons[b].method);
  }
  j["best"] = best;
  ordered methods = ordered::array();
  for (std::size_t r = 0; r < content.results.size(); ++r) {
    const MixResult& res = content.results[r];
    const SpectralModel& model = *res.model;
    const ModelDescription& d = model.model().description();
    ordered m;
    m["method"] = to_string(res.method);
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
  AtomicFile out(path);
  out.stream() << j.dump(1) << '\n';
  out.commit();
}

bool is_mix_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return false;
  try {
    const json j = json::parse(in);
    return j.is_object() && j.value("format", "") == "roadbrdf-mix";
  } catch (const json::exception&) {
    return false;
  }
}

SpectralModel read_mix_file(const std::string& path, const std::string& method) {
  std::ifstream in(path);
  if (!in) throw FileError(path, 0, 0, "cannot open mix file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw FileError(path, 0, 0, std::string("not valid JSON: ") + e.what());
  }
  try {
    if (j.value("format", "") != "roadbrdf-mix") throw FileError(path, 0, 0, "not a roadbrdf mix file (format key)");
    const auto& methods = j.at("methods");
    if (!methods.is_array() || methods.empty()) throw FileError(path, 0, 0, "no methods in this mix file");
    std::string wanted = method;
    if (wanted.empty()) {
      wanted = j.at("best").is_string() ? j.at("best").get<std::string>() : methods.at(0).at("method").get<std::string>();
    }
    for (const auto& m : methods) {
      if (m.at("method").get<std::string>() != wanted) continue;
      const std::string model_name = m.at("model").get<std::string>();
      const std::string prefix = "mixture-";
      if (model_name.rfind(prefix, 0) != 0) throw FileError(path, 0, 0, "method '" + wanted + "': unknown model " + model_name);
      const MixtureKind kind = mixture_kind_from_string(model_name.substr(prefix.size()));
      std::vector<std::shared_ptr<const Model>> models;
      std::vector<std::string> names = m.at("end_members").get<std::vector<std::string>>();
      for (const auto& name : names) {
        bool found = false;
        for (const auto& e : j.at("end_members")) {
          if (e.at("name").get<std::string>() != name) continue;
          OptionSet options;
          const json option_values = e.value("options", json::object());  // named: items() must not outlive it
          for (const auto& [key, value] : option_values.items()) options[key] = value.get<std::string>();
          models.push_back(std::shared_ptr<const Model>(make_model(e.at("model").get<std::string>(), options)));
          found = true;
          break;
        }
        if (!found) throw FileError(path, 0, 0, "method '" + wanted + "': end-member '" + name + "' is not described");
      }
      std::vector<bool> coarse = m.value("coarse", std::vector<bool>{});
      auto mixture = std::make_shared<const MixtureModel>(kind, models, names, coarse);
      const auto wavelengths = m.at("wavelengths").get<std::vector<double>>();
      const std::size_t rows = wavelengths.empty() ? 1 : wavelengths.size();
      const std::size_t n = mixture->parameter_count();
      std::vector<double> table(rows * n);
      const auto& parameters = m.at("parameters");
      for (std::size_t q = 0; q < n; ++q) {
        const std::string& pname = mixture->description().parameters[q].name;
        if (!parameters.contains(pname)) {
          throw FileError(path, 0, 0, "method '" + wanted + "' lacks parameter '" + pname + "'");
        }
        const auto values = parameters.at(pname).get<std::vector<double>>();
        if (values.size() != rows) {
          throw FileError(path, 0, 0, "parameter '" + pname + "' has " + std::to_string(values.size()) + " values for " +
                                          std::to_string(rows) + " wavelengths");
        }
        for (std::size_t w = 0; w < rows; ++w) table[w * n + q] = values[w];
      }
      if (wavelengths.empty()) return SpectralModel(mixture, table);
      return SpectralModel(mixture, wavelengths, table);
    }
    throw FileError(path, 0, 0, "no method '" + wanted + "' in this mix file");
  } catch (const json::exception& e) {
    throw FileError(path, 0, 0, std::string("malformed mix file: ") + e.what());
  }
}

SpectralModel read_spectral_model_file(const std::string& path, const std::string& selection) {
  if (is_mix_file(path)) return read_mix_file(path, selection);
  return read_fit_file(path, selection);
}

}  // namespace roadbrdf::mixing
