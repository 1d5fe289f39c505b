// Where a command's BRDF comes from: a fit file or a MIX.json, a model name with NAME=VALUE
// parameters and options, or a measured dataset file. Fit files and MIX.json files are read by the
// reader the caller passes (mixing/mix_file.h read_spectral_model_file: mixing sits above io and
// photometry), so that requests of those modules resolve their sources themselves.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// Reads a fit file or a MIX.json into a spectral model: its path and selection (a fit's model or a
// mixing method; "" = the file's best).
using SpectralModelFileReader = std::function<SpectralModel(const std::string& path, const std::string& selection)>;

// How a source is taken: "fit" (a file ending in .json: a fit file or a MIX.json), "model" (a model
// name, an alias or a composite NAME+NAME) or "data" (any other file).
std::string source_kind(const std::string& source);

// "NAME=VALUE" items of the request field `field` as a map (FieldError for a malformed item or a
// repeated name).
std::map<std::string, std::string> assignments(const std::vector<std::string>& items, const std::string& field);

// A model and its parameters from its name, NAME=VALUE parameters (finite numbers within the
// model's bounds, defaults for the rest) and options: FieldError naming `parameters` or `options`.
SpectralModel spectral_model_from_assignments(const std::string& name, const std::vector<std::string>& parameters,
                                              const std::vector<std::string>& options);

// The spectral model of a "fit" or "model" source.
SpectralModel spectral_model_of(const std::string& source, const std::vector<std::string>& parameters,
                                const std::vector<std::string>& options, const std::string& fit,
                                const SpectralModelFileReader& read_model_file);

}  // namespace roadbrdf
