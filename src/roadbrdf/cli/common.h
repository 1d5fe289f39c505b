// Helpers shared by the sub-commands: NAME=VALUE parsing and model construction.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/core/parameters.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/model.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::cli {

// "name=value" strings to a map; `what` names the flag in errors (e.g. "-p").
std::map<std::string, double> parse_numeric_assignments(const std::vector<std::string>& items, const std::string& what);
OptionSet parse_option_assignments(const std::vector<std::string>& items, const std::string& what);

// A model with one parameter set, as given on the command line: MODEL -p ... --option ...
struct ModelWithParameters {
  std::unique_ptr<Model> model;
  std::vector<double> parameters;
};
ModelWithParameters model_from_command_line(const std::string& name, const std::vector<std::string>& parameter_items,
                                            const std::vector<std::string>& option_items);

// A model or a fit file, as accepted by every command that takes "MODEL -p ... | FIT.json": the
// library's one resolver (modelfile/model_source.h resolve_model); `fit_model` selects a fit or a
// mixing method inside the file (default: the file's best).
SpectralModel spectral_model_from_command_line(const std::string& argument,
                                               const std::vector<std::string>& parameter_items,
                                               const std::vector<std::string>& option_items,
                                               const std::string& fit_model = "");

// Write a dataset to `path` (atomically), or to standard output when `path` is empty or "-";
// `format` is a name of kDatasetFormatNames (io/dataset_io.h), read as the request field `format_field`.
void write_dataset_output(const SpectralDataset& data, const std::string& path, const std::string& format,
                          const std::string& format_field = "format");

// Where a command's report (tables, notes) goes: standard error when its output file is standard
// output ("-"), so that the two never mix; standard output otherwise.
std::FILE* report_stream(const std::string& output);

// A finite number; `what` names the flag in errors. Throws InputError.
double parse_number(const std::string& text, const std::string& what);

// Names from repeatable, comma-separated options ("--group-by theta_i,phi_i" or given twice), spaces dropped.
std::vector<std::string> split_commas(const std::vector<std::string>& items);
// Lists of numbers ("D", "D1,D2,...", "A:B:STEP" and mixes) are parsed by parse_range_list
// (core/range.h), the one grammar of every command and of Python.

// The flag of a library request field (FieldError::field): "multistart" -> "--multistart",
// "fixed.roughness" -> "--fix roughness", "options.distribution" -> "--option distribution".
// A field that is already a flag ("--sun-zenith") is kept.
std::string flag_for_field(const std::string& field);
// A library message with its field references (`field`, core/error.h) replaced by their flags:
// "pass `delimiter` ';'" -> "pass --delimiter ';'". Backquoted text that is not a field name (it
// holds a space or a character other than a-z, 0-9, '_', '.', '-') is kept as is.
std::string name_flags(const std::string& message);
// The same with another spelling of fields (cli/request_options.h: a request table's flags).
std::string replace_field_references(const std::string& message,
                                     const std::function<std::string(const std::string&)>& flag);

// Adds "--fit NAME": which fit of a fit file (its model name) or which method of a MIX.json, the
// option name every command uses; the old spelling --fit-model is refused with a message naming --fit.
void add_fit_flag(CLI::App* command, std::string& fit);
// The old spelling --fit-model alone, refused (for a command whose --fit comes from its request table).
void refuse_fit_model_flag(CLI::App* command);
// --quiet: no progress bar (core/progress.h; it is only drawn when standard error is a terminal).
void add_quiet_flag(CLI::App* command, bool& quiet);

// Adds the usual "-p NAME=VALUE" and "--option NAME=VALUE" flags to a sub-command.
void add_model_flags(CLI::App* command, std::vector<std::string>& parameter_items,
                     std::vector<std::string>& option_items);

}  // namespace roadbrdf::cli
