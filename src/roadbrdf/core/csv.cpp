#include "roadbrdf/core/csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace {
std::string_view trim(std::string_view s, std::size_t& offset) {
  std::size_t b = 0;
  while (b < s.size() && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r')) ++b;
  std::size_t e = s.size();
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
  offset = b;
  return s.substr(b, e - b);
}
}  // namespace

std::vector<CsvCell> split_cells(std::string_view line, char separator) {
  std::vector<CsvCell> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    const std::string_view raw = line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    std::size_t offset = 0;
    const std::string_view text = trim(raw, offset);
    cells.push_back({text, static_cast<long>(start + offset + 1)});
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return cells;
}

std::vector<CsvCell> split_whitespace(std::string_view line) {
  std::vector<CsvCell> cells;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t' || line[k] == '\r')) ++k;
    if (k >= line.size()) break;
    const std::size_t b = k;
    while (k < line.size() && line[k] != ' ' && line[k] != '\t' && line[k] != '\r') ++k;
    cells.push_back({line.substr(b, k - b), static_cast<long>(b + 1)});
  }
  return cells;
}

bool parse_finite_double(std::string_view text, double& value) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last && std::isfinite(value);
}

CsvReader::CsvReader(std::string path) : path_(std::move(path)), in_(path_) {
  if (!in_) throw FileError(path_, 0, 0, "cannot open file for reading");
}

bool CsvReader::next_row(std::vector<CsvCell>& cells) {
  while (std::getline(in_, line_)) {
    ++line_number_;
    std::size_t offset = 0;
    const std::string_view text = trim(line_, offset);
    if (text.empty()) continue;
    if (text.front() == '#') {
      comments_.emplace_back(text.substr(1));
      comment_lines_.push_back(line_number_);
      continue;
    }
    cells = split_cells(line_);
    return true;
  }
  return false;
}

double CsvReader::number(const CsvCell& cell, std::string_view what) const {
  double value = 0.0;
  const char* first = cell.text.data();
  const char* last = first + cell.text.size();
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (cell.text.empty()) fail(cell.column, "empty cell where a " + std::string(what) + " was expected");
  if (ec != std::errc() || ptr != last) {
    fail(cell.column, "'" + std::string(cell.text) + "' is not a " + std::string(what));
  }
  if (!std::isfinite(value)) fail(cell.column, "'" + std::string(cell.text) + "' is not a finite " + std::string(what));
  return value;
}

void CsvReader::fail(long column, const std::string& message) const {
  throw FileError(path_, line_number_, column, message);
}

}  // namespace roadbrdf
