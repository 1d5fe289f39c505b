// Where a command's BRDF comes from: the one resolver of "MODEL with `parameters` and `options`,
// FIT.json or MIX.json, with `fit` selecting an entry" that every command and both front ends call,
// and the kind of a source that may also be a measured dataset file.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// A spectral model and where it came from: `kind` "fit" (a fit file), "mix" (a MIX.json) or "model"
// (a model name); `entry` the fit chosen in a fit file (its model name, with its group in a grouped
// file), the method chosen in a MIX.json, or the model's name.
struct ResolvedModel {
  SpectralModel model;
  std::string kind;
  std::string entry;
};

// A fit file or a MIX.json as a spectral model: `selection` names the fit (fit file: its model, and
// group "oren-nayar,theta_i=40" in a grouped file) or the method (MIX.json); "" = the file's best.
ResolvedModel read_model_file(const std::string& path, const std::string& selection = "");
SpectralModel read_spectral_model_file(const std::string& path, const std::string& selection = "");

// The one resolver: `source` ending in ".json" is a fit file or a MIX.json, of which `fit` selects an
// entry (no `parameters` or `options` then); anything else is a model name (an alias or a composite
// NAME+NAME) with NAME=VALUE `parameters` (finite, within the model's bounds; defaults for the rest)
// and `options` (no `fit` then). FieldError naming `parameters`, `options` or `fit`; FileError for a
// bad file.
ResolvedModel resolve_model(const std::string& source, const std::vector<std::string>& parameters,
                            const std::vector<std::string>& options, const std::string& fit);

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

// The spectral model of a "fit" or "model" source (resolve_model's model).
SpectralModel spectral_model_of(const std::string& source, const std::vector<std::string>& parameters,
                                const std::vector<std::string>& options, const std::string& fit);

}  // namespace roadbrdf
