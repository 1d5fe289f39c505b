#include "roadbrdf/core/parameters.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

std::optional<std::size_t> ModelDescription::parameter_index(const std::string& parameter_name) const {
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    if (parameters[k].name == parameter_name) return k;
  }
  return std::nullopt;
}

std::vector<double> ModelDescription::default_parameters() const {
  std::vector<double> values;
  values.reserve(parameters.size());
  for (const auto& p : parameters) values.push_back(p.default_value);
  return values;
}

std::pair<double, double> ModelDescription::physical_range(std::size_t k) const {
  const ParameterInfo& p = parameters.at(k);
  const auto it = physical_bounds.find(p.name);
  return it != physical_bounds.end() ? it->second : std::pair<double, double>{p.lower, p.upper};
}

OptionSet resolve_options(const std::string& model, const std::vector<OptionInfo>& declared, const OptionSet& given) {
  OptionSet resolved;
  for (const auto& option : declared) resolved[option.name] = option.default_value;
  for (const auto& entry : given) {
    // Named copies: a lambda may not capture structured bindings before C++20 P1091 (clang 14).
    const std::string& name = entry.first;
    const std::string& value = entry.second;
    auto it = std::find_if(declared.begin(), declared.end(), [&](const OptionInfo& o) { return o.name == name; });
    if (it == declared.end()) {
      std::ostringstream msg;
      msg << "model '" << model << "' has no option '" << name << "'";
      if (declared.empty()) {
        msg << " (it has no options)";
      } else {
        msg << " (options:";
        for (const auto& o : declared) msg << ' ' << o.name;
        msg << ')';
      }
      throw InputError(msg.str());
    }
    if (!it->values.empty() && std::find(it->values.begin(), it->values.end(), value) == it->values.end()) {
      std::ostringstream msg;
      msg << "option '" << name << "' of model '" << model << "' cannot be '" << value << "' (allowed:";
      for (const auto& v : it->values) msg << ' ' << v;
      msg << ')';
      throw InputError(msg.str());
    }
    resolved[name] = value;
  }
  return resolved;
}

int integer_option(const std::string& model, const OptionSet& options, const std::string& name, int lo, int hi) {
  const auto it = options.find(name);
  if (it == options.end()) throw InputError("model '" + model + "' is missing option '" + name + "'");
  std::size_t used = 0;
  int value = 0;
  try {
    value = std::stoi(it->second, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != it->second.size() || value < lo || value > hi) {
    throw InputError("option '" + name + "' of model '" + model + "' must be an integer in [" + std::to_string(lo) +
                     ", " + std::to_string(hi) + "], got '" + it->second + "'");
  }
  return value;
}

bool is_isotropic_at(const ModelDescription& d, const double* params) {
  if (d.isotropic) return true;
  if (d.isotropic_when_equal.empty()) return false;
  for (const auto& [first, second] : d.isotropic_when_equal) {
    const auto a = d.parameter_index(first);
    const auto b = d.parameter_index(second);
    if (!a || !b || params[*a] != params[*b]) return false;
  }
  return true;
}

void combine_isotropy(ModelDescription& combined, const ModelDescription& component, const std::string& prefix) {
  if (component.isotropic) return;
  // `combined` was never isotropic before this component: a component that is never isotropic
  // leaves it so (its empty pair list stays empty through the flag below).
  const bool combined_never = !combined.isotropic && combined.isotropic_when_equal.empty();
  combined.isotropic = false;
  if (combined_never || component.isotropic_when_equal.empty()) {
    combined.isotropic_when_equal.clear();
    return;
  }
  for (const auto& [first, second] : component.isotropic_when_equal) {
    combined.isotropic_when_equal.emplace_back(prefix + "." + first, prefix + "." + second);
  }
}

void check_parameters(const ModelDescription& description, const std::vector<double>& values) {
  if (values.size() != description.parameters.size()) {
    throw InputError("model '" + description.name + "' takes " + std::to_string(description.parameters.size()) +
                     " parameters, got " + std::to_string(values.size()));
  }
  for (std::size_t k = 0; k < values.size(); ++k) {
    const auto& p = description.parameters[k];
    const auto [lo, hi] = description.physical_range(k);
    if (!std::isfinite(values[k]) || values[k] < lo || values[k] > hi) {
      std::ostringstream msg;
      msg << "parameter '" << p.name << "' of model '" << description.name << "' = " << values[k]
          << " is outside its bounds [" << lo << ", " << hi << "]";
      throw InputError(msg.str());
    }
  }
}

}  // namespace roadbrdf
