// Error types shared by the library, the command line and the Python module.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace roadbrdf {

// Any problem caused by the caller's input: unknown model, out-of-bounds parameter,
// malformed file... The message is meant to be shown to the user as is.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
