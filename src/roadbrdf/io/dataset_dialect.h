// Dataset CSV dialects: how people's files are written (spreadsheet exports, instrument software),
// and the pieces the dataset reader (io/dataset_io.h) uses to read them all like the canonical CSV.
//
// - Delimiter ',' (canonical), ';' (French/German spreadsheets, usually with decimal commas) or a
//   tab. Detected from the header line: the delimiter is the one character of , ; TAB that the line
//   holds, or, when it holds several, the one that splits it into known column names; when none or
//   several do, the file is ambiguous and the error names the fields `delimiter` / `decimal`.
// - Decimal separator '.' or ',' (only with ';' or tab delimiters). Detected from the first number
//   that has one; a later number with the other separator is an error naming both places.
// - A UTF-8 byte order mark, CRLF line ends, spaces around cells: ignored.
// - Header names: any case, surrounding spaces, a unit suffix "[deg]", "(deg)" or "_deg" on angles,
//   "nm" on wavelengths (400nm, 400 nm, sigma_400nm), and the aliases of column_aliases().
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace roadbrdf {

// "auto" (0), ",", ";", "tab" (or "\t"); throws FieldError(field).
char delimiter_from_name(const std::string& name, const std::string& field = "delimiter");
// "auto" (0), ".", ","; throws FieldError(field).
char decimal_from_name(const std::string& name, const std::string& field = "decimal");
// Display name of a delimiter / decimal separator for messages ("','", "';'", "tab").
std::string delimiter_display(char delimiter);

// The canonical name of a header cell: lower case, trimmed, unit suffixes removed, aliases mapped
// (theta_i, phi_i, theta_r, phi_r, gamma, alpha, beta, delta, wavelength, brdf, sigma); anything
// else is returned lower-cased and trimmed. `angle_in_radians` is set when the name declares
// radians (e.g. "theta_i [rad]"), which the reader refuses with a message.
std::string canonical_column_name(std::string_view name, bool* angle_in_radians = nullptr);

// The alias table (canonical name, accepted aliases), for the documentation and --help.
const std::vector<std::pair<std::string, std::vector<std::string>>>& column_aliases();

// Split a line on `delimiter` without allocating: call next() until it returns false.
class CellScanner {
 public:
  CellScanner(std::string_view line, char delimiter) : line_(line), delimiter_(delimiter) {}
  // The next cell, trimmed of spaces, tabs and '\r', with its 1-based column.
  bool next(std::string_view& text, long& column);
  // Whether the last cell returned was the line's last.
  bool done() const { return done_; }

 private:
  std::string_view line_;
  char delimiter_;
  std::size_t position_ = 0;
  bool done_ = false;
};

// The delimiter of a header line (see the top of this file). `known` tells whether a canonical
// header name is one the reader understands (angle, wavelength number, sigma_<nm>, long-format
// name). Throws InputError (the caller adds file and line) when the line is ambiguous.
char detect_delimiter(std::string_view header_line, bool (*known)(std::string_view canonical_name, char delimiter));

// Numbers with a fixed or detected decimal separator. Fast path: std::from_chars on the text.
class NumberParser {
 public:
  // delimiter: the file's; decimal: '.', ',' or 0 (detect; always '.' when the delimiter is ',').
  NumberParser(char delimiter, char decimal);
  // A whole cell as a finite double (leading '+' allowed); false when it is not one.
  bool parse(std::string_view text, double& value, long line, long column) {
    if (decimal_ == '.') return parse_point(text, value);
    return parse_slow(text, value, line, column);
  }
  // For a cell that did not parse: " (...)" explaining a decimal separator that contradicts the
  // file's (naming where it was detected and --decimal), or "".
  std::string hint(std::string_view text) const;
  char decimal() const { return decimal_; }

 private:
  static bool parse_point(std::string_view text, double& value);
  bool parse_slow(std::string_view text, double& value, long line, long column);
  char delimiter_;
  char decimal_;                                // 0 while undetected
  long decided_line_ = 0, decided_column_ = 0;  // where the separator was detected
};

}  // namespace roadbrdf
