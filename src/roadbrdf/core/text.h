// The one rule every reader uses for blanks around cells, keys and values: space, horizontal tab and
// carriage return (a CR left by a CRLF line end, or a stray one, is never part of a value). Trimming
// and splitting on whitespace share it, so that a line one of them calls blank is blank for the other.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace roadbrdf {

// The blank characters as a set, for find_first_not_of and the like.
inline constexpr std::string_view kBlankCharacters = " \t\r";

constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// `s` without leading and trailing blanks; `offset` receives the index of the first kept character
// (s.size() for an all-blank line).
constexpr std::string_view trim_blanks(std::string_view s, std::size_t& offset) {
  std::size_t b = 0;
  while (b < s.size() && is_blank(s[b])) ++b;
  std::size_t e = s.size();
  while (e > b && is_blank(s[e - 1])) --e;
  offset = b;
  return s.substr(b, e - b);
}

constexpr std::string_view trim_blanks(std::string_view s) {
  std::size_t offset = 0;
  return trim_blanks(s, offset);
}

inline std::string trimmed_copy(std::string_view s) { return std::string(trim_blanks(s)); }

}  // namespace roadbrdf
