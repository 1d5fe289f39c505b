// A request's fields, declared once. Each task the front ends offer is a request struct of the
// library with one validation (Ceres-style options); its fields are listed in a table of
// RequestField rows, and everything that names a field is made from that table:
//   - the command line's options (cli/request_options.h: flag, help with unit, default),
//   - Python's keyword arguments, their conversion and docstring (python/src/request_kwargs.h),
//   - the spelling of a field in errors (FieldError::field is the row's name; the command line
//     prints the row's flag instead),
//   - the inputs and outputs that check_distinct_files compares (rows marked FileRole::input/output),
//   - the option tables of the docs.
// So adding a field to a request is one member and one row (docs/ARCHITECTURE.md has an example).
//
// A request declares its table as a static member function defined next to validate():
//   struct LuminaireRequest {
//     std::string file;
//     bool json = false;
//     static std::span<const RequestField<LuminaireRequest>> fields();
//   };
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf {

// An input of a request given as its file or as its content: Python may pass the value itself (a
// formulation as a dict) where the command line names a file. With `text` (the content, JSON) set,
// `path` only names the input in messages and relative references inside it are taken as they are;
// without, the file at `path` is read.
struct Source {
  std::string path;
  std::string text;
  bool empty() const { return path.empty() && text.empty(); }
  bool in_memory() const { return !text.empty(); }
};

// A length [mm] that the command line writes with its unit ("60mm", "6cm"; core/length.h
// parse_length_mm) and Python gives as a number of millimetres; absent = not given (the request's
// default). An optional number otherwise, so `if (size_mm)` and `size_mm.value_or(60.0)` read it.
struct LengthMm : std::optional<double> {
  LengthMm() = default;
  LengthMm(double mm) : std::optional<double>(mm) {}  // NOLINT(google-explicit-constructor): a length is a number
  LengthMm& operator=(double mm) {
    std::optional<double>::operator=(mm);
    return *this;
  }
};

// What a field holds: a pointer to one member of the request, of one of these types.
//   double, int, bool (a switch: present or not), std::string (a name, a path or a value in the
//   grammar the field's help states), std::optional<double> (absent = not given),
//   std::vector<std::string> (repeatable: NAME=VALUE items, several paths; names, also
//   comma-separated when the row says so),
//   std::vector<double> (a list of numbers in core/range.h's grammar),
//   std::map<std::string, std::string> (NAME=VALUE items; a dict in Python),
//   std::map<std::string, double> (NAME=NUMBER items; a dict of numbers),
//   std::map<std::string, std::pair<double, double>> (NAME=LOWER:UPPER items; a dict of pairs),
//   std::vector<std::pair<double, double>> (LOWER:UPPER items; pairs or "LOWER:UPPER" texts),
//   Source (a file; in Python also its content as a dict),
//   std::optional<std::pair<double, double>> (one LOWER:UPPER interval; absent = not given),
//   long, std::optional<long> (absent = not given), std::uint64_t (counts beyond int: paths, seeds),
//   std::optional<int> (a count whose default depends on other fields; absent = not given),
//   LengthMm (a length with its unit on the command line, millimetres in Python).
// A bool whose default is true is a switch that turns it off (`use_sigma`, --no-sigma-weights).
template <class Request>
using FieldMember =
    std::variant<double Request::*, int Request::*, bool Request::*, std::string Request::*,
                 std::optional<double> Request::*, std::vector<std::string> Request::*, std::vector<double> Request::*,
                 std::map<std::string, std::string> Request::*, std::map<std::string, double> Request::*,
                 std::map<std::string, std::pair<double, double>> Request::*,
                 std::vector<std::pair<double, double>> Request::*, Source Request::*,
                 std::optional<std::pair<double, double>> Request::*, long Request::*, std::optional<long> Request::*,
                 std::uint64_t Request::*, std::optional<int> Request::*, LengthMm Request::*>;

// Whether a field names a file the task reads or writes (for check_distinct_files).
enum class FileRole { none, input, output };

template <class Request>
struct RequestField {
  // The request field and Python keyword argument: "sun_zenith". Errors name it (FieldError).
  std::string_view name;
  // The command line's spelling: "--sun-zenith", "-o,--output" (short and long), or an upper-case
  // placeholder without dashes ("INSTALLATION") for a positional argument.
  std::string_view flag;
  // The unit of a number, as the docs write it ("deg", "m", "lm", "W"); "" for names, counts, paths.
  std::string_view unit;
  // One sentence: the command's --help, Python's docstring and the docs' option table.
  std::string_view help;
  FieldMember<Request> member;
  FileRole file = FileRole::none;
  bool required = false;
  // A list of names may also be given comma-separated ("theta_i,phi_i"): each item is split.
  bool comma_separated = false;

  bool positional() const { return !flag.empty() && flag.front() != '-'; }
  // The first long spelling of the flag ("--output" of "-o,--output", "--bound" of "--bound,--bounds");
  // the placeholder of a positional.
  std::string_view long_flag() const {
    std::string_view rest = flag;
    while (!rest.empty()) {
      const auto comma = rest.find(',');
      const std::string_view item = rest.substr(0, comma);
      if (item.substr(0, 2) == "--" || comma == std::string_view::npos) return item;
      rest = rest.substr(comma + 1);
    }
    return flag;
  }
};

template <class Request>
using RequestFields = std::span<const RequestField<Request>>;

// The rows of a base's table (`Base::fields()`) in the table of a Request derived from Base: the same
// rows, each member pointer converted to one of Request (a base's member is the derived's). Rows
// shared by several requests are declared once this way (modelfile/model_source_fields.h).
template <class Request, class Base>
std::vector<RequestField<Request>> fields_of_base() {
  std::vector<RequestField<Request>> rows;
  for (const RequestField<Base>& f : Base::fields()) {
    const FieldMember<Request> member = std::visit([](auto m) -> FieldMember<Request> { return m; }, f.member);
    rows.push_back({f.name, f.flag, f.unit, f.help, member, f.file, f.required, f.comma_separated});
  }
  return rows;
}

// The `threads` field of a request that runs in parallel (albedo, render): [0, 1024], 0 = all cores.
// Throws FieldError("threads").
inline void check_thread_count(int threads) {
  if (threads < 0 || threads > 1024) {
    throw FieldError("threads", std::to_string(threads) + " is outside [0, 1024] (0 = all cores)");
  }
}

// Items of a comma-separated list of names ("theta_i, phi_i"): split at commas, blanks removed,
// empty parts skipped (RequestField::comma_separated).
inline std::vector<std::string> split_name_list(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const std::string& item : items) {
    std::string part;
    for (const char c : item + ",") {
      if (c == ',') {
        if (!part.empty()) out.push_back(part);
        part.clear();
      } else if (c != ' ') {
        part += c;
      }
    }
  }
  return out;
}

// The row named `name` ("options.distribution" is found by its first part), or nullptr.
template <class Request>
const RequestField<Request>* find_field(RequestFields<Request> fields, std::string_view name) {
  const std::string_view head = name.substr(0, name.find('.'));
  for (const RequestField<Request>& field : fields) {
    if (field.name == name || field.name == head) return &field;
  }
  return nullptr;
}

// Every file a request names, as check_distinct_files takes them; a role is the field's reference
// (`output`), which the command line prints as its flag and Python as its keyword. Extra inputs a task finds inside its
// inputs (a formulation's fit files, a manifest's scans) are added by the task itself.
template <class Request>
void file_arguments(const Request& request, RequestFields<Request> fields, std::vector<FileArgument>& inputs,
                    std::vector<FileArgument>& outputs) {
  for (const RequestField<Request>& field : fields) {
    if (field.file == FileRole::none) continue;
    std::vector<FileArgument>& into = field.file == FileRole::input ? inputs : outputs;
    // Built by appending: g++ 12 warns falsely (-Wrestrict) on "`" + std::string(...).
    std::string role = "`";
    role += field.name;
    role += "`";
    if (const auto* text = std::get_if<std::string Request::*>(&field.member)) {
      if (!(request.*(*text)).empty()) into.push_back({role, request.*(*text)});
    } else if (const auto* source = std::get_if<Source Request::*>(&field.member)) {
      const Source& s = request.*(*source);
      if (!s.in_memory() && !s.path.empty()) into.push_back({role, s.path});
    } else if (const auto* list = std::get_if<std::vector<std::string> Request::*>(&field.member)) {
      for (const std::string& path : request.*(*list)) into.push_back({role, path});
    }
  }
}

// check_distinct_files over a request's file fields and `extra_inputs` (see file_arguments).
template <class Request>
void check_request_files(const Request& request, std::vector<FileArgument> extra_inputs = {}) {
  std::vector<FileArgument> outputs;
  file_arguments(request, Request::fields(), extra_inputs, outputs);
  check_distinct_files(extra_inputs, outputs);
}

}  // namespace roadbrdf
