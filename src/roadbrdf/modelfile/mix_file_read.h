// Reading a MIX.json (written by mixing/mix_file.h write_mix_file, whose header describes the format)
// back as a spectral model: one mixing method as a MixtureModel (models/mixture_model.h) of its
// end-member models with its parameter table. It sits below albedo, photometry, surface and lighting
// so that each loads a mixture the way it loads a fit file.
#pragma once

#include <string>

#include "roadbrdf/core/json_input.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// A method of a MIX.json and its name ("areal", "hapke", ...).
struct MixFileEntry {
  SpectralModel model;
  std::string entry;
};

// Read one method of a MIX.json as a spectral model ("" = the file's "best", else its first method).
// End-member models are rebuilt with make_model(model, options). Throws FileError.
SpectralModel read_mix_file(const std::string& path, const std::string& method = "");
MixFileEntry read_mix_file_entry(const std::string& path, const std::string& method = "");

// The same from the parsed document, `name` standing for the file in error messages.
MixFileEntry mix_file_entry(const Json& document, const std::string& name, const std::string& method = "");

// True when a JSON document is a MIX.json ("format": "roadbrdf-mix"), or a JSON file is one.
bool is_mix_document(const Json& document);
bool is_mix_file(const std::string& path);

}  // namespace roadbrdf
