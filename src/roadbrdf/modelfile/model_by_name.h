// A model given by its name, options and parameter values, checked as the resolver checks a model
// argument (modelfile/model_source.h resolve_model), for callers that hold the values as numbers
// (an installation file's surface, where they are JSON numbers).
#pragma once

#include <map>
#include <string>

#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// The model `name` (an alias or a composite NAME+NAME) with `options`, its parameters at their
// defaults but for `parameters`, each within the model's bounds. FieldError naming `options` (an
// unknown option or value) or `parameters` (an unknown name, listing the model's, or a value out of
// bounds).
SpectralModel spectral_model_with(const std::string& name, const std::map<std::string, double>& parameters,
                                  const OptionSet& options);

}  // namespace roadbrdf
