#include "roadbrdf/modelfile/fit_file_read.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

namespace {

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

}  // namespace

// The parameter covariance per wavelength (SpectralModel::parameter_covariance) from "stderr" and
// "correlation": cov_ab = r_ab s_a s_b, 0 for a fixed parameter, NaN where either is null (undefined).
// Empty when the file has neither, or orders its parameters otherwise than the model.
std::vector<double> read_parameter_covariance(const JsonNode& fit, const ModelDescription& d, std::size_t m) {
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

namespace {

// The group of a fit ("group" object; empty without groups) as (column, value) pairs.
std::vector<std::pair<std::string, double>> fit_group(const JsonNode& fit) {
  std::vector<std::pair<std::string, double>> g;
  if (const auto node = fit.find("group")) {
    for (const auto& [column, value] : node->members()) g.emplace_back(column, value.number());
  }
  return g;
}

std::string group_label(const std::vector<std::pair<std::string, double>>& group) {
  std::string s;
  for (const auto& [column, value] : group) s += fmt::format("{}{}={:.10g}", s.empty() ? "" : ",", column, value);
  return s;
}

// The position in `fits` of the fit of model `wanted` whose group matches the selector's columns:
// exactly one, or an error naming the choices.
std::size_t select_fits(const JsonNode& root, const JsonNode& fits, const std::string& wanted,
                        const FitSelector& selector) {
  std::vector<std::string> models, columns;
  if (const auto g = root.find("group_by")) columns = g->strings();
  for (const auto& [column, value] : selector.group) {
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) {
      throw FieldError("fit", "'" + column + "': this fit file " +
                                  (columns.empty() ? std::string("has no groups")
                                                   : "is grouped by " + fmt::format("{}", fmt::join(columns, ","))) +
                                  did_you_mean(column, columns));
    }
  }
  std::vector<std::size_t> matching;
  std::vector<std::string> labels;
  const std::vector<JsonNode> elements = fits.elements();
  for (std::size_t index = 0; index < elements.size(); ++index) {
    const JsonNode& fit = elements[index];
    const std::string model = fit.at("model").string();
    if (std::find(models.begin(), models.end(), model) == models.end()) models.push_back(model);
    if (model != wanted) continue;
    const auto group = fit_group(fit);
    bool ok = true;
    for (const auto& wanted_column : selector.group) {
      const auto it = std::find_if(group.begin(), group.end(),
                                   [&wanted_column](const auto& c) { return c.first == wanted_column.first; });
      ok = ok && it != group.end() && std::abs(it->second - wanted_column.second) <= 1e-6;
    }
    labels.push_back(group_label(group));
    if (ok) matching.push_back(index);
  }
  if (labels.empty()) fits.fail("no fit of model '" + wanted + "' in this file" + did_you_mean(wanted, models));
  if (matching.empty()) {
    throw FieldError("fit", fmt::format("no fit of {} for group {} in {}; its groups: {}", wanted,
                                        group_label(selector.group), root.file(), fmt::join(labels, " ")));
  }
  if (matching.size() > 1) {
    throw FieldError("fit", fmt::format("{} holds {} fits of {}, one per group ({}): choose one with a selector "
                                        "such as '{},{}'",
                                        root.file(), matching.size(), wanted, fmt::join(labels, " "), wanted,
                                        group_label(fit_group(elements[matching.front()]))));
  }
  return matching.front();
}
}  // namespace

bool is_fit_file_argument(const std::string& argument) {
  return argument.size() > 5 && argument.compare(argument.size() - 5, 5, ".json") == 0;
}

FitSelector parse_fit_selector(const std::string& text) {
  FitSelector s;
  std::string item;
  auto take = [&s, &text](std::string t) {
    while (!t.empty() && t.front() == ' ') t.erase(t.begin());
    while (!t.empty() && t.back() == ' ') t.pop_back();
    if (t.empty()) return;
    const auto eq = t.find('=');
    if (eq == std::string::npos) {
      if (!s.model.empty()) throw FieldError("fit", "two model names in '" + text + "'");
      s.model = t;
      return;
    }
    double v = 0.0;
    const std::string column = t.substr(0, eq);
    if (!parse_finite_double(t.substr(eq + 1), v)) {
      throw FieldError("fit", "'" + t + "': expected COLUMN=DEGREES in '" + text + "'");
    }
    s.group.emplace_back(column, v);
  };
  for (char c : text) {
    if (c == ',') {
      take(item);
      item.clear();
    } else {
      item += c;
    }
  }
  take(item);
  return s;
}

InputLimits fit_file_limits() {
  InputLimits limits;
  limits.what = "a fit file";
  limits.max_bytes = std::uintmax_t{256} << 20;
  return limits;
}

SpectralModel read_fit_file(const std::string& path, const std::string& selection) {
  return read_fit_file_entry(path, selection).model;
}

FitFileEntry read_fit_file_entry(const std::string& path, const std::string& selection) {
  return parse_fit_file_entry(read_text_file(path, fit_file_limits()), input_display_name(path), selection);
}

SpectralModel parse_fit_file(const std::string& json_text, const std::string& name, const std::string& selection) {
  return parse_fit_file_entry(json_text, name, selection).model;
}

namespace {

// A parsed fit file's root, with its format checked.
JsonNode fit_file_root(const Json& document, const std::string& name) {
  JsonNode root(document, name);
  if (!root.is_object() || root.string_or("format", "") != "roadbrdf-fit") {
    throw FileError(root.file(), 0, 0, "not a roadbrdf fit file (format key)");
  }
  return root;
}

// The fit of a parsed fit file (`root`, checked to be one) that `selection` chooses.
FitFileEntry entry_of(const JsonNode& root, const std::string& selection) {
  const JsonNode fits = root.at("fits");
  const JsonNode fit = fits[select_fit(root, selection)];
  const std::string wanted = fit.at("model").string();
  const JsonNode model_node = fit.at("model");
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
  const auto table = read_parameter_table(fit.at("parameters"), model->description(), wavelengths.size(), wavelengths);
  SpectralModel spectral(model, wavelengths, table);
  if (const auto c = fit.find("coverage")) spectral.set_coverage(read_coverage(*c));
  spectral.set_parameter_covariance(read_parameter_covariance(fit, model->description(), wavelengths.size()));
  if (const auto shared = fit.find("shared")) spectral.set_shared_parameters(shared->strings());
  const std::string group = group_label(fit_group(fit));
  return {std::move(spectral), group.empty() ? wanted : wanted + "," + group};
}

}  // namespace

FitFileEntry parse_fit_file_entry(const std::string& json_text, const std::string& name, const std::string& selection) {
  return fit_file_entry(parse_json_text(json_text, name), name, selection);
}

FitFileEntry fit_file_entry(const Json& document, const std::string& name, const std::string& selection) {
  return entry_of(fit_file_root(document, name), selection);
}

std::vector<SpectralModel> read_fit_file_models(const std::string& path, const std::vector<std::string>& selections) {
  const std::string name = input_display_name(path);
  const Json document = parse_json_text(read_text_file(path, fit_file_limits()), name);
  const JsonNode root = fit_file_root(document, name);
  std::vector<SpectralModel> models;
  models.reserve(selections.size());
  for (const std::string& selection : selections) models.push_back(entry_of(root, selection).model);
  return models;
}

std::size_t select_fit(const JsonNode& root, const std::string& selection) {
  const FitSelector selector = parse_fit_selector(selection);
  const std::string wanted = selector.model.empty() ? root.at("best").string() : selector.model;
  return select_fits(root, root.at("fits"), wanted, selector);
}

}  // namespace roadbrdf
