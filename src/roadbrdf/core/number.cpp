#include "roadbrdf/core/number.h"
#include "roadbrdf/core/length.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace {

// from_chars over the whole text after an optional single '+'; `whole` tells whether it used the whole text.
std::errc read_double(std::string_view text, double& value, bool& whole) {
  whole = false;
  if (text.empty()) return std::errc::invalid_argument;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') {
    ++first;
    if (first == last || *first == '-' || *first == '+') return std::errc::invalid_argument;  // "+", "+-1", "++1"
  }
  const auto [ptr, ec] = std::from_chars(first, last, value);
  whole = ptr == last;
  return ec;
}

}  // namespace

bool parse_finite_double(std::string_view text, double& value) {
  bool whole = false;
  return read_double(text, value, whole) == std::errc() && whole && std::isfinite(value);
}

bool is_number_text(std::string_view text) {
  double value = 0.0;
  bool whole = false;
  const std::errc ec = read_double(text, value, whole);
  return whole && (ec == std::errc() || ec == std::errc::result_out_of_range);
}

double parse_length_mm(const std::string& text, const std::string& field) {
  std::string_view number = text;
  double scale = 1.0;  // millimetres per unit
  if (number.size() > 2 && number.substr(number.size() - 2) == "mm") {
    number.remove_suffix(2);
  } else if (number.size() > 2 && number.substr(number.size() - 2) == "cm") {
    number.remove_suffix(2);
    scale = 10.0;
  }
  double value = 0.0;
  if (!parse_finite_double(number, value) || !(value > 0.0)) {
    throw FieldError(field, "expected a length such as 60mm, got '" + text + "'");
  }
  return value * scale;
}

}  // namespace roadbrdf
