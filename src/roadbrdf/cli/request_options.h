// The command line of a request (core/request_fields.h): its options made from the request's field
// table, its errors spelt with the table's flags, and its notes and warnings printed the one way.
// A command made this way is its request table, its library function and a few lines that print the
// result (see cmd_luminaire.cpp).
#pragma once

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/length.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/core/request_fields.h"

namespace roadbrdf::cli {

namespace detail {

template <class Request>
std::string option_help(const RequestField<Request>& field) {
  std::string help(field.help);
  if (!field.unit.empty()) help += " [" + std::string(field.unit) + "]";
  return help;
}

// "NAME=VALUE" of a repeated option, split at its first '='; `field` names the option.
inline std::pair<std::string, std::string> assignment(const std::string& item, const std::string& field) {
  const auto eq = item.find('=');
  if (eq == std::string::npos || eq == 0) throw FieldError(field, "expects NAME=VALUE, got '" + item + "'");
  return {item.substr(0, eq), item.substr(eq + 1)};
}

// NAME=VALUE items as a map of `Value`s, `convert`ing each value; a name given twice is an error.
template <class Value, class Convert>
std::map<std::string, Value> assignments(const std::vector<std::string>& items, const std::string& field,
                                         Convert convert) {
  std::map<std::string, Value> out;
  for (const std::string& item : items) {
    auto [key, text] = assignment(item, field);
    if (out.count(key) != 0) throw FieldError(field + "." + key, "is given twice");
    out[key] = convert(text, field + "." + key);
  }
  return out;
}

template <class Request>
std::string flag_of_field(const std::string& field_name);

// Runs a conversion made while the command line is parsed; a FieldError is spelt with the flag.
template <class Request, class Conversion>
void converting(Conversion&& conversion) {
  try {
    conversion();
  } catch (const FieldError& e) {
    throw InputError(flag_of_field<Request>(e.field()) + ": " + e.detail());
  }
}

template <class Request>
void add_field(CLI::App* command, Request& request, const RequestField<Request>& field) {
  const std::string flag(field.flag);
  const std::string help = option_help(field);
  const std::string name(field.name);
  CLI::Option* option = nullptr;
  using Items = std::vector<std::string>;
  std::visit(
      [&](auto member) {
        using Value = std::remove_reference_t<decltype(request.*member)>;
        Value& value = request.*member;
        if constexpr (std::is_same_v<Value, bool>) {
          // A switch turns its default around: --no-sigma-weights sets use_sigma (true) to false.
          const bool given = !value;
          option = command->add_flag_callback(
              flag, [&value, given] { value = given; }, help);
        } else if constexpr (std::is_same_v<Value, std::optional<double>>) {
          option = command->add_option_function<double>(
              flag, [&value](const double& v) { value = v; }, help);
        } else if constexpr (std::is_same_v<Value, std::optional<long>>) {
          option = command->add_option_function<long>(
              flag, [&value](const long& v) { value = v; }, help);
        } else if constexpr (std::is_same_v<Value, std::optional<int>>) {
          option = command->add_option_function<int>(
              flag, [&value](const int& v) { value = v; }, help);
        } else if constexpr (std::is_same_v<Value, LengthMm>) {
          // A length with its unit ("60mm", "6cm", or millimetres without one).
          option = command->add_option_function<std::string>(
              flag,
              [&value, name](const std::string& text) {
                converting<Request>([&] { value = parse_length_mm(text, name); });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::vector<double>>) {
          // Lists of numbers in the one grammar of core/range.h; the request validates the values.
          option = command->add_option_function<std::string>(
              flag,
              [&value, name](const std::string& text) {
                converting<Request>([&] { value = parse_range_list(text, name); });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::map<std::string, std::string>>) {
          option = command->add_option_function<Items>(
              flag,
              [&value, name](const Items& items) {
                converting<Request>([&] {
                  value = assignments<std::string>(items, name,
                                                   [](const std::string& text, const std::string&) { return text; });
                });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::map<std::string, double>>) {
          option = command->add_option_function<Items>(
              flag,
              [&value, name](const Items& items) {
                converting<Request>([&] {
                  value = assignments<double>(items, name, [](const std::string& text, const std::string& key) {
                    double number = 0.0;
                    if (!parse_finite_double(text, number)) {
                      throw FieldError(key, "'" + text + "' is not a finite number");
                    }
                    return number;
                  });
                });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::map<std::string, std::pair<double, double>>>) {
          option = command->add_option_function<Items>(
              flag,
              [&value, name](const Items& items) {
                converting<Request>([&] {
                  value = assignments<std::pair<double, double>>(
                      items, name,
                      [](const std::string& text, const std::string& key) { return parse_interval(text, key); });
                });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::vector<std::pair<double, double>>>) {
          option = command->add_option_function<Items>(
              flag,
              [&value, name](const Items& items) {
                converting<Request>([&] {
                  value.clear();
                  for (const std::string& item : items) value.push_back(parse_interval(item, name));
                });
              },
              help);
        } else if constexpr (std::is_same_v<Value, std::optional<std::pair<double, double>>>) {
          option = command->add_option_function<std::string>(
              flag,
              [&value, name](const std::string& text) {
                converting<Request>([&] { value = parse_interval(text, name); });
              },
              help);
        } else if constexpr (std::is_same_v<Value, Source>) {
          option = command->add_option_function<std::string>(
              flag,
              [&value](const std::string& path) {
                value = Source{path, {}};
              },
              help);
        } else if constexpr (std::is_same_v<Value, Items>) {
          if (field.comma_separated) {
            option = command->add_option_function<Items>(
                flag, [&value](const Items& items) { value = split_name_list(items); }, help);
          } else {
            option = command->add_option(flag, value, help);
          }
        } else {
          option = command->add_option(flag, value, help);
          if constexpr (std::is_arithmetic_v<Value>) option->capture_default_str();
          if constexpr (std::is_same_v<Value, std::string>) {
            if (!value.empty()) option->capture_default_str();
          }
        }
      },
      field.member);
  // A repeated option takes one value each time: "--model a --model b", not "--model a b DATA".
  if (!field.positional() && option->get_expected_max() > 1) option->allow_extra_args(false);
  if (field.required) option->required();
}

}  // namespace detail

// The flag of a request field by Request's table ("options.distribution" -> "--option distribution"),
// or nothing when the table has no such row.
template <class Request>
std::optional<std::string> table_flag(const std::string& field_name) {
  const RequestField<Request>* field = find_field(Request::fields(), field_name);
  if (field == nullptr) return std::nullopt;
  std::string flag(field->long_flag());
  const auto dot = field_name.find('.');
  if (field->name != field_name && dot != std::string::npos) flag += " " + field_name.substr(dot + 1);
  return flag;
}

// Adds every field of Request's table to `command`, bound to `request`'s members, and records the
// table as one that spells the command's fields (cli/common.h add_field_table).
template <class Request>
void add_request_options(CLI::App* command, Request& request) {
  for (const RequestField<Request>& field : Request::fields()) detail::add_field(command, request, field);
  add_field_table(command, table_flag<Request>);
}

// The flag of a request field by Request's table; a field that is not in the table is spelt by the
// plain rule (cli/common.h plain_flag).
template <class Request>
std::string flag_of(const std::string& field_name) {
  return detail::flag_of_field<Request>(field_name);
}

template <class Request>
std::string detail::flag_of_field(const std::string& field_name) {
  return table_flag<Request>(field_name).value_or(plain_flag(field_name));
}

// A library message with its `field` references spelt as the table's flags.
template <class Request>
std::string with_flags(const std::string& message) {
  return replace_field_references(message, [](const std::string& field) { return flag_of<Request>(field); });
}

// Runs `task` and rethrows a FieldError of the request as an InputError spelt with the table's
// flags (main prints it as "roadbrdf: error: --flag: detail").
template <class Request, class Task>
void run_request(Task&& task) {
  try {
    task();
  } catch (const FieldError& e) {
    throw InputError(flag_of<Request>(e.field()) + ": " + with_flags<Request>(e.detail()));
  } catch (const FileError&) {
    throw;  // located in a file: nothing of the request to spell
  } catch (const InputError& e) {
    throw InputError(with_flags<Request>(e.what()));
  }
}

// "roadbrdf: note: ..." and "roadbrdf: warning: ..." lines on standard error, fields spelt as flags.
template <class Request>
void print_diagnostics(const Diagnostics& diagnostics) {
  for (const Diagnostic& d : diagnostics.notes)
    fmt::print(stderr, "roadbrdf: note: {}\n", with_flags<Request>(d.message));
  for (const Diagnostic& d : diagnostics.warnings) {
    fmt::print(stderr, "roadbrdf: warning: {}\n", with_flags<Request>(d.message));
  }
}

// A command that is its request and its task alone: the request's options and --json; the task's
// result (with `diagnostics`, `to_json()` and `summary_text()`) printed after its notes and warnings,
// as its summary text or, with --json, as the JSON document Python's roadbrdf.Result holds too.
template <class Request, class Task>
void add_request_command(CLI::App& app, const std::string& name, const std::string& description,
                         const std::string& json_help, Task task) {
  static Request request;
  static bool as_json = false;
  auto* command = app.add_subcommand(name, description);
  add_request_options(command, request);
  command->add_flag("--json", as_json, json_help);
  command->callback([task] {
    run_request<Request>([&task] {
      const auto result = task(request);
      print_diagnostics<Request>(result.diagnostics);
      AtomicFile out("-");
      if (as_json) {
        write_json(out.stream(), result.to_json(), 2);
        out.stream() << '\n';
      } else {
        out.stream() << result.summary_text();
      }
      out.commit();
    });
  });
}

}  // namespace roadbrdf::cli
