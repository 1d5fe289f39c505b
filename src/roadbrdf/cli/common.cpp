#include "roadbrdf/cli/common.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::cli {

namespace {
std::pair<std::string, std::string> split_assignment(const std::string& item, const std::string& what) {
  const auto eq = item.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(what + " expects NAME=VALUE, got '" + item + "'");
  }
  return {item.substr(0, eq), item.substr(eq + 1)};
}
}  // namespace

std::map<std::string, double> parse_numeric_assignments(const std::vector<std::string>& items,
                                                        const std::string& what) {
  std::map<std::string, double> result;
  for (const auto& item : items) {
    auto [name, text] = split_assignment(item, what);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value)) {
      throw InputError(what + " " + name + ": '" + text + "' is not a finite number");
    }
    if (result.count(name)) throw InputError(what + " " + name + " is given twice");
    result[name] = value;
  }
  return result;
}

OptionSet parse_option_assignments(const std::vector<std::string>& items, const std::string& what) {
  OptionSet result;
  for (const auto& item : items) {
    auto [name, value] = split_assignment(item, what);
    if (result.count(name)) throw InputError(what + " " + name + " is given twice");
    result[name] = value;
  }
  return result;
}

ModelWithParameters model_from_command_line(const std::string& name, const std::vector<std::string>& parameter_items,
                                            const std::vector<std::string>& option_items) {
  ModelWithParameters m;
  m.model = make_model(name, parse_option_assignments(option_items, "--option"));
  m.parameters = parameters_from_assignments(m.model->description(), parse_numeric_assignments(parameter_items, "-p"));
  return m;
}

SpectralModel spectral_model_from_command_line(const std::string& argument,
                                               const std::vector<std::string>& parameter_items,
                                               const std::vector<std::string>& option_items,
                                               const std::string& fit_model) {
  if (is_fit_file_argument(argument)) {
    if (!parameter_items.empty() || !option_items.empty()) {
      throw InputError("-p/--option cannot be combined with a fit file ('" + argument + "')");
    }
    return mixing::read_spectral_model_file(argument, fit_model);  // a fit file or a MIX.json
  }
  ModelWithParameters m = model_from_command_line(argument, parameter_items, option_items);
  return SpectralModel(std::shared_ptr<const Model>(std::move(m.model)), std::move(m.parameters));
}

void add_model_flags(CLI::App* command, std::vector<std::string>& parameter_items,
                     std::vector<std::string>& option_items) {
  command->add_option("-p,--parameter", parameter_items, "Model parameter NAME=VALUE (repeatable); defaults otherwise")
      ->allow_extra_args(false);
  command->add_option("--option", option_items, "Model option NAME=VALUE (repeatable), e.g. distribution=ggx")
      ->allow_extra_args(false);
}

}  // namespace roadbrdf::cli
