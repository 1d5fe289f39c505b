// Minimal streaming CSV tokenizer that remembers where every cell came from, so that every
// error names file, line and column. Lines starting with '#' are comments; blank lines are
// skipped. Cells are separated by ',' (surrounding spaces trimmed); no quoting (not needed by
// any format roadbrdf reads).
#pragma once

#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace roadbrdf {

struct CsvCell {
  std::string_view text;
  long column = 0;  // 1-based character column of the cell's first character
};

class CsvReader {
 public:
  // Throws FileError if the file cannot be opened.
  explicit CsvReader(std::string path);

  // Next non-blank, non-comment line split into cells; false at end of file. Comment lines seen
  // on the way are collected in comments() (without the leading '#').
  bool next_row(std::vector<CsvCell>& cells);

  const std::string& path() const { return path_; }
  long line_number() const { return line_number_; }
  std::vector<std::string>& comments() { return comments_; }
  // Line number of each entry of comments() (same order).
  const std::vector<long>& comment_lines() const { return comment_lines_; }

  // Parse a cell as a finite double; throws FileError naming file, line, column and the text.
  double number(const CsvCell& cell, std::string_view what = "number") const;
  [[noreturn]] void fail(long column, const std::string& message) const;

 private:
  std::string path_;
  std::ifstream in_;
  std::string line_;
  long line_number_ = 0;
  std::vector<std::string> comments_;
  std::vector<long> comment_lines_;
};

// Split a line on a separator, trimming spaces; columns are 1-based.
std::vector<CsvCell> split_cells(std::string_view line, char separator = ',');
// Split a line on runs of spaces/tabs (for whitespace-separated tables); columns are 1-based.
std::vector<CsvCell> split_whitespace(std::string_view line);
// Parse a whole cell as a finite double (leading '+' allowed); false otherwise.
bool parse_finite_double(std::string_view text, double& value);

}  // namespace roadbrdf
