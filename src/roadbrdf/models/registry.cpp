#include "roadbrdf/models/registry.h"

#include <functional>
#include <set>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/models/composite.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

namespace {

// Every model's factory, in display order (one per model source file, model_factory.h).
const std::vector<ModelFactory>& factories() {
  static const std::vector<ModelFactory> table = {
      lambert_factory(),   oren_nayar_factory(),  ashikhmin_shirley_factory(), simonot_factory(),
      lafortune_factory(), retro_phong_factory(), torrance_sparrow_factory(),  kelemen_szirmay_kalos_factory(),
      burley_factory(),    hapke_factory(),       ross_li_factory(),           rpv_factory(),
      // [model-entries]
  };
  return table;
}

struct AliasEntry {
  ModelAlias alias;
  const ModelFactory* factory;
};

const std::vector<AliasEntry>& alias_entries() {
  static const std::vector<AliasEntry> table = [] {
    std::vector<AliasEntry> t;
    for (const ModelFactory& factory : factories()) {
      for (ModelAlias& alias : factory.aliases()) t.push_back({std::move(alias), &factory});
    }
    return t;
  }();
  return table;
}

// The alias's fixed options are merged into the given ones; giving one of them another value is an
// error naming the model that allows it.
std::unique_ptr<Model> make_alias(const AliasEntry& entry, const OptionSet& given) {
  const ModelAlias& alias = entry.alias;
  OptionSet options = given;
  for (const auto& [option, value] : alias.options) {
    const auto it = given.find(option);
    if (it != given.end() && it->second != value) {
      throw InputError("model '" + alias.name + "' fixes option '" + option + "' = " + value + " (" +
                       alias.description + "); for " + option + "=" + it->second + " use model '" + alias.model + "'");
    }
    options[option] = value;
  }
  return entry.factory->make(options, alias.name);
}

std::unique_ptr<Model> make_single(const std::string& name, const OptionSet& options) {
  for (const ModelFactory& factory : factories()) {
    if (factory.name == name) return factory.make(options, name);
  }
  for (const AliasEntry& entry : alias_entries()) {
    if (entry.alias.name == name) return make_alias(entry, options);
  }
  std::vector<std::string> known;
  for (const ModelFactory& factory : factories()) known.emplace_back(factory.name);
  for (const auto& a : alias_entries()) known.push_back(a.alias.name);
  std::ostringstream msg;
  msg << "unknown model '" << name << "'" << did_you_mean(name, known) << " (known:";
  for (const ModelFactory& factory : factories()) msg << ' ' << factory.name;
  for (const auto& a : alias_entries()) msg << ' ' << a.alias.name;
  msg << "; combine with '+', e.g. oren-nayar+torrance-sparrow)";
  throw InputError(msg.str());
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : s) {
    if (c == sep) {
      parts.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  parts.push_back(current);
  return parts;
}

}  // namespace

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const ModelFactory& factory : factories()) names.emplace_back(factory.name);
  return names;
}

std::vector<ModelAlias> model_aliases() {
  std::vector<ModelAlias> aliases;
  for (const auto& a : alias_entries()) aliases.push_back(a.alias);
  return aliases;
}

std::unique_ptr<Model> make_model(const std::string& name, const OptionSet& options) {
  if (name.find('+') == std::string::npos) return make_single(name, options);

  const std::vector<std::string> parts = split(name, '+');
  std::vector<std::string> prefixes;
  std::map<std::string, int> seen;
  for (const auto& part : parts) {
    if (part.empty()) throw InputError("empty component in composite model name '" + name + "'");
    const int count = ++seen[part];
    prefixes.push_back(count == 1 ? part : part + "#" + std::to_string(count));
  }
  // Distribute options: "prefix.option" to one component, plain "option" to all that declare it.
  std::vector<OptionSet> component_options(parts.size());
  std::set<std::string> used;
  for (const auto& [key, value] : options) {
    const auto dot = key.find('.');
    if (dot != std::string::npos) {
      const std::string prefix = key.substr(0, dot);
      bool found = false;
      for (std::size_t k = 0; k < parts.size(); ++k) {
        if (prefixes[k] == prefix) {
          component_options[k][key.substr(dot + 1)] = value;
          found = true;
        }
      }
      if (!found) throw InputError("option '" + key + "': no component '" + prefix + "' in model '" + name + "'");
      continue;
    }
    bool found = false;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const auto declared = make_single(parts[k], {})->description().options;
      for (const auto& o : declared) {
        if (o.name == key) {
          component_options[k][key] = value;
          found = true;
        }
      }
    }
    if (!found) throw InputError("no component of model '" + name + "' has option '" + key + "'");
  }
  std::vector<std::unique_ptr<Model>> components;
  for (std::size_t k = 0; k < parts.size(); ++k) components.push_back(make_single(parts[k], component_options[k]));
  return std::make_unique<CompositeModel>(std::move(components), prefixes);
}

std::vector<double> parameters_from_assignments(const ModelDescription& description,
                                                const std::map<std::string, double>& assignments) {
  std::vector<double> values = description.default_parameters();
  for (const auto& [key, value] : assignments) {
    const auto index = description.parameter_index(key);
    if (!index) {
      std::ostringstream msg;
      msg << "model '" << description.name << "' has no parameter '" << key << "' (parameters:";
      for (const auto& p : description.parameters) msg << ' ' << p.name;
      msg << ')';
      throw InputError(msg.str());
    }
    values[*index] = value;
  }
  check_parameters(description, values);
  return values;
}

}  // namespace roadbrdf
