#include "roadbrdf/core/csv.h"

#include <fmt/core.h>

#include <charconv>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf {

std::vector<CsvCell> split_cells(std::string_view line, char separator, std::size_t limit, std::size_t* count) {
  std::vector<CsvCell> cells;
  std::size_t start = 0;
  std::size_t n = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    if (n <= limit) {
      const std::string_view raw =
          line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
      std::size_t offset = 0;
      const std::string_view text = trim_blanks(raw, offset);
      cells.push_back({text, static_cast<long>(start + offset + 1)});
    }
    ++n;
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  if (count) *count = n;
  return cells;
}

std::vector<CsvCell> split_whitespace(std::string_view line) {
  std::vector<CsvCell> cells;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && is_blank(line[k])) ++k;
    if (k >= line.size()) break;
    const std::size_t b = k;
    while (k < line.size() && !is_blank(line[k])) ++k;
    cells.push_back({line.substr(b, k - b), static_cast<long>(b + 1)});
  }
  return cells;
}

CsvReader::CsvReader(const std::string& path, const InputLimits& limits)
    : path_(input_display_name(path)), in_(std::make_unique<InputFile>(path, limits)) {}

bool CsvReader::next_line(std::string_view& line) {
  std::string_view raw;
  while (in_->read_line(raw)) {
    ++line_number_;
    if (line_number_ == 1 && raw.substr(0, 3) == "\xEF\xBB\xBF") raw.remove_prefix(3);
    std::size_t offset = 0;
    const std::string_view text = trim_blanks(raw, offset);
    if (text.empty()) continue;
    if (text.front() == '#') {
      comments_.emplace_back(text.substr(1));
      comment_lines_.push_back(line_number_);
      continue;
    }
    line = raw;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  }
  return false;
}

bool CsvReader::next_row(std::vector<CsvCell>& cells) {
  std::string_view line;
  if (!next_line(line)) return false;
  cells = split_cells(line, delimiter_, cell_limit_, &cell_count_);
  return true;
}

double CsvReader::number(const CsvCell& cell, std::string_view what) const {
  if (cell.text.empty()) fail(cell.column, fmt::format("empty cell where a {} was expected", what));
  double value = 0.0;
  if (parse_finite_double(cell.text, value)) return value;
  // Tell an out-of-range or infinite number from text that is no number at all.
  const char* first = cell.text.data();
  const char* last = first + cell.text.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ptr == last && ec == std::errc::result_out_of_range) {
    fail(cell.column, fmt::format("'{}' is out of the range of double-precision numbers ({})", cell.text, what));
  }
  if (ptr == last && ec == std::errc() && !std::isfinite(value)) {
    fail(cell.column, fmt::format("'{}' is not a finite {}", cell.text, what));
  }
  fail(cell.column, fmt::format("'{}' is not a {}", cell.text, what));
}

void CsvReader::fail(long column, const std::string& message) const {
  throw FileError(path_, line_number_, column, message);
}

}  // namespace roadbrdf
