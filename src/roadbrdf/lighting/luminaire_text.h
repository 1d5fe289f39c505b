// The text of a luminaire file as the two readers (eulumdat.cpp, ies_file.cpp) see it: numbered
// lines, and a stream of numbers across lines whose every error names file, line and column.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace roadbrdf::lighting::detail {

class LuminaireText {
 public:
  // Lines end at "\n", "\r\n" or "\r"; the content must stay alive while the text is used.
  LuminaireText(std::string_view content, std::string file);

  std::size_t line_count() const { return lines_.size(); }
  // Line k (0-based) without its end of line.
  std::string_view line(std::size_t k) const { return lines_[k]; }
  const std::string& file() const { return file_; }
  // Throws FileError at line k (0-based; k = line_count() is the end of the file), column (1-based;
  // 0 = unknown).
  [[noreturn]] void fail(std::size_t k, std::size_t column, const std::string& what) const;

 private:
  std::vector<std::string_view> lines_;
  std::string file_;
};

// `text` without leading and trailing blanks (spaces, tabs).
std::string_view trimmed(std::string_view text);

// Numbers separated by blanks (and by commas when `commas_separate`; otherwise a comma is read as
// a decimal comma, "0,5" = 0.5), from line `first_line` on, across line ends.
class NumberStream {
 public:
  NumberStream(const LuminaireText& text, std::size_t first_line, bool commas_separate);

  // The next number; `what` names it in errors ("vertical angle 3 of 37"). At the end of the file:
  // "truncated: ...".
  double next(const std::string& what);
  // The next number, which must be an integer within [lo, hi].
  long next_integer(const std::string& what, long lo, long hi);
  // Whether only blanks are left.
  bool at_end();
  // Where the last number read was (0-based line, 1-based column), and the position after it.
  std::size_t line() const { return token_line_; }
  std::size_t column() const { return token_column_; }
  std::size_t next_line() const { return line_; }
  // Whether a decimal comma was read.
  bool read_decimal_comma() const { return decimal_comma_; }

 private:
  bool skip_separators();
  const LuminaireText& text_;
  std::size_t line_;
  std::size_t offset_ = 0;
  bool commas_separate_;
  bool decimal_comma_ = false;
  std::size_t token_line_ = 0;
  std::size_t token_column_ = 0;
};

// A text field of a file as valid UTF-8: kept when it is UTF-8, otherwise read as Latin-1 (the
// Windows code pages of many EULUMDAT and IES files), trimmed.
std::string text_field(std::string_view text);

// One field of a line-per-field format: the whole trimmed line as a number (a decimal comma read as
// a point), or FileError naming `what`.
double number_on_line(const LuminaireText& text, std::size_t k, const std::string& what, bool& decimal_comma);

}  // namespace roadbrdf::lighting::detail
