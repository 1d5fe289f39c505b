// Internal helpers of the text instrument readers (sed.cpp, sig.cpp): lines with their numbers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/text.h"

namespace roadbrdf::instrument_text {

struct Line {
  std::string_view text;  // without the line end ("\n", "\r\n")
  long number = 0;        // 1-based
};

// Split text into lines (LF or CRLF; a final line without an end is kept).
inline std::vector<Line> lines(std::string_view text) {
  std::vector<Line> out;
  long n = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.push_back({line, ++n});
    start = end + 1;
  }
  return out;
}

// The blanks rule of every reader (core/text.h): the row splitters use it too.
inline std::string_view trim(std::string_view s) { return trim_blanks(s); }

// "a, b ,c" -> {"a", "b", "c"}
inline std::vector<std::string> split_list(std::string_view s, char separator = ',') {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = s.find(separator, start);
    out.emplace_back(trim(s.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

// Text safe to print and to store as metadata: control and non-ASCII bytes become '?'.
inline std::string printable(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) c = '?';
  }
  return out;
}

}  // namespace roadbrdf::instrument_text
