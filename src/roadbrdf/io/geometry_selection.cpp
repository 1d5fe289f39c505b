#include "roadbrdf/io/geometry_selection.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf {

namespace {

// An azimuth folded to [0, 360) degrees; values within the tolerance of 360 fold to 0.
double fold_azimuth(double degrees) {
  double a = std::fmod(degrees, 360.0);
  if (a < 0.0) a += 360.0;
  if (a > 360.0 - kAngleTolerance) a = 0.0;
  return a;
}

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// Scanner of a `where` expression that reports errors at a character position (1-based).
class SelectionScanner {
 public:
  SelectionScanner(const std::string& text, const std::string& field) : text_(text), field_(field) {}

  bool at_end() {
    skip_spaces();
    return pos_ >= text_.size();
  }
  [[noreturn]] void fail(const std::string& what, std::size_t at) const {
    throw FieldError(field_, fmt::format("{} at character {} of '{}'", what, at + 1, text_));
  }
  std::size_t position() const { return pos_; }

  std::string column() {
    skip_spaces();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    if (pos_ == start) fail("expected an angle column (" + column_list() + ")", start);
    std::string name = text_.substr(start, pos_ - start);
    const auto& names = geometry_column_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      fail("unknown column '" + name + "'" + did_you_mean(name, names) + "; columns: " + column_list(), start);
    }
    return name;
  }

  std::string comparison() {
    skip_spaces();
    const std::size_t start = pos_;
    for (const char* op : {"<=", ">=", "==", "!=", "<", ">", "="}) {
      const std::string o(op);
      if (text_.compare(pos_, o.size(), o) == 0) {
        pos_ += o.size();
        return o == "=" ? "==" : o;
      }
    }
    fail("expected a comparison (<, <=, >, >=, =, !=)", start);
  }

  double number() {
    skip_spaces();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != ',') ++pos_;
    double v = 0.0;
    if (!parse_finite_double(std::string_view(text_).substr(start, pos_ - start), v)) {
      fail("expected a finite number of degrees", start);
    }
    return v;
  }

  // After a condition: end, "," or the word "and".
  void separator() {
    skip_spaces();
    if (pos_ >= text_.size()) return;
    if (text_[pos_] == ',') {
      ++pos_;
      return;
    }
    if (text_.compare(pos_, 3, "and") == 0 && pos_ + 3 < text_.size() && is_space(text_[pos_ + 3])) {
      pos_ += 3;
      return;
    }
    fail("expected ',' or 'and' between conditions", pos_);
  }

 private:
  void skip_spaces() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
  }
  static std::string column_list() {
    std::string s;
    for (const auto& n : geometry_column_names()) s += (s.empty() ? "" : ", ") + n;
    return s;
  }

  const std::string& text_;
  const std::string& field_;
  std::size_t pos_ = 0;
};

bool compare(double x, const std::string& op, double v) {
  const bool equal = std::abs(x - v) <= kAngleTolerance;
  if (op == "==") return equal;
  if (op == "!=") return !equal;
  if (op == "<") return x < v && !equal;
  if (op == "<=") return x < v || equal;
  if (op == ">") return x > v && !equal;
  return x > v || equal;  // ">="
}

std::string format_angle(double degrees) { return fmt::format("{:.10g}", degrees); }

}  // namespace

const std::vector<std::string>& geometry_column_names() {
  static const std::vector<std::string> names = {"theta_i", "phi_i", "theta_r", "phi_r",
                                                 "gamma",   "alpha", "beta",    "delta"};
  return names;
}

namespace {

// The angles are stored in radians: 60 degrees comes back as 59.99999999999999. Columns are rounded to
// 1e-9 degrees, far below any goniometer's resolution, so that group keys are the numbers of the file.
double clean_degrees(double degrees) { return std::round(degrees * 1e9) / 1e9; }

double raw_column(const Geometry& g, const std::string& column) {
  if (column == "theta_i") return rad_to_deg(g.theta_i);
  if (column == "phi_i") return fold_azimuth(rad_to_deg(g.phi_i));
  if (column == "theta_r") return rad_to_deg(g.theta_r);
  if (column == "phi_r") return fold_azimuth(rad_to_deg(g.phi_r));
  const RoadAngles road = road_angles_from_geometry(g);
  if (column == "gamma") return road.gamma;
  if (column == "alpha") return road.alpha;
  if (column == "beta") return fold_azimuth(road.beta);
  if (column == "delta") return fold_azimuth(road.delta);
  throw InputError("unknown angle column '" + column + "'" + did_you_mean(column, geometry_column_names()));
}

}  // namespace

double geometry_column(const Geometry& g, const std::string& column) {
  return clean_degrees(raw_column(g, column)) + 0.0;  // + 0.0: no -0
}

bool GeometrySelection::matches(const Geometry& g) const {
  for (const auto& c : conditions) {
    if (!compare(geometry_column(g, c.column), c.op, c.value)) return false;
  }
  return true;
}

GeometrySelection parse_geometry_selection(const std::string& text, const std::string& field) {
  GeometrySelection s;
  s.text = text;
  SelectionScanner scan(text, field);
  if (scan.at_end()) scan.fail("empty selection", 0);
  while (!scan.at_end()) {
    GeometryCondition c;
    c.column = scan.column();
    c.op = scan.comparison();
    c.value = scan.number();
    s.conditions.push_back(c);
    const std::size_t before = scan.position();
    scan.separator();
    if (scan.position() != before && scan.at_end()) scan.fail("expected a condition after the separator", before);
  }
  return s;
}

std::string GeometryGroup::label() const {
  std::string s;
  for (const auto& [column, value] : key) s += (s.empty() ? "" : ",") + column + "=" + format_angle(value);
  return s;
}

std::vector<GeometryGroup> group_geometries(const std::vector<Geometry>& geometries,
                                            const std::vector<std::string>& columns, const std::string& field) {
  const auto& names = geometry_column_names();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (std::find(names.begin(), names.end(), columns[c]) == names.end()) {
      throw FieldError(field, "unknown column '" + columns[c] + "'" + did_you_mean(columns[c], names));
    }
    if (std::find(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(c), columns[c]) !=
        columns.begin() + static_cast<std::ptrdiff_t>(c)) {
      throw FieldError(field, "column '" + columns[c] + "' given twice");
    }
  }
  std::vector<GeometryGroup> groups;
  for (std::size_t g = 0; g < geometries.size(); ++g) {
    std::vector<double> values;
    values.reserve(columns.size());
    for (const auto& c : columns) values.push_back(geometry_column(geometries[g], c));
    auto same = [&values](const GeometryGroup& group) {
      for (std::size_t c = 0; c < values.size(); ++c) {
        if (std::abs(group.key[c].second - values[c]) > kAngleTolerance) return false;
      }
      return true;
    };
    auto it = std::find_if(groups.begin(), groups.end(), same);
    if (it == groups.end()) {
      GeometryGroup group;
      for (std::size_t c = 0; c < columns.size(); ++c) group.key.emplace_back(columns[c], values[c]);
      groups.push_back(group);
      it = groups.end() - 1;
    }
    it->indices.push_back(g);
  }
  std::stable_sort(groups.begin(), groups.end(), [](const GeometryGroup& a, const GeometryGroup& b) {
    for (std::size_t c = 0; c < a.key.size(); ++c) {
      if (a.key[c].second != b.key[c].second) return a.key[c].second < b.key[c].second;
    }
    return false;
  });
  return groups;
}

SpectralDataset subset_geometries(const SpectralDataset& data, const std::vector<std::size_t>& indices) {
  SpectralDataset out;
  out.wavelengths = data.wavelengths;
  out.convention = data.convention;
  out.metadata = data.metadata;
  out.comments = data.comments;
  const std::size_t M = data.wavelength_count();
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const std::size_t g = indices[k];
    if (g >= data.geometry_count() || (k > 0 && g <= indices[k - 1])) {
      throw InputError("subset_geometries: indices must be increasing and inside the dataset");
    }
    out.geometries.push_back(data.geometries[g]);
    out.brdf.insert(out.brdf.end(), data.brdf.begin() + static_cast<std::ptrdiff_t>(g * M),
                    data.brdf.begin() + static_cast<std::ptrdiff_t>((g + 1) * M));
    if (data.has_sigma()) {
      out.sigma.insert(out.sigma.end(), data.sigma.begin() + static_cast<std::ptrdiff_t>(g * M),
                       data.sigma.begin() + static_cast<std::ptrdiff_t>((g + 1) * M));
    }
  }
  return out;
}

}  // namespace roadbrdf
