// roadbrdf models [--json]: every model with its parameters and options.
#include <fmt/core.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::cli {

namespace {

nlohmann::json describe_json(const ModelDescription& d) {
  nlohmann::json j;
  j["name"] = d.name;
  j["summary"] = d.summary;
  j["citation"] = d.citation;
  j["reciprocal"] = d.reciprocal;
  j["energy_conserving"] = d.energy_conserving;
  j["non_negative"] = d.non_negative;
  j["has_delta"] = d.has_delta;
  j["parameters"] = nlohmann::json::array();
  for (const auto& p : d.parameters) {
    j["parameters"].push_back({{"name", p.name},
                               {"unit", p.unit},
                               {"description", p.description},
                               {"default", p.default_value},
                               {"lower", p.lower},
                               {"upper", p.upper},
                               {"spectral", p.spectral},
                               {"linear", p.linear}});
  }
  j["options"] = nlohmann::json::array();
  for (const auto& o : d.options) {
    j["options"].push_back(
        {{"name", o.name}, {"description", o.description}, {"values", o.values}, {"default", o.default_value}});
  }
  return j;
}

void run(bool as_json) {
  if (as_json) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& name : model_names()) all.push_back(describe_json(make_model(name)->description()));
    std::cout << all.dump(2) << '\n';
    return;
  }
  for (const auto& name : model_names()) {
    const ModelDescription d = make_model(name)->description();
    fmt::print("{}  {}\n", d.name, d.summary);
    fmt::print("    reciprocal: {}   energy conserving: {}{}\n", d.reciprocal ? "yes" : "no",
               d.energy_conserving ? "yes" : "no", d.has_delta ? "   ideal specular part: yes" : "");
    fmt::print("    {}\n", d.citation);
    for (const auto& p : d.parameters) {
      fmt::print("    {:<14} [{}] {:g} in [{:g}, {:g}]{}  {}\n", p.name, p.unit, p.default_value, p.lower, p.upper,
                 p.spectral ? ", spectral" : "", p.description);
    }
    for (const auto& o : d.options) {
      std::string values;
      for (const auto& v : o.values) values += (values.empty() ? "" : "|") + v;
      if (values.empty()) values = "integer";
      fmt::print("    --option {}={} (default {})  {}\n", o.name, values, o.default_value, o.description);
    }
  }
}

}  // namespace

void register_models_command(CLI::App& app) {
  auto* command = app.add_subcommand("models", "List every model with its parameters (name, unit, bounds, default)");
  static bool as_json = false;
  command->add_flag("--json", as_json, "Machine-readable output");
  command->callback([] { run(as_json); });
}

}  // namespace roadbrdf::cli
