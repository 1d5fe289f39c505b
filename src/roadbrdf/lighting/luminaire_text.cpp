#include "roadbrdf/lighting/luminaire_text.h"

#include <cmath>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf::lighting::detail {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }

// Quotes a cell for a message, shortened and with control bytes shown as '?'.
std::string quoted(std::string_view cell) {
  std::string out = "'";
  for (std::size_t k = 0; k < cell.size() && k < 40; ++k) {
    const auto c = static_cast<unsigned char>(cell[k]);
    out += c < 0x20 || c == 0x7f ? '?' : static_cast<char>(c);
  }
  if (cell.size() > 40) out += "...";
  return out + "'";
}

// The number a cell holds, reading a single decimal comma as a point.
bool cell_number(std::string_view cell, double& value, bool& decimal_comma) {
  if (parse_finite_double(cell, value)) return true;
  const std::size_t comma = cell.find(',');
  if (comma == std::string_view::npos || cell.find(',', comma + 1) != std::string_view::npos ||
      cell.find('.') != std::string_view::npos) {
    return false;
  }
  std::string with_point(cell);
  with_point[comma] = '.';
  if (!parse_finite_double(with_point, value)) return false;
  decimal_comma = true;
  return true;
}

}  // namespace

LuminaireText::LuminaireText(std::string_view content, std::string file) : file_(std::move(file)) {
  std::size_t start = 0;
  for (std::size_t k = 0; k < content.size(); ++k) {
    if (content[k] != '\n' && content[k] != '\r') continue;
    lines_.push_back(content.substr(start, k - start));
    if (content[k] == '\r' && k + 1 < content.size() && content[k + 1] == '\n') ++k;
    start = k + 1;
  }
  if (start < content.size()) lines_.push_back(content.substr(start));
}

void LuminaireText::fail(std::size_t k, std::size_t column, const std::string& what) const {
  throw FileError(file_, static_cast<long>(k) + 1, static_cast<long>(column), what);
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

NumberStream::NumberStream(const LuminaireText& text, std::size_t first_line, bool commas_separate)
    : text_(text), line_(first_line), commas_separate_(commas_separate) {}

bool NumberStream::skip_separators() {
  while (line_ < text_.line_count()) {
    const std::string_view line = text_.line(line_);
    while (offset_ < line.size() && (is_blank(line[offset_]) || (commas_separate_ && line[offset_] == ','))) {
      ++offset_;
    }
    if (offset_ < line.size()) return true;
    ++line_;
    offset_ = 0;
  }
  return false;
}

bool NumberStream::at_end() { return !skip_separators(); }

double NumberStream::next(const std::string& what) {
  if (!skip_separators()) {
    // The end of the file: located at its last line.
    const std::size_t last = text_.line_count() == 0 ? 0 : text_.line_count() - 1;
    text_.fail(last, 0, "truncated: the file ends before " + what);
  }
  const std::string_view line = text_.line(line_);
  std::size_t end = offset_;
  while (end < line.size() && !is_blank(line[end]) && !(commas_separate_ && line[end] == ',')) ++end;
  const std::string_view cell = line.substr(offset_, end - offset_);
  token_line_ = line_;
  token_column_ = offset_ + 1;
  offset_ = end;
  double value = 0.0;
  if (!cell_number(cell, value, decimal_comma_)) {
    text_.fail(token_line_, token_column_, quoted(cell) + " is not a number (" + what + ")");
  }
  return value;
}

long NumberStream::next_integer(const std::string& what, long lo, long hi) {
  const double value = next(what);
  if (value != std::floor(value) || value < static_cast<double>(lo) || value > static_cast<double>(hi)) {
    text_.fail(token_line_, token_column_,
               what + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
  }
  return static_cast<long>(value);
}

namespace {

bool is_utf8(std::string_view text) {
  std::size_t k = 0;
  while (k < text.size()) {
    const auto c = static_cast<unsigned char>(text[k]);
    std::size_t extra = 0;
    if (c < 0x80) {
      extra = 0;
    } else if (c >= 0xc2 && c <= 0xdf) {
      extra = 1;
    } else if (c >= 0xe0 && c <= 0xef) {
      extra = 2;
    } else if (c >= 0xf0 && c <= 0xf4) {
      extra = 3;
    } else {
      return false;
    }
    if (k + extra >= text.size() && extra > 0) return false;
    for (std::size_t j = 1; j <= extra; ++j) {
      if ((static_cast<unsigned char>(text[k + j]) & 0xc0) != 0x80) return false;
    }
    // No overlong forms, surrogates or code points beyond U+10FFFF (RFC 3629, section 4).
    const auto second = extra > 0 ? static_cast<unsigned char>(text[k + 1]) : 0;
    if ((c == 0xe0 && second < 0xa0) || (c == 0xed && second > 0x9f) || (c == 0xf0 && second < 0x90) ||
        (c == 0xf4 && second > 0x8f)) {
      return false;
    }
    k += extra + 1;
  }
  return true;
}

}  // namespace

std::string text_field(std::string_view text) {
  text = trimmed(text);
  if (is_utf8(text)) return std::string(text);
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else {
      out += static_cast<char>(0xc0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3f));
    }
  }
  return out;
}

double number_on_line(const LuminaireText& text, std::size_t k, const std::string& what, bool& decimal_comma) {
  if (k >= text.line_count()) {
    text.fail(text.line_count() == 0 ? 0 : text.line_count() - 1, 0, "truncated: the file ends before " + what);
  }
  const std::string_view line = text.line(k);
  const std::string_view cell = trimmed(line);
  double value = 0.0;
  if (!cell_number(cell, value, decimal_comma)) {
    const std::size_t column = cell.empty() ? 1 : static_cast<std::size_t>(cell.data() - line.data()) + 1;
    text.fail(k, column,
              (cell.empty() ? std::string("an empty line") : quoted(cell)) + " is not a number (" + what + ")");
  }
  return value;
}

}  // namespace roadbrdf::lighting::detail
