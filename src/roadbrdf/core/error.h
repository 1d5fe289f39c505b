// Error types shared by the library, the command line and the Python module.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace roadbrdf {

// Any problem caused by the caller's input: unknown model, out-of-bounds parameter,
// malformed file... The message is meant to be shown to the user as is.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Library messages name request fields, never a front end's spelling of them (no command-line
// flags): a field that is the subject of the error is FieldError::field; a field mentioned inside a
// message (a hint such as "pass `delimiter`") is written as field_reference() makes it, between
// backquotes. The command line replaces each reference by its flag (cli/common.h, name_flags);
// Python shows it as is, which is the keyword argument's name.
inline std::string field_reference(const std::string& field) { return "`" + field + "`"; }

// A problem with one named field of a request: "wavelengths", "options.distribution",
// "fixed.roughness". The message is "FIELD: DETAIL"; the front ends may name the field their own
// way (the command line maps it to its flag, see cli/common.h), Python shows it as is.
class FieldError : public InputError {
 public:
  FieldError(std::string field, std::string detail)
      : InputError(field + ": " + detail), field_(std::move(field)), detail_(std::move(detail)) {}
  const std::string& field() const { return field_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string field_;
  std::string detail_;
};

// A problem in a file, located by file, line and column (1-based; 0 = unknown).
class FileError : public InputError {
 public:
  FileError(std::string file, long line, long column, const std::string& what)
      : InputError(format(file, line, column, what)), file_(std::move(file)), line_(line), column_(column) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }
  long column() const { return column_; }

 private:
  static std::string format(const std::string& file, long line, long column, const std::string& what) {
    std::ostringstream where;
    where << file;
    if (line > 0) where << ':' << line;
    if (column > 0) where << ':' << column;
    where << ": " << what;
    return where.str();
  }
  std::string file_;
  long line_;
  long column_;
};

}  // namespace roadbrdf
