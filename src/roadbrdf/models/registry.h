// Look-up of models by their command-line names, composites included ("a+b").
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/models/model.h"

namespace roadbrdf {

// Names of the single (non-composite) models, in display order.
std::vector<std::string> model_names();

// The other names models are known by (ModelAlias), in display order. make_model accepts them
// wherever it accepts a model name, composites included.
std::vector<ModelAlias> model_aliases();

// Create a model from its name. A name with '+' is a composite (see composite.h); its options
// may be given as "component.option" or, when unambiguous, as plain "option" (applied to every
// component that declares it). Throws InputError for an unknown model or option.
std::unique_ptr<Model> make_model(const std::string& name, const OptionSet& options = {});

// Parameter vector from "name -> value" assignments: defaults for the rest. Throws InputError
// for an unknown name (listing the model's parameters) or a value outside the bounds.
std::vector<double> parameters_from_assignments(const ModelDescription& description,
                                                const std::map<std::string, double>& assignments);

}  // namespace roadbrdf
