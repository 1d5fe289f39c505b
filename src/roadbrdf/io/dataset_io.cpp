#include "roadbrdf/io/dataset_io.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <ostream>
#include <unordered_map>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/csv.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Key identifying a geometry: zenith angles and azimuths (azimuth mod 360, undefined azimuth at
// zenith 0 set to 0), rounded to 1e-7 degree.
struct GeometryKey {
  std::array<long long, 4> v;
  bool operator==(const GeometryKey& o) const { return v == o.v; }
};
struct GeometryKeyHash {
  std::size_t operator()(const GeometryKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (long long x : k.v) h = (h ^ static_cast<std::size_t>(x)) * 1099511628211ull;
    return h;
  }
};

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

bool is_missing_text(std::string_view t) {
  if (t.empty()) return true;
  std::string lower;
  for (char c : t) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "nan" || lower == "na" || lower == "-nan";
}

bool parse_double(std::string_view text, double& value) {
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last && std::isfinite(value);
}

std::string trim_copy(const std::string& s) {
  std::size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  std::size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool is_metadata_key(const std::string& key) {
  if (key.empty()) return false;
  for (char c : key) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  }
  return true;
}

void default_warn(const std::string& message) { fmt::print(stderr, "roadbrdf: warning: {}\n", message); }

struct Reading {
  const DatasetReadOptions& options;
  DatasetReadStats& stats;
  CsvReader& reader;
  std::string first_negative;  // location of the first negative value
  std::string first_missing;
};

// Metadata from the comment lines seen before the header.
void read_metadata(Reading& r, SpectralDataset& d) {
  const auto& comments = r.reader.comments();
  const auto& lines = r.reader.comment_lines();
  for (std::size_t k = 0; k < comments.size(); ++k) {
    const std::string& c = comments[k];
    const auto colon = c.find(':');
    if (colon == std::string::npos) continue;  // a free comment
    const std::string key = trim_copy(c.substr(0, colon));
    if (!is_metadata_key(key)) continue;  // a free comment containing ':'
    const std::string value = trim_copy(c.substr(colon + 1));
    if (d.metadata.count(key)) {
      throw FileError(r.reader.path(), k < lines.size() ? lines[k] : 0, 0,
                      fmt::format("metadata key '{}' is given twice", key));
    }
    if (key == "units" && !r.options.any_units) {
      if (value != "sr^-1" && value != "1/sr" && value != "sr-1") {
        throw FileError(r.reader.path(), k < lines.size() ? lines[k] : 0, 0,
                        fmt::format("units '{}' are not supported: a BRDF dataset holds sr^-1 "
                                    "(convert reflectance factors with BRDF = BRF/pi)",
                                    value));
      }
    }
    d.metadata[key] = value;
  }
  if (!d.metadata.count("units")) d.metadata["units"] = "sr^-1";
}

// Zenith-range check of the raw angle cells, so that the error points at the offending column.
void check_angles(Reading& r, AngleConvention convention, const std::vector<CsvCell>& cells,
                  const std::vector<std::size_t>& angle_columns, const double a[4]) {
  static const char* zenith_names[4] = {"theta_i", "phi_i", "theta_r", "phi_r"};
  static const char* road_names[4] = {"gamma", "alpha", "beta", "delta"};
  for (int k : {0, 2}) {
    const int col = convention == AngleConvention::kRoad ? (k == 0 ? 0 : 1) : k;
    const double v = a[col];
    if (v < 0.0 || v > 90.0) {
      const auto& cell = cells[angle_columns[static_cast<std::size_t>(col)]];
      r.reader.fail(cell.column,
                    fmt::format("{} = '{}' is outside [0, 90] deg ({} zenith angle)",
                                convention == AngleConvention::kRoad ? road_names[col] : zenith_names[col],
                                cell.text, convention == AngleConvention::kRoad && col == 1 ? "90 - viewing" : "a"));
    }
  }
}

Geometry parse_geometry(Reading& r, AngleConvention convention, const std::vector<CsvCell>& cells,
                        const std::vector<std::size_t>& angle_columns) {
  double a[4];
  for (int k = 0; k < 4; ++k) a[k] = r.reader.number(cells[angle_columns[static_cast<std::size_t>(k)]], "angle in degrees");
  check_angles(r, convention, cells, angle_columns, a);
  try {
    return geometry_from_angle_values(convention, a);
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    r.reader.fail(cells[angle_columns[0]].column, e.what());
  }
}

double parse_brdf(Reading& r, const CsvCell& cell) {
  double v = 0.0;
  if (parse_double(cell.text, v)) {
    if (v < 0.0) {
      if (r.stats.negative_values++ == 0) {
        r.first_negative = fmt::format("{}:{}:{}", r.reader.path(), r.reader.line_number(), cell.column);
      }
    }
    return v;
  }
  if (r.options.allow_missing && is_missing_text(cell.text)) {
    if (r.stats.missing_values++ == 0) {
      r.first_missing = fmt::format("{}:{}:{}", r.reader.path(), r.reader.line_number(), cell.column);
    }
    return kNaN;
  }
  if (cell.text.empty()) r.reader.fail(cell.column, "empty cell where a BRDF value [sr^-1] was expected");
  r.reader.number(cell, "BRDF value [sr^-1]");  // throws with the right message
  r.reader.fail(cell.column, fmt::format("'{}' is not a BRDF value", cell.text));
}

double parse_sigma(Reading& r, const CsvCell& cell) {
  double v = 0.0;
  if (parse_double(cell.text, v)) {
    if (v < 0.0) r.reader.fail(cell.column, fmt::format("'{}': an uncertainty cannot be negative", cell.text));
    return v;
  }
  if (r.options.allow_missing && is_missing_text(cell.text)) return kNaN;
  if (cell.text.empty()) r.reader.fail(cell.column, "empty cell where an uncertainty [sr^-1] was expected");
  r.reader.number(cell, "uncertainty [sr^-1]");
  r.reader.fail(cell.column, fmt::format("'{}' is not an uncertainty", cell.text));
}

void ragged(Reading& r, const std::vector<CsvCell>& cells, std::size_t expected) {
  if (cells.size() > expected) {
    r.reader.fail(cells[expected].column,
                  fmt::format("row has {} cells but the header has {} columns (extra cell '{}')", cells.size(),
                              expected, cells[expected].text));
  }
  r.reader.fail(cells.back().column + static_cast<long>(cells.back().text.size()),
                fmt::format("row has {} cells but the header has {} columns (row ends after '{}')", cells.size(),
                            expected, cells.back().text));
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
  if (r.stats.averaged_duplicate_rows > 0) {
    warn(fmt::format("{}: {} duplicate geometry rows were averaged", r.reader.path(), r.stats.averaged_duplicate_rows));
  }
}

// ---- wide ---------------------------------------------------------------------------------------

SpectralDataset read_wide(Reading& r, const std::vector<CsvCell>& header_cells) {
  CsvReader& reader = r.reader;
  SpectralDataset d;
  read_metadata(r, d);
  std::vector<std::string> names;
  for (const auto& c : header_cells) names.emplace_back(c.text);
  const long header_line = reader.line_number();
  const std::vector<std::size_t> angle_columns = find_angle_columns(names, reader.path(), header_line, d.convention);
  std::vector<bool> is_angle(names.size(), false);
  for (auto k : angle_columns) is_angle[k] = true;

  std::vector<std::size_t> value_columns, sigma_columns;
  std::vector<double> sigma_wavelengths;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (is_angle[k]) continue;
    const CsvCell& cell = header_cells[k];
    const bool sigma = names[k].rfind("sigma_", 0) == 0;
    const std::string_view text = sigma ? cell.text.substr(6) : cell.text;
    double wl = 0.0;
    if (!parse_double(text, wl) || wl <= 0.0) {
      reader.fail(cell.column, fmt::format("column '{}' is neither an angle column, a wavelength in nm (e.g. 550) "
                                           "nor an uncertainty column sigma_<nm>",
                                           cell.text));
    }
    if (sigma) {
      if (!sigma_columns.empty() && wl <= sigma_wavelengths.back()) {
        reader.fail(cell.column, fmt::format("uncertainty column '{}' follows sigma_{}: wavelengths must be strictly "
                                             "increasing (no duplicates)",
                                             cell.text, sigma_wavelengths.back()));
      }
      sigma_columns.push_back(k);
      sigma_wavelengths.push_back(wl);
    } else {
      if (!sigma_columns.empty()) {
        reader.fail(cell.column, fmt::format("wavelength column '{}' after the sigma_<nm> block: put every "
                                             "wavelength column before the uncertainties",
                                             cell.text));
      }
      if (!d.wavelengths.empty() && wl <= d.wavelengths.back()) {
        reader.fail(cell.column,
                    fmt::format("wavelength '{}' nm is {} the previous column's {} nm: wavelengths must be "
                                "strictly increasing (no duplicates)",
                                cell.text, wl == d.wavelengths.back() ? "equal to" : "below", d.wavelengths.back()));
      }
      value_columns.push_back(k);
      d.wavelengths.push_back(wl);
    }
  }
  if (d.wavelengths.empty()) {
    reader.fail(header_cells.back().column + static_cast<long>(header_cells.back().text.size()),
                "header has no wavelength columns (one column per wavelength, named by its value in nm)");
  }
  if (!sigma_columns.empty()) {
    for (std::size_t k = 0; k < std::max(sigma_columns.size(), value_columns.size()); ++k) {
      if (k >= sigma_columns.size()) {
        reader.fail(header_cells.back().column,
                    fmt::format("uncertainty block lacks sigma_{} (it must list the same wavelengths)",
                                fmt::format("{}", d.wavelengths[k])));
      }
      if (k >= value_columns.size() || sigma_wavelengths[k] != d.wavelengths[k]) {
        reader.fail(header_cells[sigma_columns[k]].column,
                    fmt::format("uncertainty column '{}' does not match wavelength column {} (the sigma_<nm> block "
                                "must list the same wavelengths in the same order)",
                                header_cells[sigma_columns[k]].text,
                                k < value_columns.size() ? std::string(header_cells[value_columns[k]].text) : "none"));
      }
    }
  }

  const std::size_t m = d.wavelengths.size();
  const bool with_sigma = !sigma_columns.empty();
  std::unordered_map<GeometryKey, std::size_t, GeometryKeyHash> seen;
  std::vector<long> row_lines;
  std::vector<int> multiplicity;  // only when averaging
  std::vector<CsvCell> cells;
  std::vector<double> row(m), srow(m);
  bool reserved = false;
  while (reader.next_row(cells)) {
    if (cells.size() != names.size()) ragged(r, cells, names.size());
    if (!reserved) {
      // Reserve for the whole file from the length of the first row (memory proportional to the
      // data, without the copies of repeated growth).
      reserved = true;
      const auto size = reader.size_hint();
      const auto line_length = static_cast<std::uintmax_t>(cells.back().column) + cells.back().text.size() + 1;
      if (size > 0 && line_length > 0) {
        const std::size_t rows = static_cast<std::size_t>(size / line_length) + 1;
        if (rows < (std::size_t{1} << 26) / std::max<std::size_t>(m, 1)) {
          d.brdf.reserve(rows * m);
          d.geometries.reserve(rows);
          if (with_sigma) d.sigma.reserve(rows * m);
        }
      }
    }
    const Geometry g = parse_geometry(r, d.convention, cells, angle_columns);
    for (std::size_t j = 0; j < m; ++j) row[j] = parse_brdf(r, cells[value_columns[j]]);
    if (with_sigma) {
      for (std::size_t j = 0; j < m; ++j) srow[j] = parse_sigma(r, cells[sigma_columns[j]]);
    }
    const auto [it, inserted] = seen.emplace(key_of(g), d.geometries.size());
    if (!inserted) {
      if (!r.options.average_duplicates) {
        reader.fail(cells[angle_columns[0]].column,
                    fmt::format("duplicate geometry: same angles as line {} (ask for averaging of duplicates, e.g. "
                                "--average-duplicates, to average them)",
                                row_lines[it->second]));
      }
      const std::size_t n = it->second;
      if (multiplicity.empty()) multiplicity.assign(d.geometries.size(), 1);
      ++multiplicity[n];
      ++r.stats.averaged_duplicate_rows;
      for (std::size_t j = 0; j < m; ++j) d.brdf[n * m + j] += row[j];
      if (with_sigma) {
        for (std::size_t j = 0; j < m; ++j) d.sigma[n * m + j] += srow[j] * srow[j];
      }
      continue;
    }
    d.geometries.push_back(g);
    row_lines.push_back(reader.line_number());
    if (!multiplicity.empty()) multiplicity.push_back(1);
    d.brdf.insert(d.brdf.end(), row.begin(), row.end());
    if (with_sigma) {
      if (r.options.average_duplicates) {
        for (std::size_t j = 0; j < m; ++j) d.sigma.push_back(srow[j] * srow[j]);
      } else {
        d.sigma.insert(d.sigma.end(), srow.begin(), srow.end());
      }
    }
  }
  if (d.geometries.empty()) throw FileError(reader.path(), reader.line_number(), 0, "file has a header but no data rows");
  if (r.options.average_duplicates) {
    for (std::size_t n = 0; n < d.geometries.size(); ++n) {
      const double c = multiplicity.empty() ? 1.0 : multiplicity[n];
      for (std::size_t j = 0; j < m; ++j) {
        d.brdf[n * m + j] /= c;
        if (with_sigma) d.sigma[n * m + j] = std::sqrt(d.sigma[n * m + j]) / c;
      }
    }
    if (r.stats.averaged_duplicate_rows) d.metadata["averaged_duplicate_rows"] = std::to_string(r.stats.averaged_duplicate_rows);
  }
  return d;
}

// ---- long ---------------------------------------------------------------------------------------

SpectralDataset read_long(Reading& r, const std::vector<CsvCell>& header_cells) {
  CsvReader& reader = r.reader;
  SpectralDataset d;
  read_metadata(r, d);
  std::vector<std::string> names;
  for (const auto& c : header_cells) names.emplace_back(c.text);
  const std::vector<std::size_t> angle_columns =
      find_angle_columns(names, reader.path(), reader.line_number(), d.convention);
  long wl_col = -1, brdf_col = -1, sigma_col = -1;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (std::find(angle_columns.begin(), angle_columns.end(), k) != angle_columns.end()) continue;
    long* target = names[k] == "wavelength" ? &wl_col : names[k] == "brdf" ? &brdf_col : names[k] == "sigma" ? &sigma_col : nullptr;
    if (!target) {
      reader.fail(header_cells[k].column,
                  fmt::format("unexpected column '{}' in a long dataset (expected the angle columns and "
                              "wavelength,brdf[,sigma])",
                              header_cells[k].text));
    }
    if (*target >= 0) reader.fail(header_cells[k].column, fmt::format("column '{}' appears twice", header_cells[k].text));
    *target = static_cast<long>(k);
  }
  if (brdf_col < 0) throw FileError(reader.path(), reader.line_number(), 0, "long dataset header lacks the 'brdf' column");

  struct Record {
    std::size_t geometry;
    double wavelength, brdf, sigma;
    long line, column;
  };
  std::vector<Record> records;
  std::unordered_map<GeometryKey, std::size_t, GeometryKeyHash> seen;
  std::vector<long> first_lines;
  std::vector<CsvCell> cells;
  while (reader.next_row(cells)) {
    if (cells.size() != names.size()) ragged(r, cells, names.size());
    const Geometry g = parse_geometry(r, d.convention, cells, angle_columns);
    const CsvCell& wcell = cells[static_cast<std::size_t>(wl_col)];
    const double wl = reader.number(wcell, "wavelength in nm");
    if (wl <= 0.0) reader.fail(wcell.column, fmt::format("wavelength '{}' nm is not positive", wcell.text));
    const double v = parse_brdf(r, cells[static_cast<std::size_t>(brdf_col)]);
    const double s = sigma_col >= 0 ? parse_sigma(r, cells[static_cast<std::size_t>(sigma_col)]) : 0.0;
    const auto [it, inserted] = seen.emplace(key_of(g), d.geometries.size());
    if (inserted) {
      d.geometries.push_back(g);
      first_lines.push_back(reader.line_number());
    }
    records.push_back({it->second, wl, v, s, reader.line_number(), cells[angle_columns[0]].column});
  }
  if (records.empty()) throw FileError(reader.path(), reader.line_number(), 0, "file has a header but no data rows");
  std::vector<double> wls;
  wls.reserve(records.size());
  for (const auto& rec : records) wls.push_back(rec.wavelength);
  std::sort(wls.begin(), wls.end());
  wls.erase(std::unique(wls.begin(), wls.end()), wls.end());
  d.wavelengths = wls;
  const std::size_t n = d.geometries.size(), m = wls.size();
  d.brdf.assign(n * m, 0.0);
  if (sigma_col >= 0) d.sigma.assign(n * m, 0.0);
  std::vector<int> count(n * m, 0);
  std::vector<long> where(n * m, 0);
  for (const auto& rec : records) {
    const std::size_t j = static_cast<std::size_t>(std::lower_bound(wls.begin(), wls.end(), rec.wavelength) - wls.begin());
    const std::size_t idx = rec.geometry * m + j;
    if (count[idx] > 0 && !r.options.average_duplicates) {
      throw FileError(reader.path(), rec.line, rec.column,
                      fmt::format("duplicate value: this geometry already has wavelength {} nm at line {} (ask for "
                                  "averaging of duplicates, e.g. --average-duplicates, to average them)",
                                  rec.wavelength, where[idx]));
    }
    if (count[idx] > 0) ++r.stats.averaged_duplicate_rows;
    ++count[idx];
    if (!where[idx]) where[idx] = rec.line;
    d.brdf[idx] += rec.brdf;
    if (sigma_col >= 0) d.sigma[idx] += rec.sigma * rec.sigma;
  }
  for (std::size_t g = 0; g < n; ++g) {
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t idx = g * m + j;
      if (count[idx] == 0) {
        throw FileError(reader.path(), first_lines[g], 0,
                        fmt::format("the geometry first given on this line has no value at wavelength {} nm (every "
                                    "geometry needs every wavelength)",
                                    wls[j]));
      }
      d.brdf[idx] /= count[idx];
      if (sigma_col >= 0) d.sigma[idx] = std::sqrt(d.sigma[idx]) / count[idx];
    }
  }
  if (r.stats.averaged_duplicate_rows) d.metadata["averaged_duplicate_rows"] = std::to_string(r.stats.averaged_duplicate_rows);
  return d;
}

std::string fmt_value(double v) {
  if (std::isnan(v)) return "nan";
  return fmt::format("{}", v);
}

std::string fmt_angle(double v) {
  const double r = std::round(v * 1e9) / 1e9 + 0.0;
  return fmt::format("{}", r);
}

}  // namespace

void angle_values_of_geometry(const Geometry& g, AngleConvention convention, double out[4]) {
  if (convention == AngleConvention::kRoad) {
    const RoadAngles a = road_angles_from_geometry(g);
    out[0] = a.gamma;
    out[1] = a.alpha;
    out[2] = a.beta;
    out[3] = a.delta;
  } else {
    out[0] = rad_to_deg(g.theta_i);
    out[1] = rad_to_deg(g.phi_i);
    out[2] = rad_to_deg(g.theta_r);
    out[3] = rad_to_deg(g.phi_r);
  }
}

SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options, DatasetReadStats& stats) {
  stats = {};
  CsvReader reader(path);
  std::vector<CsvCell> header;
  if (!reader.next_row(header)) throw FileError(path, reader.line_number(), 0, "file is empty (no header line)");
  Reading r{options, stats, reader, {}, {}};
  const bool is_long =
      std::any_of(header.begin(), header.end(), [](const CsvCell& c) { return c.text == "wavelength"; });
  SpectralDataset d = is_long ? read_long(r, header) : read_wide(r, header);
  finish_warnings(r, d);
  return d;
}

SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options) {
  DatasetReadStats stats;
  return read_dataset(path, options, stats);
}

void validate_dataset(const SpectralDataset& d) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  if (n == 0 || m == 0) throw InputError("dataset has no geometries or no wavelengths");
  if (d.brdf.size() != n * m) {
    throw InputError(fmt::format("dataset holds {} BRDF values for {} geometries x {} wavelengths", d.brdf.size(), n, m));
  }
  if (!d.sigma.empty() && d.sigma.size() != n * m) {
    throw InputError(fmt::format("dataset holds {} uncertainties for {} geometries x {} wavelengths", d.sigma.size(), n, m));
  }
  for (std::size_t j = 1; j < m; ++j) {
    if (!(d.wavelengths[j] > d.wavelengths[j - 1])) {
      throw InputError(fmt::format("dataset wavelengths are not strictly increasing ({} nm then {} nm)",
                                   d.wavelengths[j - 1], d.wavelengths[j]));
    }
  }
}

void write_dataset(const SpectralDataset& d, std::ostream& out, DatasetFormat format) {
  validate_dataset(d);
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  out << "# roadbrdf spectral BRDF dataset (" << (format == DatasetFormat::kWide ? "wide" : "long")
      << " CSV); angles in degrees, wavelengths in nm, BRDF and sigma in sr^-1\n";
  if (!d.metadata.count("units")) out << "# units: sr^-1\n";
  for (const auto& [key, value] : d.metadata) {
    std::string v = value;
    std::replace(v.begin(), v.end(), '\n', ' ');
    out << "# " << key << ": " << v << '\n';
  }
  const bool road = d.convention == AngleConvention::kRoad;
  const char* angle_header = road ? "gamma,alpha,beta,delta" : "theta_i,phi_i,theta_r,phi_r";
  std::string line;
  if (format == DatasetFormat::kWide) {
    line = angle_header;
    for (double wl : d.wavelengths) line += fmt::format(",{}", fmt_value(wl));
    if (d.has_sigma()) {
      for (double wl : d.wavelengths) line += fmt::format(",sigma_{}", fmt_value(wl));
    }
    out << line << '\n';
    for (std::size_t g = 0; g < n; ++g) {
      double a[4];
      angle_values_of_geometry(d.geometries[g], d.convention, a);
      line.clear();
      for (int k = 0; k < 4; ++k) {
        if (k) line += ',';
        line += fmt_angle(a[k]);
      }
      for (std::size_t j = 0; j < m; ++j) {
        line += ',';
        line += fmt_value(d.brdf[g * m + j]);
      }
      if (d.has_sigma()) {
        for (std::size_t j = 0; j < m; ++j) {
          line += ',';
          line += fmt_value(d.sigma[g * m + j]);
        }
      }
      out << line << '\n';
    }
  } else {
    out << angle_header << ",wavelength,brdf" << (d.has_sigma() ? ",sigma" : "") << '\n';
    for (std::size_t g = 0; g < n; ++g) {
      double a[4];
      angle_values_of_geometry(d.geometries[g], d.convention, a);
      std::string prefix;
      for (int k = 0; k < 4; ++k) prefix += fmt::format("{},", fmt_angle(a[k]));
      for (std::size_t j = 0; j < m; ++j) {
        line = fmt::format("{}{},{}", prefix, fmt_value(d.wavelengths[j]), fmt_value(d.brdf[g * m + j]));
        if (d.has_sigma()) line += fmt::format(",{}", fmt_value(d.sigma[g * m + j]));
        out << line << '\n';
      }
    }
  }
}

void write_dataset(const SpectralDataset& d, const std::string& path, DatasetFormat format) {
  AtomicFile file(path);
  write_dataset(d, file.stream(), format);
  file.commit();
}

DatasetFormat dataset_format_from_string(const std::string& name) {
  if (name == "wide") return DatasetFormat::kWide;
  if (name == "long") return DatasetFormat::kLong;
  throw InputError("unknown dataset format '" + name + "' (expected wide or long)");
}

}  // namespace roadbrdf
