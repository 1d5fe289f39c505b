#include "roadbrdf/cli/parse_errors.h"

#include <charconv>
#include <string_view>
#include <vector>

#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf::cli {

namespace {

std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> flag_names(CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : command.get_options([](const CLI::Option*) { return true; })) {
    for (const auto& l : opt->get_lnames()) names.push_back("--" + l);
    for (const auto& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

CLI::App* find_command(CLI::App& app, std::string_view name) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    if (sub->check_name(std::string(name))) return sub;
  }
  return nullptr;
}

std::string command_label(const CLI::App& app, const CLI::App& command) {
  return &command == &app ? std::string("roadbrdf") : "roadbrdf " + command.get_name();
}

}  // namespace

std::string explain_parse_error(CLI::App& app, int argc, char** argv, const CLI::ParseError& error) {
  CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string_view token = argv[i];
    if (token == "--") break;
    if (current->get_prefix_command()) break;  // `plot`: its own parser reports
    if (token.size() > 1 && token.front() == '-' && !is_number_text(token)) {
      // "--name=value" and "-pVALUE" name the flags "--name" and "-p".
      std::string name(token.substr(0, token.find('=')));
      if (name.rfind("--", 0) != 0) name = name.substr(0, 2);
      if (current->get_option_no_throw(name) == nullptr && !(current == &app && name == "--version")) {
        return "unknown option '" + name + "' of '" + command_label(app, *current) + "'" +
               did_you_mean(name, flag_names(*current)) + "; see '" + command_label(app, *current) + " --help'";
      }
      continue;
    }
    if (current == &app) {
      CLI::App* sub = find_command(app, token);
      if (sub == nullptr) {
        return "unknown command '" + std::string(token) + "'" + did_you_mean(token, command_names(app)) +
               "; see 'roadbrdf --help'";
      }
      current = sub;
    }
  }
  if (current == &app && app.get_subcommands().empty() &&
      std::string_view(error.what()).find("subcommand") != std::string_view::npos) {
    return "a command is required; see 'roadbrdf --help'";
  }
  std::string message = error.what();
  // CLI11 prefixes a validation message with the option's name, empty for hidden options (a refused
  // old spelling, whose message names itself).
  if (message.rfind(": ", 0) == 0) message.erase(0, 2);
  return message + "; see '" + command_label(app, *current) + " --help'";
}

}  // namespace roadbrdf::cli
