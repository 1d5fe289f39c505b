// Python's side of a request (core/request_fields.h): arguments converted into the request's
// members by its field table, the docstring made from the same table, and a task's result handed
// over as a roadbrdf.Result (value, notes, warnings, summary) with its warnings issued.
//
//   m.def("luminaire", [](py::args args, py::kwargs kwargs) {
//     const auto request = request_from_arguments<LuminaireRequest>(args, kwargs);
//     const auto result = lighting::luminaire_summary(request);
//     return python_result(result.to_json(), result.diagnostics, result.summary_text());
//   }, request_docstring<LuminaireRequest>("Summary of a luminaire photometry file."));
//
// Positional arguments fill the table's positional fields in order (INSTALLATION, ...), keyword
// arguments any field by its name. A wrong type or value is a roadbrdf.InputError (FieldError)
// naming the argument; an unknown keyword is a TypeError with the nearest valid name.
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "binding.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/request_fields.h"

namespace roadbrdf::python {

namespace request_detail {

inline std::string type_name(const pybind11::handle& value) {
  return pybind11::str(pybind11::type::handle_of(value).attr("__name__"));
}

inline double number(const pybind11::handle& value, const std::string& field) {
  namespace py = pybind11;
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value))) {
    // numpy scalars are accepted through __float__.
    if (!py::hasattr(value, "__float__") || py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value)) {
      throw FieldError(field, "expected a number, got " + type_name(value));
    }
  }
  const double x = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  if (!std::isfinite(x)) throw FieldError(field, "expected a finite number");
  return x;
}

inline std::string text(const pybind11::handle& value, const std::string& field) {
  namespace py = pybind11;
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    const py::object path = py::module_::import("os").attr("fspath")(value);
    if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  }
  throw FieldError(field, "expected a string or a path, got " + type_name(value));
}

// A Python int within the range of `Integer` (bool is not an integer here).
template <class Integer>
Integer integer(const pybind11::handle& value, const std::string& field) {
  namespace py = pybind11;
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value)) {
    throw FieldError(field, "expected an integer, got " + type_name(value));
  }
  const py::int_ big = py::reinterpret_borrow<py::int_>(value);
  if (big < py::int_(std::numeric_limits<Integer>::min())) {
    throw FieldError(field, "expected an integer of at least " + std::to_string(std::numeric_limits<Integer>::min()));
  }
  if (big > py::int_(std::numeric_limits<Integer>::max())) {
    throw FieldError(field, "expected an integer of at most " + std::to_string(std::numeric_limits<Integer>::max()));
  }
  return big.cast<Integer>();
}

template <class Value>
void assign(Value& into, const pybind11::handle& value, const std::string& field) {
  namespace py = pybind11;
  if constexpr (std::is_same_v<Value, bool>) {
    if (!py::isinstance<py::bool_>(value)) throw FieldError(field, "expected True or False, got " + type_name(value));
    into = value.cast<bool>();
  } else if constexpr (std::is_same_v<Value, double>) {
    into = number(value, field);
  } else if constexpr (std::is_same_v<Value, int> || std::is_same_v<Value, long> ||
                       std::is_same_v<Value, std::uint64_t>) {
    into = integer<Value>(value, field);
  } else if constexpr (std::is_same_v<Value, std::optional<long>>) {
    if (value.is_none()) {
      into.reset();
    } else {
      into = integer<long>(value, field);
    }
  } else if constexpr (std::is_same_v<Value, std::optional<int>>) {
    if (value.is_none()) {
      into.reset();
    } else {
      into = integer<int>(value, field);
    }
  } else if constexpr (std::is_same_v<Value, LengthMm>) {
    // Millimetres as a number (the command line's text with a unit is its own spelling).
    if (value.is_none()) {
      into.reset();
    } else {
      into = number(value, field);
    }
  } else if constexpr (std::is_same_v<Value, std::string>) {
    into = value.is_none() ? std::string() : text(value, field);  // None: not given (no file, no name)
  } else if constexpr (std::is_same_v<Value, std::optional<double>>) {
    if (value.is_none()) {
      into.reset();
    } else {
      into = number(value, field);
    }
  } else if constexpr (std::is_same_v<Value, std::vector<std::string>>) {
    into.clear();
    if (value.is_none()) return;
    if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) {
      into.push_back(text(value, field));
      return;
    }
    if (!py::isinstance<py::sequence>(value)) throw FieldError(field, "expected a string or a list of strings");
    for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) into.push_back(text(item, field));
  } else if constexpr (std::is_same_v<Value, std::vector<double>>) {
    into = values_argument(py::reinterpret_borrow<py::object>(value), field);
  } else if constexpr (std::is_same_v<Value, Source>) {
    // A file, or the content itself (a dict or list, as its JSON text; named `<field>` in messages).
    if (value.is_none()) {
      into = Source{};
    } else if (py::isinstance<py::dict>(value) || py::isinstance<py::list>(value)) {
      into = Source{"<" + field + ">", py::module_::import("json").attr("dumps")(value).cast<std::string>()};
    } else {
      into = Source{text(value, field), {}};
    }
  } else if constexpr (std::is_same_v<Value, std::vector<std::pair<double, double>>>) {
    into = intervals_argument(py::reinterpret_borrow<py::object>(value), field);
  } else if constexpr (std::is_same_v<Value, std::optional<std::pair<double, double>>>) {
    // One (lower, upper) pair or "LOWER:UPPER"; None: not given.
    into.reset();
    if (value.is_none()) return;
    const auto pairs = intervals_argument(py::reinterpret_borrow<py::object>(value), field);
    if (pairs.size() != 1) throw FieldError(field, "expected one 'LOWER:UPPER' or (lower, upper) pair");
    into = pairs.front();
  } else {
    // A dict {name: value}; None is an empty one. Model options are names (any value as its text),
    // numbers are numbers, bounds (lower, upper) pairs or "LOWER:UPPER".
    into.clear();
    if (value.is_none()) return;
    if (!py::isinstance<py::dict>(value)) {
      throw FieldError(field, "expected a dict {name: value}, got " + type_name(value));
    }
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      const std::string name = py::str(key);
      const std::string at = field + "." + name;
      if constexpr (std::is_same_v<Value, std::map<std::string, std::string>>) {
        into[name] = py::str(item).cast<std::string>();
      } else if constexpr (std::is_same_v<Value, std::map<std::string, double>>) {
        into[name] = number(item, at);
      } else {
        static_assert(std::is_same_v<Value, std::map<std::string, std::pair<double, double>>>);
        const auto pair = intervals_argument(py::reinterpret_borrow<py::object>(item), at);
        if (pair.size() != 1) throw FieldError(at, "expected (lower, upper)");
        into[name] = pair.front();
      }
    }
  }
}

}  // namespace request_detail

// The request from a Python call's arguments (see above). Fields not given keep their defaults.
template <class Request>
Request request_from_arguments(const pybind11::args& args, const pybind11::kwargs& kwargs) {
  namespace py = pybind11;
  Request request;
  const RequestFields<Request> fields = Request::fields();
  std::vector<const RequestField<Request>*> positionals;
  for (const RequestField<Request>& field : fields) {
    if (field.positional()) positionals.push_back(&field);
  }
  if (args.size() > positionals.size()) {
    throw py::type_error("takes " + std::to_string(positionals.size()) + " positional argument(s) but " +
                         std::to_string(args.size()) + " were given");
  }
  std::vector<std::string> given;
  const auto set = [&](const RequestField<Request>& field, const py::handle& value) {
    const std::string name(field.name);
    for (const std::string& g : given) {
      if (g == name) throw py::type_error("got multiple values for argument '" + name + "'");
    }
    given.push_back(name);
    std::visit([&](auto member) { request_detail::assign(request.*member, value, name); }, field.member);
    if (field.comma_separated) {
      if (auto list = std::get_if<std::vector<std::string> Request::*>(&field.member)) {
        request.*(*list) = split_name_list(request.*(*list));
      }
    }
  };
  for (std::size_t k = 0; k < args.size(); ++k) set(*positionals[k], args[k]);
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const RequestField<Request>* field = nullptr;
    for (const RequestField<Request>& f : fields) {
      if (f.name == name) field = &f;
    }
    if (field == nullptr) {
      std::vector<std::string> names;
      for (const RequestField<Request>& f : fields) names.emplace_back(f.name);
      throw py::type_error("unexpected keyword argument '" + name + "'" + did_you_mean(name, names));
    }
    set(*field, value);
  }
  for (const RequestField<Request>& field : fields) {
    if (!field.required) continue;
    bool found = false;
    for (const std::string& g : given) found = found || g == field.name;
    if (!found) throw py::type_error("missing required argument '" + std::string(field.name) + "'");
  }
  return request;
}

// "SUMMARY\n\nArguments:\n    name [unit]: help\n..." from the request's table.
template <class Request>
std::string request_docstring(
    const std::string& summary,
    const std::string& returns =
        "Returns a roadbrdf.Result (value, notes, warnings, summary); warnings are also issued.") {
  std::string doc = summary + "\n\nArguments (positional first; all may be given by keyword):\n";
  for (const RequestField<Request>& field : Request::fields()) {
    doc += "    " + std::string(field.name);
    if (!field.unit.empty()) doc += " [" + std::string(field.unit) + "]";
    doc += ": " + std::string(field.help) + "\n";
  }
  return doc + "\n" + returns + "\n";
}

// A task's warnings issued as roadbrdf.RoadbrdfWarning at the caller's line.
inline void issue_warnings(const Diagnostics& diagnostics) {
  namespace py = pybind11;
  const py::object warning_type = py::module_::import("roadbrdf.result").attr("RoadbrdfWarning");
  for (const Diagnostic& d : diagnostics.warnings) {
    py::module_::import("roadbrdf.core").attr("warn_at_caller")(d.message, warning_type);
  }
}

// A task's result as a roadbrdf.Result; its warnings are issued (issue_warnings).
inline pybind11::object python_result(const nlohmann::json& value, const Diagnostics& diagnostics,
                                      const std::string& summary) {
  namespace py = pybind11;
  const py::module_ result_module = py::module_::import("roadbrdf.result");
  issue_warnings(diagnostics);
  const nlohmann::json diagnostics_json = diagnostics.to_json();
  return result_module.attr("Result")(json_to_python(value), json_to_python(diagnostics_json["notes"]),
                                      json_to_python(diagnostics_json["warnings"]), summary);
}

}  // namespace roadbrdf::python
