// A model's metadata as JSON: the one serialisation used by `roadbrdf models --json` and the
// Python module (roadbrdf.models(), Model.description).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

// Keys: name, summary, citation, reciprocal, energy_conserving, non_negative, has_delta, grazing_zero,
// reduces_to [[name, values], ...],
// isotropic, isotropic_when_equal [[name, name], ...], parameters [{name, unit, description, default, lower, upper,
// spectral, linear}], options [{name, description, values, default}], option_values {name: value}.
nlohmann::json description_to_json(const ModelDescription& description);

// A model alias (ModelAlias). Keys: name, model, description, citation, options {name: value}.
nlohmann::json alias_to_json(const ModelAlias& alias);

// "yes", "no" or "where `nu` = `nv`" (for the help texts and docs/models.md).
std::string isotropy_summary(const ModelDescription& description);

}  // namespace roadbrdf
