// The long dataset format, and the per-cell helpers of both formats (dataset_read_support.h).
#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/huge_pages.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/io/dataset_read_support.h"

namespace roadbrdf::dataset_read {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool is_missing_text(std::string_view t) {
  if (t.empty()) return true;
  if (t.size() > 4) return false;
  std::string lower;
  for (char c : t) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "nan" || lower == "na" || lower == "-nan";
}

std::string trim_copy(const std::string& s) { return trimmed_copy(s); }

void default_warn(const std::string& message) { route_warning(message); }

// Why a cell is no number, for an error message: out of range, not finite, or not a number at all.
[[noreturn]] void not_a_number(Reading& r, std::string_view text, long column, std::string_view what) {
  if (text.empty()) r.reader.fail(column, fmt::format("empty cell where a {} was expected", what));
  double value = 0.0;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ptr == last && ec == std::errc::result_out_of_range) {
    r.reader.fail(column, fmt::format("'{}' is out of the range of double-precision numbers ({})", text, what));
  }
  if (ptr == last && ec == std::errc() && !std::isfinite(value)) {
    r.reader.fail(column, fmt::format("'{}' is not a finite {}", text, what));
  }
  r.reader.fail(column, fmt::format("'{}' is not a {}{}", text, what, r.numbers.hint(text)));
}

}  // namespace

GeometryKey key_of(const Geometry& g) {
  auto az = [](double phi_rad, double theta_rad) {
    if (theta_rad == 0.0) return 0.0;
    double d = std::fmod(rad_to_deg(phi_rad), 360.0);
    if (d < 0) d += 360.0;
    if (d >= 360.0 - 5e-8) d = 0.0;
    return d;
  };
  auto q = [](double deg) { return static_cast<long long>(std::llround(deg * 1e7)); };
  return {{q(rad_to_deg(g.theta_i)), q(az(g.phi_i, g.theta_i)), q(rad_to_deg(g.theta_r)), q(az(g.phi_r, g.theta_r))}};
}

void read_metadata(Reading& r, SpectralDataset& d) {
  const auto& comments = r.reader.comments();
  const auto& lines = r.reader.comment_lines();
  for (std::size_t k = 0; k < comments.size(); ++k) {
    const std::string& c = comments[k];
    if (!is_metadata_comment(c)) {
      // A free comment is kept (in order) for the writers, except the banner they write themselves.
      const std::string text = trim_copy(c);
      if (text.rfind(kDatasetBanner, 0) != 0) d.comments.push_back(text);
      continue;
    }
    const auto colon = c.find(':');
    const std::string key = trim_copy(c.substr(0, colon));
    const std::string value = trim_copy(c.substr(colon + 1));
    if (d.metadata.count(key)) {
      throw FileError(r.reader.path(), k < lines.size() ? lines[k] : 0, 0,
                      fmt::format("metadata key '{}' is given twice", key));
    }
    // With a quantity other than BRDF the units line describes that quantity (kept as source_units).
    if (key == "units" && !r.options.any_units && r.options.quantity == DatasetQuantity::kBrdf) {
      if (value != "sr^-1" && value != "1/sr" && value != "sr-1") {
        throw FileError(r.reader.path(), k < lines.size() ? lines[k] : 0, 0,
                        fmt::format("units '{}' are not supported: a BRDF dataset holds sr^-1 (a reflectance "
                                    "factor BRF = pi BRDF is read with `quantity` brf, in percent with percent-brf)",
                                    value));
      }
    }
    // A reflectance factor has no unit: a file that says sr^-1 holds a BRDF, whatever the options say.
    const bool factor =
        r.options.quantity == DatasetQuantity::kBrf || r.options.quantity == DatasetQuantity::kPercentBrf;
    if (key == "units" && factor && (value == "sr^-1" || value == "1/sr" || value == "sr-1")) {
      throw FileError(r.reader.path(), k < lines.size() ? lines[k] : 0, 0,
                      fmt::format("units '{}' are those of a BRDF, but `quantity` is {} (a reflectance factor, "
                                  "without unit): read the file as brdf, or correct its units line",
                                  value, name_of(r.options.quantity)));
    }
    d.metadata[key] = value;
  }
  if (!d.metadata.count("units")) d.metadata["units"] = "sr^-1";
}

AngleCells initial_angles(const Reading& r) {
  AngleCells a;
  for (std::size_t k = 0; k < 4; ++k) {
    if (r.fixed[k]) {
      a.value[k] = r.fixed_value[k];
      a.text[k] = "(fixed)";
    }
  }
  return a;
}

double number(Reading& r, std::string_view text, long column, std::string_view what) {
  double v = 0.0;
  if (r.numbers.parse(text, v, r.reader.line_number(), column)) return v;
  not_a_number(r, text, column, what);
}

double parse_brdf(Reading& r, std::string_view text, long column) {
  double v = 0.0;
  if (r.numbers.parse(text, v, r.reader.line_number(), column)) {
    if (v < 0.0 && r.stats.negative_values++ == 0) {
      r.first_negative = fmt::format("{}:{}:{}", r.reader.path(), r.reader.line_number(), column);
    }
    if (v > kImplausibleBrdf) {
      if (r.stats.implausible_values++ == 0) {
        r.first_large = fmt::format("{}:{}:{}", r.reader.path(), r.reader.line_number(), column);
      }
      r.largest = std::max(r.largest, v);
    }
    return v;
  }
  if (r.options.allow_missing && is_missing_text(text)) {
    if (r.stats.missing_values++ == 0) {
      r.first_missing = fmt::format("{}:{}:{}", r.reader.path(), r.reader.line_number(), column);
    }
    return kNaN;
  }
  if (text.empty()) r.reader.fail(column, "empty cell where a BRDF value [sr^-1] was expected");
  not_a_number(r, text, column, "BRDF value [sr^-1]");
}

double parse_sigma(Reading& r, std::string_view text, long column) {
  double v = 0.0;
  if (r.numbers.parse(text, v, r.reader.line_number(), column)) {
    if (v < 0.0) r.reader.fail(column, fmt::format("'{}': an uncertainty cannot be negative", text));
    return v;
  }
  if (r.options.allow_missing && is_missing_text(text)) return kNaN;
  if (text.empty()) r.reader.fail(column, "empty cell where an uncertainty [sr^-1] was expected");
  not_a_number(r, text, column, "uncertainty [sr^-1]");
}

Geometry parse_geometry(Reading& r, AngleConvention convention, const AngleCells& a) {
  static const char* zenith_names[4] = {"theta_i", "phi_i", "theta_r", "phi_r"};
  static const char* road_names[4] = {"gamma", "alpha", "beta", "delta"};
  const bool road = convention == AngleConvention::kRoad;
  // Zenith-range check of the raw angle cells, so that the error points at the offending column.
  for (int k : {0, 2}) {
    const std::size_t col = road ? (k == 0 ? 0 : 1) : static_cast<std::size_t>(k);
    const double v = a.value[col];
    if (v < 0.0 || v > 90.0) {
      r.reader.fail(a.column[col], fmt::format("{} = '{}' is outside [0, 90] deg ({} zenith angle)",
                                               road ? road_names[col] : zenith_names[col], a.text[col],
                                               road && col == 1 ? "90 - viewing" : "a"));
    }
  }
  try {
    return geometry_from_angle_values(convention, a.value.data());
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    r.reader.fail(a.column[0], e.what());
  }
}

void ragged(Reading& r, std::string_view line, std::size_t expected, std::string_view text, long column, bool extra) {
  const std::size_t count = static_cast<std::size_t>(std::count(line.begin(), line.end(), r.delimiter)) + 1;
  if (extra) {
    r.reader.fail(
        column, fmt::format("row has {} cells but the header has {} columns (extra cell '{}')", count, expected, text));
  }
  r.reader.fail(
      column + static_cast<long>(text.size()),
      fmt::format("row has {} cells but the header has {} columns (row ends after '{}')", count, expected, text));
}

std::string duplicates_hint() { return "ask for averaging of duplicates (`average_duplicates`) to average them"; }

double relative_spread(double lo, double hi, double mean) {
  if (hi == lo) return 0.0;
  return (hi - lo) / std::fabs(mean);
}

Repeatability repeatability_of(std::vector<std::vector<double>>& spreads, std::size_t geometries) {
  Repeatability out;
  out.geometries = geometries;
  if (geometries == 0) return out;
  for (auto& s : spreads) {
    if (s.empty()) {
      out.median_relative_spread.push_back(kNaN);
      out.max_relative_spread.push_back(kNaN);
      continue;
    }
    const std::size_t h = s.size() / 2;
    std::nth_element(s.begin(), s.begin() + static_cast<long>(h), s.end());
    double median = s[h];
    if (s.size() % 2 == 0) median = 0.5 * (median + *std::max_element(s.begin(), s.begin() + static_cast<long>(h)));
    out.median_relative_spread.push_back(median);
    out.max_relative_spread.push_back(*std::max_element(s.begin(), s.end()));
  }
  return out;
}

void set_pooled_relative_sd(Repeatability& out, const std::vector<double>& squares,
                            const std::vector<std::size_t>& degrees_of_freedom) {
  out.degrees_of_freedom = degrees_of_freedom;
  out.pooled_relative_sd.resize(squares.size());
  for (std::size_t j = 0; j < squares.size(); ++j) {
    out.pooled_relative_sd[j] =
        degrees_of_freedom[j] == 0 ? kNaN : std::sqrt(squares[j] / static_cast<double>(degrees_of_freedom[j]));
  }
}

void finish_warnings(Reading& r, const SpectralDataset& d) {
  auto warn = r.options.warn ? r.options.warn : default_warn;
  const std::size_t total = d.brdf.size();
  if (r.stats.negative_values > 0) {
    warn(fmt::format("{}: {} of {} BRDF values are negative (kept: measurement noise; first at {})", r.reader.path(),
                     r.stats.negative_values, total, r.first_negative));
  }
  if (r.stats.missing_values > 0) {
    warn(fmt::format("{}: {} of {} BRDF values are missing (kept as NaN; first at {})", r.reader.path(),
                     r.stats.missing_values, total, r.first_missing));
  }
  if (r.stats.absent_rows > 0) {
    warn(fmt::format("{}: {} (geometry, wavelength) pairs of {} have no row (kept as missing NaN cells; first: {})",
                     r.reader.path(), r.stats.absent_rows, total, r.first_absent));
  }
  if (!r.ignored_columns.empty()) {
    std::string listed;
    for (std::size_t k = 0; k < std::min<std::size_t>(r.ignored_columns.size(), 5); ++k) {
      listed += fmt::format("{}'{}'", k ? ", " : "", r.ignored_columns[k]);
    }
    warn(fmt::format("{}: {} column(s) hold no dataset field and were not read: {}{} (map one with `columns`)",
                     r.reader.path(), r.ignored_columns.size(), listed, r.ignored_columns.size() > 5 ? ", ..." : ""));
  }
  if (r.stats.averaged_duplicate_rows > 0) {
    warn(fmt::format("{}: {} duplicate geometry rows were averaged", r.reader.path(), r.stats.averaged_duplicate_rows));
  }
  if (r.stats.implausible_values > 0) {
    warn(
        fmt::format("{}: {} of {} BRDF values are above {:g} sr^-1 (largest {:g}, first at {}): only a mirror or "
                    "retroreflector peak is that bright; check that the file holds a BRDF in sr^-1 (not a radiance, "
                    "counts or a reflectance in percent)",
                    r.reader.path(), r.stats.implausible_values, total, kImplausibleBrdf, r.largest, r.first_large));
  }
  const char* wavelength_place = r.long_format ? "in the 'wavelength' column" : "in the header";
  if (!d.wavelengths.empty() && d.wavelengths.back() < kMetreLikeWavelength) {
    r.stats.metre_wavelengths = true;
    warn(
        fmt::format("{}: every wavelength {} is below {:g} nm ({:g}-{:g}): they look like metres; datasets "
                    "hold nm (multiply the wavelengths {} by 1e9)",
                    r.reader.path(), wavelength_place, kMetreLikeWavelength, d.wavelengths.front(),
                    d.wavelengths.back(), wavelength_place));
  } else if (!d.wavelengths.empty() && d.wavelengths.back() < kMicrometreLikeWavelength) {
    r.stats.micrometre_wavelengths = true;
    warn(
        fmt::format("{}: every wavelength {} is below {:g} nm ({:g}-{:g}): they look like micrometres; datasets "
                    "hold nm (multiply the wavelengths {} by 1000)",
                    r.reader.path(), wavelength_place, kMicrometreLikeWavelength, d.wavelengths.front(),
                    d.wavelengths.back(), wavelength_place));
  }
  // Zenith angles in radians lie within [0, pi/2], azimuths within +-2 pi: judged separately, so that
  // azimuths up to pi or 2 pi do not hide radian zeniths. Azimuths are compared modulo 360 (a file's
  // -1 rad reads as 359 "deg").
  double largest_zenith = 0.0, largest_azimuth = 0.0;
  const bool road = d.convention == AngleConvention::kRoad;
  for (const Geometry& g : d.geometries) {
    double a[4];
    angle_values_of_geometry(g, d.convention, a);
    // zenith convention: theta_i, phi_i, theta_r, phi_r; road: gamma, alpha (zenith-like), beta, delta.
    const double zeniths[2] = {a[0], road ? a[1] : a[2]};
    const double azimuths[2] = {road ? a[2] : a[1], a[3]};
    for (double v : zeniths) largest_zenith = std::max(largest_zenith, std::fabs(v));
    for (double v : azimuths) largest_azimuth = std::max(largest_azimuth, std::fabs(std::remainder(v, 360.0)));
  }
  if (!d.geometries.empty() && largest_zenith > 0.0 && largest_zenith <= kRadianLikeZenith &&
      largest_azimuth <= kRadianLikeAzimuth) {
    r.stats.radian_angles = true;
    warn(
        fmt::format("{}: every zenith angle is within {:g} deg (largest {:g}) and every azimuth within +-{:g} deg "
                    "(largest {:g}): they look like radians; datasets hold degrees (multiply the angles by 180/pi)",
                    r.reader.path(), kRadianLikeZenith, largest_zenith, kRadianLikeAzimuth, largest_azimuth));
  }
}

// ---- long ---------------------------------------------------------------------------------------

namespace {

// The role of each column of a long dataset: 0-3 the angles, 4 wavelength, 5 brdf, 6 sigma, 7 not read.
constexpr int kIgnoredColumn = 7;
struct LongLayout {
  std::vector<int> role;
  bool with_sigma = false;
};

LongLayout long_layout(Reading& r, const std::vector<LongColumn>& columns, std::size_t column_count,
                       const std::vector<std::size_t>& angle_columns) {
  CsvReader& reader = r.reader;
  std::size_t wl_col = column_count, brdf_col = column_count, sigma_col = column_count;
  for (const auto& c : columns) {
    std::size_t* target = c.canonical == "wavelength" ? &wl_col
                          : c.canonical == "brdf"     ? &brdf_col
                          : c.canonical == "sigma"    ? &sigma_col
                                                      : nullptr;
    if (!target && ignores_other_columns(r.options)) {
      r.ignored_columns.push_back(c.text);
      continue;
    }
    if (!target) {
      reader.fail(c.column, fmt::format("unexpected column '{}' in a long dataset (expected the angle columns and "
                                        "wavelength,brdf[,sigma])",
                                        c.text));
    }
    if (*target != column_count) reader.fail(c.column, fmt::format("column '{}' appears twice", c.text));
    *target = c.index;
  }
  if (brdf_col == column_count) {
    throw FileError(reader.path(), reader.line_number(), 0, "long dataset header lacks the 'brdf' column");
  }
  LongLayout l;
  l.with_sigma = sigma_col != column_count;
  l.role.assign(column_count, kIgnoredColumn);
  for (int k = 0; k < 4; ++k) {
    const std::size_t c = angle_columns[static_cast<std::size_t>(k)];
    if (c != kFixedAngle) l.role[c] = k;
  }
  l.role[wl_col] = 4;
  l.role[brdf_col] = 5;
  if (l.with_sigma) l.role[sigma_col] = 6;
  return l;
}

// One data row: a value (and its uncertainty) at one geometry and wavelength.
struct Record {
  std::size_t geometry;
  double wavelength, brdf, sigma;
  long line, column;
};

// The cells of one row: the angle cells into angles, the wavelength, BRDF and uncertainty into rec.
void read_long_row(Reading& r, std::string_view line, const std::vector<int>& role, AngleCells& angles, Record& rec) {
  const std::size_t column_count = role.size();
  CellScanner cells(line, r.delimiter);
  std::string_view text;
  long column = 0;
  std::size_t k = 0;
  while (cells.next(text, column)) {
    if (k == column_count) ragged(r, line, column_count, text, column, true);
    const int what = role[k++];
    if (what == kIgnoredColumn) continue;
    if (what < 4) {
      angles.text[static_cast<std::size_t>(what)] = text;
      angles.column[static_cast<std::size_t>(what)] = column;
      angles.value[static_cast<std::size_t>(what)] = number(r, text, column, "angle in degrees");
    } else if (what == 4) {
      rec.wavelength = number(r, text, column, "wavelength in nm");
      if (rec.wavelength <= 0.0) r.reader.fail(column, fmt::format("wavelength '{}' nm is not positive", text));
    } else if (what == 5) {
      rec.brdf = parse_brdf(r, text, column);
    } else {
      rec.sigma = parse_sigma(r, text, column);
    }
  }
  if (k != column_count) ragged(r, line, column_count, text, column, false);
}

// Every data row as a record; the geometries into d in order of first appearance, with the line of
// each one's first row in first_lines.
std::vector<Record> read_records(Reading& r, const std::vector<int>& role, SpectralDataset& d,
                                 std::vector<long>& first_lines) {
  CsvReader& reader = r.reader;
  std::vector<Record> records;
  std::unordered_map<GeometryKey, std::size_t, GeometryKeyHash> seen;
  AngleCells angles = initial_angles(r);
  std::string_view line;
  while (reader.next_line(line)) {
    Record rec{0, 0.0, 0.0, 0.0, 0, 0};
    read_long_row(r, line, role, angles, rec);
    const Geometry g = parse_geometry(r, d.convention, angles);
    const auto [it, inserted] = seen.emplace(key_of(g), d.geometries.size());
    if (inserted) {
      d.geometries.push_back(g);
      first_lines.push_back(reader.line_number());
    }
    rec.geometry = it->second;
    rec.line = reader.line_number();
    rec.column = angles.column[0];
    records.push_back(rec);
  }
  if (records.empty()) throw FileError(reader.path(), reader.line_number(), 0, "file has a header but no data rows");
  return records;
}

// The records with their wavelength grid (the distinct wavelengths, ascending), each record's index
// on it, and the records' order by geometry, wavelength and line: the shape checks work on these,
// so that memory stays proportional to the file, whatever geometries x wavelengths would be.
struct RecordTable {
  std::vector<Record> records;
  std::vector<double> wavelengths;
  std::vector<std::uint32_t> wl_index;
  std::vector<std::size_t> order;

  // Records a and b are of one (geometry, wavelength) pair.
  bool same(std::size_t a, std::size_t b) const {
    return records[a].geometry == records[b].geometry && wl_index[a] == wl_index[b];
  }
};

RecordTable record_table(std::vector<Record> records) {
  RecordTable t;
  t.records = std::move(records);
  const auto& rec = t.records;
  auto& wls = t.wavelengths;
  wls.reserve(rec.size());
  for (const auto& x : rec) wls.push_back(x.wavelength);
  std::sort(wls.begin(), wls.end());
  wls.erase(std::unique(wls.begin(), wls.end()), wls.end());
  t.wl_index.resize(rec.size());
  for (std::size_t k = 0; k < rec.size(); ++k) {
    t.wl_index[k] =
        static_cast<std::uint32_t>(std::lower_bound(wls.begin(), wls.end(), rec[k].wavelength) - wls.begin());
  }
  t.order.resize(rec.size());
  for (std::size_t k = 0; k < t.order.size(); ++k) t.order[k] = k;
  std::sort(t.order.begin(), t.order.end(), [&](std::size_t a, std::size_t b) {
    if (rec[a].geometry != rec[b].geometry) return rec[a].geometry < rec[b].geometry;
    if (t.wl_index[a] != t.wl_index[b]) return t.wl_index[a] < t.wl_index[b];
    return a < b;
  });
  return t;
}

// Duplicates: report the first one in file order (a group's members are in file order).
void refuse_duplicates(Reading& r, const RecordTable& t) {
  const auto& order = t.order;
  std::size_t worst = t.records.size(), earlier = 0;
  for (std::size_t k = 0; k < order.size();) {
    std::size_t e = k + 1;
    while (e < order.size() && t.same(order[e], order[k])) ++e;
    if (e - k > 1 && order[k + 1] < worst) {
      worst = order[k + 1];
      earlier = order[k];
    }
    k = e;
  }
  if (worst < t.records.size()) {
    const auto& rec = t.records[worst];
    throw FileError(r.reader.path(), rec.line, rec.column,
                    fmt::format("duplicate value: this geometry already has wavelength {} nm at line {} ({})",
                                rec.wavelength, t.records[earlier].line, duplicates_hint()));
  }
}

// Completeness: a (geometry, wavelength) pair without a row is a measurement that was not made,
// a missing cell like an empty or "nan" one (counted and warned about), unless missing values
// are refused. A table that would be more than half missing is refused too: its geometries are on
// different wavelength grids, and the table would take memory out of proportion to the file.
void check_completeness(Reading& r, const RecordTable& t, std::size_t n, const std::vector<long>& first_lines) {
  const auto& order = t.order;
  const auto& wls = t.wavelengths;
  const std::size_t m = wls.size();
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < order.size(); ++k) distinct += k == 0 || !t.same(order[k], order[k - 1]);
  const bool too_sparse = n * m > 2 * distinct;
  std::size_t k = 0;
  for (std::size_t g = 0; g < n; ++g) {
    for (std::size_t j = 0; j < m; ++j) {
      if (k >= order.size() || t.records[order[k]].geometry != g || t.wl_index[order[k]] != j) {
        if (!r.options.allow_missing) {
          throw FileError(r.reader.path(), first_lines[g], 0,
                          fmt::format("the geometry first given on this line has no value at wavelength {} nm "
                                      "(missing values are refused here)",
                                      wls[j]));
        }
        if (too_sparse) {
          throw FileError(r.reader.path(), first_lines[g], 0,
                          fmt::format("the geometry first given on this line has no value at wavelength {} nm, "
                                      "and {} of the {} x {} (geometry, wavelength) pairs have no row: the "
                                      "geometries are on different wavelength grids (put them on one grid first)",
                                      wls[j], n * m - distinct, n, m));
        }
        if (r.stats.absent_rows++ == 0) {
          r.first_absent = fmt::format("the geometry of {}:{} at {} nm", r.reader.path(), first_lines[g], wls[j]);
        }
        continue;
      }
      while (k < order.size() && t.records[order[k]].geometry == g && t.wl_index[order[k]] == j) ++k;
    }
  }
}

// The geometries x wavelengths table of d from the records. Rows per cell, and how many of them
// were measured: a duplicate average is over the measured values; a cell no row measured stays
// missing (NaN).
void fill_table(Reading& r, const RecordTable& t, bool with_sigma, SpectralDataset& d) {
  const std::size_t n = d.geometries.size(), m = t.wavelengths.size();
  d.wavelengths = t.wavelengths;
  reserve_on_huge_pages(d.brdf, n * m);
  d.brdf.assign(n * m, 0.0);
  if (with_sigma) {
    reserve_on_huge_pages(d.sigma, n * m);
    d.sigma.assign(n * m, 0.0);
  }
  std::vector<std::uint32_t> rows(n * m, 0), count(n * m, 0);
  // Smallest and largest value of each cell (duplicates are averaged only when asked for).
  std::vector<double> lo, hi;
  if (r.options.average_duplicates) {
    lo.assign(n * m, kNaN);
    hi.assign(n * m, kNaN);
  }
  for (std::size_t k = 0; k < t.records.size(); ++k) {
    const auto& rec = t.records[k];
    const std::size_t idx = rec.geometry * m + t.wl_index[k];
    if (rows[idx]++ > 0) ++r.stats.averaged_duplicate_rows;
    if (std::isnan(rec.brdf)) continue;
    if (!lo.empty()) {
      lo[idx] = count[idx] == 0 ? rec.brdf : std::min(lo[idx], rec.brdf);
      hi[idx] = count[idx] == 0 ? rec.brdf : std::max(hi[idx], rec.brdf);
    }
    ++count[idx];
    d.brdf[idx] += rec.brdf;
    if (with_sigma) d.sigma[idx] += rec.sigma * rec.sigma;
  }
  for (std::size_t idx = 0; idx < n * m; ++idx) {
    if (count[idx] == 0) {
      d.brdf[idx] = kNaN;
      if (with_sigma) d.sigma[idx] = kNaN;
      continue;
    }
    d.brdf[idx] /= count[idx];
    if (with_sigma) d.sigma[idx] = std::sqrt(d.sigma[idx]) / count[idx];
  }
  if (lo.empty()) return;
  std::vector<std::vector<double>> spreads(m);
  std::size_t duplicated = 0;
  for (std::size_t g = 0; g < n; ++g) {
    bool any = false;
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t idx = g * m + j;
      any = any || rows[idx] > 1;
      if (count[idx] >= 2) spreads[j].push_back(relative_spread(lo[idx], hi[idx], d.brdf[idx]));
    }
    if (any) ++duplicated;
  }
  r.stats.repeatability = repeatability_of(spreads, duplicated);
  if (duplicated == 0) return;
  // The squared relative deviations of the duplicated cells from their means (a second pass: the
  // means are known now).
  std::vector<double> squares(m, 0.0);
  std::vector<std::size_t> dof(m, 0);
  for (std::size_t k = 0; k < t.records.size(); ++k) {
    const auto& rec = t.records[k];
    const std::size_t idx = rec.geometry * m + t.wl_index[k];
    if (count[idx] < 2 || std::isnan(rec.brdf) || d.brdf[idx] == 0.0) continue;
    const double deviation = (rec.brdf - d.brdf[idx]) / d.brdf[idx];
    squares[t.wl_index[k]] += deviation * deviation;
  }
  for (std::size_t idx = 0; idx < n * m; ++idx) {
    if (count[idx] >= 2 && d.brdf[idx] != 0.0) dof[idx % m] += count[idx] - 1;
  }
  set_pooled_relative_sd(r.stats.repeatability, squares, dof);
  r.stats.repeatability.cell_counts = std::move(count);
}

}  // namespace

SpectralDataset read_long(Reading& r, const std::vector<LongColumn>& columns, std::size_t column_count,
                          const std::vector<std::size_t>& angle_columns, AngleConvention convention) {
  SpectralDataset d;
  d.convention = convention;
  r.long_format = true;
  read_metadata(r, d);
  const LongLayout layout = long_layout(r, columns, column_count, angle_columns);
  // One record per row; the table is allocated only once its shape is known to be complete.
  std::vector<long> first_lines;
  const RecordTable table = record_table(read_records(r, layout.role, d, first_lines));
  if (!r.options.average_duplicates) refuse_duplicates(r, table);
  check_completeness(r, table, d.geometries.size(), first_lines);
  fill_table(r, table, layout.with_sigma, d);
  if (r.stats.averaged_duplicate_rows)
    d.metadata["averaged_duplicate_rows"] = std::to_string(r.stats.averaged_duplicate_rows);
  return d;
}

}  // namespace roadbrdf::dataset_read
