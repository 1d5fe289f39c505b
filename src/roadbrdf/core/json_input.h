// Reading JSON that comes from users (fit, MIX, formulation and surface files, options objects).
//
// parse_json() is the one entry point: it bounds the nesting depth (a deep document would otherwise
// overflow the stack when a value is copied or compared), refuses duplicate keys (nlohmann keeps the
// last one silently) and numbers outside the double range (1e400), and locates every error by file,
// line, column and key path. JsonNode then reads values out of the document with the key path in
// every message ("fits[0].parameters.albedo[3]: must be a number"), and without copying subtrees.
// dump_json() and write_json() write any document, replacing bytes that are not UTF-8 (a file name)
// instead of throwing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

using Json = nlohmann::json;

// No roadbrdf file nests more than a handful of levels; 64 leaves room for hand-written extras.
constexpr int kMaxJsonDepth = 64;

// The largest JSON file read: a surface of the most cells (4e7 heights) takes a few hundred MB.
inline constexpr std::uintmax_t kJsonFileMaxBytes = std::uintmax_t{1} << 30;

// Parses a whole document. `file` names it in errors (FileError with line, column and key path).
Json parse_json(std::istream& in, const std::string& file, int max_depth = kMaxJsonDepth);
Json parse_json_text(const std::string& text, const std::string& file, int max_depth = kMaxJsonDepth);
// Opens `path` ("-" = standard input) with the project's input rules and parses it.
Json parse_json_file(const std::string& path, int max_depth = kMaxJsonDepth);

// Serialises with invalid UTF-8 replaced by U+FFFD (never throws on strings).
std::string dump_json(const Json& j, int indent = -1);
std::string dump_json(const nlohmann::ordered_json& j, int indent = -1);
// The same text as dump_json(), written to `out` in blocks (a large document is never held whole).
void write_json(std::ostream& out, const Json& j, int indent = -1);
void write_json(std::ostream& out, const nlohmann::ordered_json& j, int indent = -1);

// A value inside a parsed document, with its file and key path. Cheap to copy (holds a reference;
// the document must outlive it).
class JsonNode {
 public:
  JsonNode(const Json& value, std::string file, std::string path = "");

  const Json& json() const { return *value_; }
  const std::string& file() const { return file_; }
  // "fits[0].model"; empty for the top level.
  const std::string& path() const { return path_; }
  // The path as shown in messages ("(top level)" for the root).
  std::string where() const;

  bool is_object() const { return value_->is_object(); }
  bool is_array() const { return value_->is_array(); }
  bool is_null() const { return value_->is_null(); }
  bool is_string() const { return value_->is_string(); }
  bool is_number() const { return value_->is_number(); }

  // Objects. at() fails with "missing" when the key is absent; find() gives nullopt.
  bool has(const std::string& key) const;
  JsonNode at(const std::string& key) const;
  std::optional<JsonNode> find(const std::string& key) const;
  // Members in key order, as (key, node) pairs; fails unless this is an object.
  std::vector<std::pair<std::string, JsonNode>> members() const;
  // Fails naming the first key that is not in `allowed`.
  void check_keys(const std::vector<std::string>& allowed) const;

  // Arrays. size() and operator[] fail unless this is an array.
  std::size_t size() const;
  JsonNode operator[](std::size_t index) const;
  std::vector<JsonNode> elements() const;

  // Scalars, with the key path in every error.
  std::string string() const;
  bool boolean() const;
  double number() const;  // finite
  // An integer in [lo, hi]: integral-valued (1.0 is accepted, 1.9 and 1e10 out of range are not).
  long long integer(long long lo, long long hi) const;
  std::vector<double> numbers() const;
  std::vector<std::string> strings() const;
  std::vector<long long> integers(long long lo, long long hi) const;
  std::map<std::string, std::string> string_map() const;
  std::map<std::string, double> number_map() const;

  // Optional members with defaults (the member, when present, must have the right type).
  std::string string_or(const std::string& key, const std::string& fallback) const;
  double number_or(const std::string& key, double fallback) const;
  bool boolean_or(const std::string& key, bool fallback) const;

  // FileError "file: key.path: what".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  JsonNode child(const Json& value, const std::string& suffix) const;
  std::string type_name() const;

  const Json* value_;
  std::string file_;
  std::string path_;
};

// The parameter table of a fit or MIX file: `parameters` maps each parameter name of `description` to
// `rows` values (one per wavelength, `wavelengths` for messages; empty for a single row). Every value
// must lie within the parameter's declared bounds (the metadata is the only valid range).
// Returns rows x parameter_count values, row-major.
std::vector<double> read_parameter_table(const JsonNode& parameters, const ModelDescription& description,
                                         std::size_t rows, const std::vector<double>& wavelengths);

}  // namespace roadbrdf
