#include "roadbrdf/core/range.h"

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf {

namespace {

std::string_view trim(std::string_view s) { return trim_blanks(s); }

[[noreturn]] void fail(std::string_view field, const std::string& detail) {
  throw FieldError(std::string(field), detail);
}

double number(std::string_view text, std::string_view field, std::string_view item) {
  const std::string_view t = trim(text);
  double v = 0.0;
  if (!parse_finite_double(t, v)) {
    if (t.size() == item.size()) fail(field, fmt::format("'{}' is not a finite number", t));
    fail(field, fmt::format("'{}' in '{}' is not a finite number", t, item));
  }
  return v;
}

void append_range(std::string_view item, std::string_view field, const RangeRules& rules, std::vector<double>& out) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = item.find(':', start);
    parts.push_back(item.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start));
    if (colon == std::string_view::npos) break;
    start = colon + 1;
  }
  if (parts.size() != 3) fail(field, fmt::format("'{}': a range is START:STOP:STEP", item));
  const double a = number(parts[0], field, item), b = number(parts[1], field, item),
               step = number(parts[2], field, item);
  if (!(step > 0.0)) fail(field, fmt::format("'{}': STEP must be > 0", item));
  if (b < a) fail(field, fmt::format("'{}': STOP is below START (for descending values, list them)", item));
  const double steps = (b - a) / step;  // finite: a, b, step finite and step > 0 (may be +inf if step is tiny)
  const double room = static_cast<double>(rules.max_count);
  if (!(steps < room)) {
    fail(field, fmt::format("'{}' has more than {} values", item, rules.max_count));
  }
  const double whole = std::round(steps);
  if (std::fabs(steps - whole) > 1e-9 * std::max(1.0, whole)) {
    const double below = a + std::floor(steps) * step, above = a + std::ceil(steps) * step;
    fail(field,
         fmt::format("'{}': STOP - START = {} is not a whole number of STEPs {} (a range includes both ends: "
                     "write {}:{}:{} or {}:{}:{}, or list the values)",
                     item, b - a, step, trim(parts[0]), below, trim(parts[2]), trim(parts[0]), above, trim(parts[2])));
  }
  const auto n = static_cast<std::size_t>(whole);
  if (out.size() + n + 1 > rules.max_count) {
    fail(field, fmt::format("more than {} values", rules.max_count));
  }
  for (std::size_t k = 0; k <= n; ++k) out.push_back(k == n ? b : a + static_cast<double>(k) * step);
}

}  // namespace

RangeRules wavelength_rules() {
  RangeRules r;
  r.positive = true;
  r.increasing = true;
  r.unit = "nm";
  return r;
}

void check_range_values(const std::vector<double>& values, std::string_view field, const RangeRules& rules) {
  if (values.empty()) fail(field, "no value given");
  if (values.size() > rules.max_count) fail(field, fmt::format("more than {} values", rules.max_count));
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    if (!std::isfinite(v)) fail(field, fmt::format("{} is not a finite number", v));
    if (rules.positive && !(v > 0.0))
      fail(field, fmt::format("{} must be > 0{}", v, rules.unit.empty() ? "" : " " + rules.unit));
    if ((rules.lower && v < *rules.lower) || (rules.upper && v > *rules.upper)) {
      const std::string lo = rules.lower ? fmt::format("{}", *rules.lower) : std::string("-inf");
      const std::string hi = rules.upper ? fmt::format("{}", *rules.upper) : std::string("inf");
      fail(field, fmt::format("{}{} is outside [{}, {}]{}", v, rules.unit.empty() ? "" : " " + rules.unit, lo, hi,
                              rules.unit.empty() ? "" : " " + rules.unit));
    }
    if (k > 0 && rules.increasing && !(v > values[k - 1])) {
      fail(field, fmt::format("values must increase, but {} follows {}", v, values[k - 1]));
    }
  }
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (std::fabs(sorted[k] - sorted[k - 1]) <= 1e-9 * std::max(1.0, std::fabs(sorted[k]))) {
      fail(field, fmt::format("{} is given twice", sorted[k]));
    }
  }
}

std::vector<double> parse_range_list(std::string_view text, std::string_view field, const RangeRules& rules) {
  std::vector<double> out;
  if (trim(text).empty()) fail(field, "no value given");
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item =
        trim(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (item.empty()) fail(field, fmt::format("empty item in '{}'", text));
    if (item.find(':') != std::string_view::npos) {
      append_range(item, field, rules, out);
    } else {
      out.push_back(number(item, field, item));
      if (out.size() > rules.max_count) fail(field, fmt::format("more than {} values", rules.max_count));
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  check_range_values(out, field, rules);
  return out;
}

std::pair<double, double> parse_interval(std::string_view text, std::string_view field) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || text.find(':', colon + 1) != std::string_view::npos) {
    fail(field, fmt::format("expected LOWER:UPPER, got '{}'", text));
  }
  const double lower = number(text.substr(0, colon), field, text);
  const double upper = number(text.substr(colon + 1), field, text);
  if (lower > upper) fail(field, fmt::format("'{}': LOWER is above UPPER", text));
  return {lower, upper};
}

}  // namespace roadbrdf
