#include "roadbrdf/models/description_json.h"

namespace roadbrdf {

nlohmann::json alias_to_json(const ModelAlias& a) {
  return {{"name", a.name},
          {"model", a.model},
          {"description", a.description},
          {"citation", a.citation},
          {"options", a.options}};
}

nlohmann::json description_to_json(const ModelDescription& d) {
  nlohmann::json j;
  j["name"] = d.name;
  j["summary"] = d.summary;
  j["citation"] = d.citation;
  j["reciprocal"] = d.reciprocal;
  j["energy_conserving"] = d.energy_conserving;
  j["non_negative"] = d.non_negative;
  j["has_delta"] = d.has_delta;
  j["mirror_lobe"] = d.mirror_lobe;
  j["grazing_zero"] = d.grazing_zero;
  j["reduces_to"] = nlohmann::json::array();
  for (const auto& [simpler, values] : d.reduces_to) j["reduces_to"].push_back({simpler, values});
  j["isotropic"] = d.isotropic;
  j["isotropic_when_equal"] = nlohmann::json::array();
  for (const auto& [first, second] : d.isotropic_when_equal) j["isotropic_when_equal"].push_back({first, second});
  j["parameters"] = nlohmann::json::array();
  for (std::size_t k = 0; k < d.parameters.size(); ++k) {
    const ParameterInfo& p = d.parameters[k];
    const auto [physical_lower, physical_upper] = d.physical_range(k);
    j["parameters"].push_back({{"name", p.name},
                               {"unit", p.unit},
                               {"description", p.description},
                               {"default", p.default_value},
                               {"lower", p.lower},
                               {"upper", p.upper},
                               {"physical_bounds", {physical_lower, physical_upper}},
                               {"spectral", p.spectral},
                               {"linear", p.linear}});
  }
  j["options"] = nlohmann::json::array();
  for (const auto& o : d.options) {
    j["options"].push_back(
        {{"name", o.name}, {"description", o.description}, {"values", o.values}, {"default", o.default_value}});
  }
  j["option_values"] = d.option_values;
  return j;
}

std::string isotropy_summary(const ModelDescription& d) {
  if (d.isotropic) return "yes";
  if (d.isotropic_when_equal.empty()) return "no";
  std::string pairs;
  for (const auto& [first, second] : d.isotropic_when_equal) {
    pairs += (pairs.empty() ? "" : ", ") + ("`" + first + "` = `" + second + "`");
  }
  return "where " + pairs;
}

}  // namespace roadbrdf
