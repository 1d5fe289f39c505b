// Helpers shared by the sub-commands: the dataset output, the spelling of request fields as flags, common flags.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/parameters.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/model.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::cli {

// A dataset command's request, its `output` standard output ("-") by default.
template <typename Request>
Request with_standard_output(Request request) {
  if (request.output.empty()) request.output = "-";
  return request;
}
// The warning of the BRDF values a written dataset is missing (`path` "" = standard output).
void warn_missing_values(const SpectralDataset& data, const std::string& path);

// Where a command's report (tables, notes) goes: standard error when its output file is standard
// output ("-"), so that the two never mix; standard output otherwise.
std::FILE* report_stream(const std::string& output);

// Lists of numbers ("D", "D1,D2,...", "A:B:STEP" and mixes) are parsed by parse_range_list
// (core/range.h), the one grammar of every command and of Python.

// The spelling of request fields on the command line: each command made from request tables
// (core/request_fields.h) records them (add_field_table; cli/request_options.h does it for
// add_request_options and cli/dataset_flags.h for the dataset-reading rows). A field is spelt by
// the first table of the running command that has its row: the row's long flag, with the part after
// a dot kept ("fixed.roughness" -> "--fix roughness", "parameters" -> "--parameter"). A field of no
// table is spelt by the plain rule, which only fits a field named exactly like its flag:
// "sun_zenith" -> "--sun-zenith" (plain_flag). A field that is already a flag ("--grid") is kept.
using FieldSpelling = std::function<std::optional<std::string>(const std::string& field)>;
void add_field_table(const CLI::App* command, FieldSpelling spelling);
std::string plain_flag(const std::string& field);
// `field` spelt by the tables of `app`'s running command (the parsed subcommand), else plain_flag.
std::string flag_for_field(const CLI::App& app, const std::string& field);
// A library message with its field references (`field`, core/error.h) replaced by their flags:
// "pass `delimiter` ';'" -> "pass --delimiter ';'". Backquoted text that is not a field name (it
// holds a space or a character other than a-z, 0-9, '_', '.', '-') is kept as is.
std::string name_flags(const CLI::App& app, const std::string& message);
// The same with another spelling of fields (cli/request_options.h: a request table's flags).
std::string replace_field_references(const std::string& message,
                                     const std::function<std::string(const std::string&)>& flag);

// The old spelling --fit-model alone, refused (for a command whose --fit comes from its request table).
void refuse_fit_model_flag(CLI::App* command);
// --quiet: no progress bar (core/progress.h; it is only drawn when standard error is a terminal).
void add_quiet_flag(CLI::App* command, bool& quiet);

}  // namespace roadbrdf::cli
