// Minimal streaming CSV tokenizer that remembers where every cell came from, so that every
// error names file, line and column. Lines starting with '#' are comments; blank lines are
// skipped; a UTF-8 byte order mark is ignored. Cells are separated by ',' (or set_delimiter;
// surrounding spaces trimmed); no quoting (not needed by any format roadbrdf reads). "-" reads standard input; read
// errors are errors (core/input_file.h).
#pragma once

#include <cstddef>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf {

struct CsvCell {
  std::string_view text;
  long column = 0;  // 1-based character column of the cell's first character
};

class CsvReader {
 public:
  // Throws FileError if the file cannot be opened ("-" = standard input) or is refused by `limits`.
  explicit CsvReader(const std::string& path, const InputLimits& limits = {});

  // Next non-blank, non-comment line split into cells; false at end of file. Comment lines seen
  // on the way are collected in comments() (without the leading '#'). Throws FileError on a read
  // error.
  bool next_row(std::vector<CsvCell>& cells);
  // Same, without splitting: the line as it is (a trailing '\r' removed), valid until the next call.
  // A UTF-8 byte order mark at the start of the file is skipped (columns count after it).
  bool next_line(std::string_view& line);
  // The separator next_row splits on (default ',').
  void set_delimiter(char delimiter) { delimiter_ = delimiter; }

  // Split rows into at most `limit` + 1 cells; cell_count() still gives the row's true count. A
  // reader that knows how many cells a row must have sets this, so that an overlong row costs no
  // more than the line itself before it is refused.
  void set_cell_limit(std::size_t limit) { cell_limit_ = limit; }
  // Number of cells of the last row returned by next_row.
  std::size_t cell_count() const { return cell_count_; }

  // The name for messages ("<standard input>" for "-").
  const std::string& path() const { return path_; }
  // Size of a regular file in bytes, 0 when unknown.
  std::uintmax_t size_hint() const { return in_->size_hint(); }
  long line_number() const { return line_number_; }
  std::vector<std::string>& comments() { return comments_; }
  // Line number of each entry of comments() (same order).
  const std::vector<long>& comment_lines() const { return comment_lines_; }

  // Parse a cell as a finite double; throws FileError naming file, line, column and the text.
  double number(const CsvCell& cell, std::string_view what = "number") const;
  [[noreturn]] void fail(long column, const std::string& message) const;

 private:
  std::string path_;
  std::unique_ptr<InputFile> in_;
  long line_number_ = 0;
  std::size_t cell_limit_ = std::numeric_limits<std::size_t>::max() - 1;
  std::size_t cell_count_ = 0;
  char delimiter_ = ',';
  std::vector<std::string> comments_;
  std::vector<long> comment_lines_;
};

// Split a line on a separator, trimming spaces; columns are 1-based. At most `limit` + 1 cells are
// made; `count` (if given) receives the line's true number of cells.
std::vector<CsvCell> split_cells(std::string_view line, char separator = ',',
                                 std::size_t limit = std::numeric_limits<std::size_t>::max() - 1,
                                 std::size_t* count = nullptr);
// Split a line on runs of spaces/tabs (for whitespace-separated tables); columns are 1-based.
std::vector<CsvCell> split_whitespace(std::string_view line);

}  // namespace roadbrdf
