// Reading a fit file (FIT.json, written by fitting/fit_file.h write_fit_file) back as a spectral model.
// The format is described in fitting/fit_file.h next to its writer; the reader sits here, below every
// module that takes a fitted model (albedo, photometry, mixing, surface, lighting), so that none of
// them links the fitting module to read one.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

// Which fit of a fit file (request field `fit`): comma-separated items, a model name and
// COLUMN=DEGREES for the columns the file is grouped by ("oren-nayar,theta_i=40", "theta_i=40").
// No model: the file's best.
struct FitSelector {
  std::string model;
  std::vector<std::pair<std::string, double>> group;
};
// Throws FieldError("fit", ...).
FitSelector parse_fit_selector(const std::string& text);

// The position in a fit file's "fits" of the fit `selection` chooses (parse_fit_selector; default:
// the file's "best"): the fit of that model whose group matches the selection's columns, exactly one.
// The one rule of "which fit of a FIT.json" for every reader and front end. Throws FieldError("fit",
// ...) naming the choices, FileError for a model the file does not hold.
std::size_t select_fit(const JsonNode& root, const std::string& selection);

// A fit of a fit file and which one it is: `entry` is the fit's model name, followed by its group
// ("oren-nayar,theta_i=40") in a grouped file.
struct FitFileEntry {
  SpectralModel model;
  std::string entry;
};

// A fit file as a spectral model: the fit chosen by `selection` (parse_fit_selector; default: the
// file's "best"). In a grouped file (version 2) the selection must name one group. Throws FileError /
// InputError (FieldError "fit" for a selection matching no fit or several).
SpectralModel read_fit_file(const std::string& path, const std::string& selection = "");
FitFileEntry read_fit_file_entry(const std::string& path, const std::string& selection = "");
// Several fits of one fit file, one per selection (as read_fit_file selects), from one parse of the
// file: a fit file of several models at a few thousand wavelengths takes longer to parse than to read
// a model out of, so a caller that wants several models of it asks for them at once.
std::vector<SpectralModel> read_fit_file_models(const std::string& path, const std::vector<std::string>& selections);
// What a fit file (or a mix file, read as a model the same way) may be: at most 256 MiB (a fit of a
// few models at a few thousand wavelengths with covariances takes a few MB).
InputLimits fit_file_limits();
// The same from a fit file's content held in memory (Python: a fit file as a dict): `name` stands
// for the file in error messages, which name the JSON key as for a file.
SpectralModel parse_fit_file(const std::string& json_text, const std::string& name, const std::string& selection = "");
FitFileEntry parse_fit_file_entry(const std::string& json_text, const std::string& name,
                                  const std::string& selection = "");
// The same from the parsed document (model_source.h read_model_file parses a file once to tell a fit
// file from a MIX.json).
FitFileEntry fit_file_entry(const Json& document, const std::string& name, const std::string& selection = "");

// The parameter covariance per wavelength (SpectralModel::parameter_covariance) of a fit object of a
// fit file, or of a method of a MIX.json (the same keys), from its "stderr" {name: [per wavelength]}
// and "correlation" [per wavelength: p x p]: cov_ab = r_ab s_a s_b, 0 for a parameter in "fixed", NaN
// where either is null (undefined). Empty when the object has neither, or orders its parameters
// ("parameter_order") otherwise than `description`. `m` wavelengths. Throws FileError at a bad shape.
std::vector<double> read_parameter_covariance(const JsonNode& fit, const ModelDescription& description, std::size_t m);

// True if `argument` names a fit file or a MIX.json rather than a model (ends in ".json").
bool is_fit_file_argument(const std::string& argument);

}  // namespace roadbrdf
