#include "roadbrdf/io/dataset_dialect.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf {

namespace {

std::string_view trim(std::string_view s) { return trim_blanks(s); }

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

char delimiter_from_name(const std::string& name, const std::string& field) {
  if (name.empty() || name == "auto") return 0;
  if (name == "," || name == "comma") return ',';
  if (name == ";" || name == "semicolon") return ';';
  if (name == "tab" || name == "\t" || name == "\\t") return '\t';
  throw FieldError(field, fmt::format("'{}' is not one of auto, ',', ';', tab", name));
}

char decimal_from_name(const std::string& name, const std::string& field) {
  if (name.empty() || name == "auto") return 0;
  if (name == "." || name == "point") return '.';
  if (name == "," || name == "comma") return ',';
  throw FieldError(field, fmt::format("'{}' is not one of auto, '.', ','", name));
}

std::string delimiter_display(char c) {
  if (c == '\t') return "tab";
  return fmt::format("'{}'", c);
}

const std::vector<std::pair<std::string, std::vector<std::string>>>& column_aliases() {
  // A small table on purpose: names seen in instrument exports and published datasets, no guesses
  // that could map a column to the wrong angle. The road names need none.
  static const std::vector<std::pair<std::string, std::vector<std::string>>> table = {
      {"theta_i", {"thetai", "theta_in", "theta_inc", "inc", "incidence", "zenith_i"}},
      {"phi_i", {"phii", "phi_in", "phi_inc", "azimuth_i"}},
      {"theta_r", {"thetar", "theta_out", "theta_v", "thetav", "view", "zenith_r"}},
      {"phi_r", {"phir", "phi_out", "phi_v", "phiv", "azimuth_r"}},
      {"wavelength", {"wavelength_nm", "lambda", "wl"}},
      {"brdf", {"brdf_sr-1", "brdf_1/sr"}},
      {"sigma", {"uncertainty", "sigma_brdf"}},
  };
  return table;
}

std::string canonical_column_name(std::string_view raw, bool* angle_in_radians) {
  if (angle_in_radians) *angle_in_radians = false;
  std::string name;
  name.reserve(raw.size());
  for (char c : trim(raw)) name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  // Unit suffixes: "[deg]", "(deg)", " deg", "_deg" on angles, "nm" on wavelengths.
  for (const char* unit : {"[deg]", "(deg)", "[degree]", "(degree)", "[degrees]", "(degrees)"}) {
    if (ends_with(name, unit)) name = std::string(trim(name.substr(0, name.size() - std::strlen(unit))));
  }
  for (const char* unit : {"[rad]", "(rad)", "_rad"}) {
    if (ends_with(name, unit)) {
      if (angle_in_radians) *angle_in_radians = true;
      name = std::string(trim(name.substr(0, name.size() - std::strlen(unit))));
    }
  }
  if (ends_with(name, "_deg")) name.resize(name.size() - 4);
  for (const char* unit : {"[nm]", "(nm)", "nm"}) {
    if (ends_with(name, unit) && name.size() > std::strlen(unit)) {
      const std::string stem(trim(name.substr(0, name.size() - std::strlen(unit))));
      // Only a number or sigma_<number> carries a wavelength unit ("wavelength_nm" is an alias).
      const std::string_view digits = stem.rfind("sigma_", 0) == 0 ? std::string_view(stem).substr(6) : stem;
      if (!digits.empty() && (std::isdigit(static_cast<unsigned char>(digits.front())) || digits.front() == '.')) {
        name = stem;
      }
    }
  }
  for (const auto& [canonical, aliases] : column_aliases()) {
    if (name == canonical) return name;
    if (std::find(aliases.begin(), aliases.end(), name) != aliases.end()) return canonical;
  }
  return name;
}

bool CellScanner::next(std::string_view& text, long& column) {
  if (done_) return false;
  const std::size_t start = position_;
  std::size_t end = line_.find(delimiter_, start);
  if (end == std::string_view::npos) {
    end = line_.size();
    done_ = true;
  }
  position_ = end + 1;
  std::size_t b = start, e = end;
  while (b < e && is_blank(line_[b]) && line_[b] != delimiter_) ++b;
  while (e > b && is_blank(line_[e - 1]) && line_[e - 1] != delimiter_) --e;
  text = line_.substr(b, e - b);
  column = static_cast<long>(b + 1);
  return true;
}

char detect_delimiter(std::string_view line, bool (*known)(std::string_view, char)) {
  static constexpr std::array<char, 3> kCandidates = {',', ';', '\t'};
  std::vector<char> present;
  for (char c : kCandidates) {
    if (line.find(c) != std::string_view::npos) present.push_back(c);
  }
  if (present.empty()) return ',';
  if (present.size() == 1) return present.front();
  // Several: the delimiter is the one that splits the header into names the reader knows.
  std::vector<char> fitting;
  for (char c : present) {
    CellScanner cells(line, c);
    std::string_view text;
    long column = 0;
    bool all = true;
    while (all && cells.next(text, column)) all = known(canonical_column_name(text), c);
    if (all) fitting.push_back(c);
  }
  if (fitting.size() == 1) return fitting.front();
  std::string list;
  for (char c : present) list += (list.empty() ? "" : " and ") + delimiter_display(c);
  throw InputError(
      fmt::format("cannot tell the delimiter of the header line (it holds {}{}): pass `delimiter` "
                  "',' | ';' | tab (and `decimal` '.' | ',' for the numbers)",
                  list, fitting.empty() ? ", and no choice gives known column names" : ""));
}

NumberParser::NumberParser(char delimiter, char decimal) : delimiter_(delimiter), decimal_(decimal) {
  if (delimiter_ == ',') decimal_ = '.';
}

bool NumberParser::parse_point(std::string_view text, double& value) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') {
    ++first;
    if (first == last || *first == '-' || *first == '+') return false;
  }
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last && std::isfinite(value);
}

bool NumberParser::parse_slow(std::string_view text, double& value, long line, long column) {
  const bool has_point = text.find('.') != std::string_view::npos;
  const bool has_comma = text.find(',') != std::string_view::npos;
  if (has_point && has_comma) return false;  // "1.234,5": thousands separators are not numbers here
  if (decimal_ == 0 && (has_point || has_comma)) {
    decimal_ = has_point ? '.' : ',';
    decided_line_ = line;
    decided_column_ = column;
  }
  if (decimal_ == '.') return parse_point(text, value);
  if (has_point) return false;  // a decimal point in a decimal-comma file
  if (!has_comma) return parse_point(text, value);
  // Decimal comma: the same text with '.' (cells are short; a longer one is no number).
  std::array<char, 128> buffer{};
  if (text.size() > buffer.size()) return false;
  std::copy(text.begin(), text.end(), buffer.begin());
  std::replace(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(text.size()), ',', '.');
  return parse_point(std::string_view(buffer.data(), text.size()), value);
}

std::string NumberParser::hint(std::string_view text) const {
  const char decimal = decimal_ == 0 ? '.' : decimal_;
  const char other = decimal == '.' ? ',' : '.';
  if (text.find(other) == std::string_view::npos) return "";
  if (decided_line_ > 0) {
    return fmt::format(
        " (it uses '{}' as the decimal separator, but line {} column {} used '{}': pass `decimal` "
        "'.' or `decimal` ',' to say which one the file uses)",
        other, decided_line_, decided_column_, decimal);
  }
  return fmt::format(" (the decimal separator is '{}'{}; see `decimal`)", decimal,
                     delimiter_ == ',' ? " in a ','-separated file" : "");
}

}  // namespace roadbrdf
