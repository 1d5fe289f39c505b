#include "roadbrdf/cli/common.h"

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <iostream>
#include <optional>
#include <system_error>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::cli {

std::string plain_flag(const std::string& field) {
  if (field.empty() || field.front() == '-') return field;
  const auto dot = field.find('.');
  std::string flag = "--" + field.substr(0, dot);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return dot == std::string::npos ? flag : flag + " " + field.substr(dot + 1);
}

namespace {
// The tables each command was made from, in the order they were added.
std::map<const CLI::App*, std::vector<FieldSpelling>>& field_tables() {
  static std::map<const CLI::App*, std::vector<FieldSpelling>> tables;
  return tables;
}
}  // namespace

void add_field_table(const CLI::App* command, FieldSpelling spelling) {
  field_tables()[command].push_back(std::move(spelling));
}

std::string flag_for_field(const CLI::App& app, const std::string& field) {
  for (const CLI::App* command : app.get_subcommands()) {
    const auto tables = field_tables().find(command);
    if (tables == field_tables().end()) continue;
    for (const FieldSpelling& table : tables->second) {
      if (std::optional<std::string> flag = table(field)) return *flag;
    }
  }
  return plain_flag(field);
}

std::string replace_field_references(const std::string& message,
                                     const std::function<std::string(const std::string&)>& flag) {
  auto is_field_character = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
  };
  std::string out;
  std::size_t at = 0;
  while (at < message.size()) {
    const std::size_t open = message.find('`', at);
    const std::size_t close = open == std::string::npos ? std::string::npos : message.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string inside = message.substr(open + 1, close - open - 1);
    const bool field = !inside.empty() && inside.front() >= 'a' && inside.front() <= 'z' &&
                       std::all_of(inside.begin(), inside.end(), is_field_character);
    out += message.substr(at, open - at);
    out += field ? flag(inside) : message.substr(open, close - open + 1);
    at = close + 1;
  }
  return out + message.substr(std::min(at, message.size()));
}

std::string name_flags(const CLI::App& app, const std::string& message) {
  return replace_field_references(message, [&app](const std::string& field) { return flag_for_field(app, field); });
}

void add_quiet_flag(CLI::App* command, bool& quiet) {
  command->add_flag("--quiet", quiet, "No progress bar (it is only drawn on a terminal anyway)");
}

void refuse_fit_model_flag(CLI::App* command) {
  static std::string refused;
  command->add_option("--fit-model", refused, "")->group("")->each([](const std::string&) {
    throw CLI::ValidationError("--fit-model", "renamed: use --fit NAME");
  });
}

void warn_missing_values(const SpectralDataset& data, const std::string& path) {
  if (const std::size_t missing = missing_value_count(data); missing > 0) {
    fmt::print(stderr,
               "roadbrdf: warning: {}: {} of {} BRDF values are missing (written as nan: not measured, never "
               "filled in)\n",
               path.empty() ? std::string("-") : path, missing, data.brdf.size());
  }
}

std::FILE* report_stream(const std::string& output) { return is_standard_stream(output) ? stderr : stdout; }

}  // namespace roadbrdf::cli
