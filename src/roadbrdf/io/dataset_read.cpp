// Reading spectral BRDF datasets (wide and long CSV, every dialect of io/dataset_dialect.h).
//
// Speed: a wide row is scanned once, cell by cell, without allocating (CellScanner), and each number
// is parsed with std::from_chars in place; only a cell that is not a plain number takes the slow
// path (decimal comma, missing value, error message). Memory: the dataset itself, plus the current
// line; the header costs a few bytes per column; a long file holds one record per row until its
// shape has been checked, and only then the geometries x wavelengths table is allocated.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/huge_pages.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_support.h"
#include "roadbrdf/io/openmaterial3d.h"

namespace roadbrdf {

namespace {

using namespace dataset_read;

// ---- header -------------------------------------------------------------------------------------

bool is_angle_name(std::string_view n) {
  for (const char* a : {"theta_i", "phi_i", "theta_r", "phi_r", "gamma", "alpha", "beta", "delta"}) {
    if (n == a) return true;
  }
  return false;
}

bool is_long_name(std::string_view n) { return n == "wavelength" || n == "brdf" || n == "sigma"; }

// Whether a canonical header name is one a dataset can have, for delimiter detection.
bool known_name(std::string_view n, char delimiter) {
  if (is_angle_name(n) || is_long_name(n)) return true;
  if (n.rfind("sigma_", 0) == 0) n.remove_prefix(6);
  NumberParser numbers(delimiter, 0);
  double v = 0.0;
  return numbers.parse(n, v, 1, 1) && v > 0.0;
}

// A mapped header name and a header cell: equal as written, or ignoring case and surrounding blanks.
bool same_header_name(std::string_view mapped, std::string_view cell) {
  if (mapped == cell) return true;
  const std::string a = trimmed_copy(std::string(mapped)), b = trimmed_copy(std::string(cell));
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

struct HeaderCell {
  std::string canonical;
  std::string_view text;
  long column;
  std::size_t index;
};

// The header's non-numeric cells (names), and its cell count. A numeric cell (a wavelength column)
// costs nothing here: the wide reader reads them in its own pass.
std::vector<HeaderCell> header_names(Reading& r, std::string_view header, std::size_t& count, bool& is_long) {
  std::vector<HeaderCell> names;
  CellScanner cells(header, r.delimiter);
  std::string_view text;
  long column = 0;
  count = 0;
  is_long = false;
  const auto& mapping = r.options.columns;
  std::vector<bool> mapped_found(mapping.size(), false);
  std::vector<std::string> all_names;
  while (cells.next(text, column)) {
    const std::size_t index = count++;
    all_names.emplace_back(text);
    // A column the mapping names is that field, whatever it is called; another column of the same
    // canonical name is then not read (the mapping chose).
    std::size_t k = 0;
    const std::string* mapped = nullptr;
    for (const auto& [field, name] : mapping) {
      if (same_header_name(name, text)) {
        if (mapped_found[k]) {
          r.reader.fail(column, fmt::format("column '{}' matches `columns` {}={} a second time", text, field, name));
        }
        mapped_found[k] = true;
        mapped = &field;
      }
      ++k;
    }
    if (mapped) {
      names.push_back({*mapped, text, column, index});
      if (*mapped == "wavelength") is_long = true;
      continue;
    }
    if (!text.empty() && (std::isdigit(static_cast<unsigned char>(text.front())) || text.front() == '.')) continue;
    bool radians = false;
    std::string canonical = canonical_column_name(text, &radians);
    if (mapping.count(canonical)) canonical = "(not the mapped column) " + canonical;
    if (radians) {
      r.reader.fail(column, fmt::format("column '{}' is in radians: dataset angles are in degrees (convert them, "
                                        "e.g. x 180/pi)",
                                        text));
    }
    if (canonical == "wavelength") is_long = true;
    names.push_back({std::move(canonical), text, column, index});
  }
  std::size_t k = 0;
  for (const auto& [field, name] : mapping) {
    if (!mapped_found[k++]) {
      r.reader.fail(0, fmt::format("`columns` {}={}: the header has no column '{}'{}", field, name, name,
                                   did_you_mean(name, all_names)));
    }
  }
  return names;
}

// The four angle columns (indices into the header) and the convention.
std::vector<std::size_t> angle_columns_of(Reading& r, const std::vector<HeaderCell>& names, long header_line,
                                          AngleConvention& convention) {
  std::vector<std::string> canonical;
  canonical.reserve(names.size() + r.options.fixed_angles.size());
  for (const auto& n : names) canonical.push_back(n.canonical);
  // A fixed angle stands for a column the file lacks; given as a column too, it is a contradiction.
  for (const auto& [field, value] : r.options.fixed_angles) {
    const auto it = std::find(canonical.begin(), canonical.end(), field);
    if (it != canonical.end()) {
      r.reader.fail(names[static_cast<std::size_t>(it - canonical.begin())].column,
                    fmt::format("column '{}' holds {}, which `set` fixes to {:g} deg too: give one of them",
                                names[static_cast<std::size_t>(it - canonical.begin())].text, field, value));
    }
    canonical.push_back(field);
  }
  std::vector<std::size_t> columns = find_angle_columns(canonical, r.reader.path(), header_line, convention);
  for (const auto& [field, value] : r.options.fixed_angles) {
    const auto it = std::find(canonical.begin(), canonical.end(), field);
    const auto k = static_cast<std::size_t>(it - canonical.begin());
    const auto where = std::find(columns.begin(), columns.end(), k);
    if (where == columns.end()) {
      throw FileError(r.reader.path(), header_line, 0,
                      fmt::format("`set` {}: the file's angles are in the other convention (theta_i,phi_i,theta_r,"
                                  "phi_r or gamma,alpha,beta,delta; one convention per file)",
                                  field));
    }
    const auto a = static_cast<std::size_t>(where - columns.begin());
    r.fixed[a] = true;
    r.fixed_value[a] = value;
  }
  for (auto& c : columns) {
    const std::size_t k = c;
    if (k >= names.size()) {
      c = kFixedAngle;
      continue;
    }
    c = names[k].index;
    // An angle column given twice (e.g. "theta_i" and its alias "inc") is an error, not a choice.
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (j != k && names[j].canonical == names[k].canonical) {
        r.reader.fail(names[j].column, fmt::format("column '{}' is a second '{}' column (first: '{}')", names[j].text,
                                                   names[k].canonical, names[k].text));
      }
    }
  }
  return columns;
}

// ---- wide ---------------------------------------------------------------------------------------

struct Role {
  enum Kind : std::uint8_t { kAngle, kValue, kSigma, kOther } kind;
  std::uint32_t index;  // angle 0-3, or wavelength index
};

// The wide header's column roles; its wavelengths go to the dataset.
struct WideColumns {
  std::vector<Role> roles;
  bool with_sigma = false;
};

// The sigma_<nm> columns of a wide header, in header order.
struct SigmaColumns {
  std::vector<double> wavelengths;
  std::vector<long> columns;
  std::vector<std::string_view> texts;
};

// A non-angle header cell: the wavelength [nm] it names ("550", "550nm", "550 nm"), and whether it
// is an uncertainty column ("sigma_550").
double header_wavelength(Reading& r, std::string_view text, long column, long header_line, bool& sigma) {
  std::string lower(text.substr(0, std::min<std::size_t>(text.size(), 6)));
  for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  sigma = lower == "sigma_";
  std::string_view number = sigma ? text.substr(6) : text;
  // "400nm", "400 nm"
  std::string stripped = canonical_column_name(number);
  double wl = 0.0;
  if (!r.numbers.parse(stripped, wl, header_line, column) || !(wl > 0.0)) {
    r.reader.fail(column, fmt::format("column '{}' is neither an angle column, a wavelength in nm (e.g. 550) "
                                      "nor an uncertainty column sigma_<nm>{}",
                                      text, r.numbers.hint(stripped)));
  }
  return wl;
}

// The sigma_<nm> block, if any, lists the wavelengths of the value columns, in their order.
void check_sigma_block(Reading& r, const SigmaColumns& sigma, const std::vector<double>& wavelengths,
                       const std::vector<std::string_view>& value_texts, long header_end) {
  const std::size_t m = wavelengths.size();
  for (std::size_t k = 0; k < std::max(sigma.wavelengths.size(), m); ++k) {
    if (k >= sigma.wavelengths.size()) {
      r.reader.fail(header_end, fmt::format("uncertainty block lacks sigma_{} (it must list the same wavelengths)",
                                            wavelengths[k]));
    }
    if (k >= m || sigma.wavelengths[k] != wavelengths[k]) {
      r.reader.fail(sigma.columns[k],
                    fmt::format("uncertainty column '{}' does not match wavelength column {} (the sigma_<nm> "
                                "block must list the same wavelengths in the same order)",
                                sigma.texts[k], k < m ? std::string(value_texts[k]) : "none"));
    }
  }
}

// The roles of a wide header's columns: the four angles (d's convention), then one column per
// wavelength (strictly increasing, into d.wavelengths), then optionally the same wavelengths again
// as sigma_<nm>.
WideColumns wide_columns(Reading& r, std::string_view header, const std::vector<HeaderCell>& names,
                         std::size_t column_count, SpectralDataset& d) {
  CsvReader& reader = r.reader;
  const long header_line = reader.line_number();
  const std::vector<std::size_t> angle_columns = angle_columns_of(r, names, header_line, d.convention);
  WideColumns w;
  auto& roles = w.roles;
  roles.assign(column_count, Role{Role::kValue, 0});
  for (int k = 0; k < 4; ++k) {
    const std::size_t c = angle_columns[static_cast<std::size_t>(k)];
    if (c != kFixedAngle) roles[c] = {Role::kAngle, static_cast<std::uint32_t>(k)};
  }
  SigmaColumns sigma_columns;
  auto& sigma_wavelengths = sigma_columns.wavelengths;
  std::vector<std::string_view> value_header_texts;
  CellScanner cells(header, r.delimiter);
  std::string_view text;
  long column = 0;
  // The canonical name of each named header cell (numeric cells, the wavelengths, have none).
  std::vector<const std::string*> canonical_of(column_count, nullptr);
  for (const HeaderCell& n : names) canonical_of[n.index] = &n.canonical;
  for (std::size_t k = 0; cells.next(text, column); ++k) {
    if (roles[k].kind == Role::kAngle) continue;
    if (ignores_other_columns(r.options) && canonical_of[k] && !known_name(*canonical_of[k], r.delimiter)) {
      roles[k] = {Role::kOther, 0};
      r.ignored_columns.emplace_back(text);
      continue;
    }
    bool sigma = false;
    const double wl = header_wavelength(r, text, column, header_line, sigma);
    if (sigma) {
      if (!sigma_wavelengths.empty() && wl <= sigma_wavelengths.back()) {
        reader.fail(column, fmt::format("uncertainty column '{}' follows sigma_{}: wavelengths must be strictly "
                                        "increasing (no duplicates)",
                                        text, sigma_wavelengths.back()));
      }
      roles[k] = {Role::kSigma, static_cast<std::uint32_t>(sigma_wavelengths.size())};
      sigma_wavelengths.push_back(wl);
      sigma_columns.columns.push_back(column);
      sigma_columns.texts.push_back(text);
    } else {
      if (!sigma_wavelengths.empty()) {
        reader.fail(column, fmt::format("wavelength column '{}' after the sigma_<nm> block: put every "
                                        "wavelength column before the uncertainties",
                                        text));
      }
      if (!d.wavelengths.empty() && wl <= d.wavelengths.back()) {
        reader.fail(column, fmt::format("wavelength '{}' nm is {} the previous column's {} nm: wavelengths must be "
                                        "strictly increasing (no duplicates)",
                                        text, wl == d.wavelengths.back() ? "equal to" : "below", d.wavelengths.back()));
      }
      roles[k] = {Role::kValue, static_cast<std::uint32_t>(d.wavelengths.size())};
      d.wavelengths.push_back(wl);
      value_header_texts.push_back(text);
    }
  }
  const long header_end = static_cast<long>(header.size()) + 1;
  if (d.wavelengths.empty()) {
    reader.fail(header_end, "header has no wavelength columns (one column per wavelength, named by its value in nm)");
  }
  w.with_sigma = !sigma_wavelengths.empty();
  if (w.with_sigma) check_sigma_block(r, sigma_columns, d.wavelengths, value_header_texts, header_end);
  return w;
}

// The cells of one row by their column roles: the angle cells into angles, the BRDF values into
// values[wavelength index], the uncertainties into sigmas. The hot loop of a wide file: nothing is
// allocated, each number is parsed in place.
void read_wide_cells(Reading& r, std::string_view line, const std::vector<Role>& roles, AngleCells& angles,
                     double* values, double* sigmas) {
  const std::size_t column_count = roles.size();
  CellScanner cells(line, r.delimiter);
  std::string_view text;
  long column = 0;
  std::size_t k = 0;
  while (cells.next(text, column)) {
    if (k == column_count) ragged(r, line, column_count, text, column, true);
    const Role role = roles[k++];
    switch (role.kind) {
      case Role::kAngle:
        angles.text[role.index] = text;
        angles.column[role.index] = column;
        angles.value[role.index] = number(r, text, column, "angle in degrees");
        break;
      case Role::kValue:
        values[role.index] = parse_brdf(r, text, column);
        break;
      case Role::kSigma:
        sigmas[role.index] = parse_sigma(r, text, column);
        break;
      case Role::kOther:
        break;
    }
  }
  if (k != column_count) ragged(r, line, column_count, text, column, false);
}

// The data rows of a wide file into the dataset, one at a time: each a new geometry, or (when
// averaging is asked for) one more measurement of a geometry already read. While averaging, the
// dataset holds sums (of values, and of squared uncertainties) until finish().
class WideRows {
 public:
  WideRows(Reading& r, SpectralDataset& d, const WideColumns& columns)
      : r_(r),
        d_(d),
        roles_(columns.roles),
        m_(d.wavelengths.size()),
        with_sigma_(columns.with_sigma),
        row_(m_),
        srow_(with_sigma_ ? m_ : 0),
        angles_(initial_angles(r)) {}

  void read(std::string_view line) {
    if (!reserved_) reserve(line);
    read_wide_cells(r_, line, roles_, angles_, row_.data(), srow_.data());
    const Geometry g = parse_geometry(r_, d_.convention, angles_);
    const auto [it, inserted] = seen_.emplace(key_of(g), d_.geometries.size());
    if (inserted) {
      append(g);
    } else {
      add_duplicate(it->second);
    }
  }

  void finish();

 private:
  void reserve(std::string_view first_row);
  void append(const Geometry& g);
  void add_duplicate(std::size_t n);

  Reading& r_;
  SpectralDataset& d_;
  const std::vector<Role>& roles_;
  const std::size_t m_;
  const bool with_sigma_;
  std::unordered_map<GeometryKey, std::size_t, GeometryKeyHash> seen_;
  std::vector<long> row_lines_;
  std::vector<int> multiplicity_;  // only when averaging
  // Only when averaging: per duplicated geometry and cell, the smallest and largest value, and the
  // running mean and sum of squared deviations from it (Welford 1962, Technometrics 4:419).
  struct CellSpread {
    double lo, hi, mean, squares;
  };
  std::map<std::size_t, std::vector<CellSpread>> ranges_;
  std::vector<double> row_, srow_;
  AngleCells angles_;
  bool reserved_ = false;
};

// Reserve for the whole file from the length of the first row (memory proportional to the data,
// without the copies of repeated growth), in huge pages where the system offers them.
void WideRows::reserve(std::string_view first_row) {
  reserved_ = true;
  const auto size = r_.reader.size_hint();
  if (size > 0 && !first_row.empty()) {
    const std::size_t rows = static_cast<std::size_t>(size / (first_row.size() + 1)) + 1;
    if (rows < (std::size_t{1} << 26) / std::max<std::size_t>(m_, 1)) {
      reserve_on_huge_pages(d_.brdf, rows * m_);
      d_.geometries.reserve(rows);
      if (with_sigma_) reserve_on_huge_pages(d_.sigma, rows * m_);
    }
  }
}

void WideRows::append(const Geometry& g) {
  d_.geometries.push_back(g);
  row_lines_.push_back(r_.reader.line_number());
  if (!multiplicity_.empty()) {
    for (std::size_t j = 0; j < m_; ++j) multiplicity_.push_back(std::isnan(row_[j]) ? 0 : 1);
  }
  d_.brdf.insert(d_.brdf.end(), row_.begin(), row_.end());
  if (with_sigma_) {
    if (r_.options.average_duplicates) {
      for (std::size_t j = 0; j < m_; ++j) d_.sigma.push_back(srow_[j] * srow_[j]);
    } else {
      d_.sigma.insert(d_.sigma.end(), srow_.begin(), srow_.end());
    }
  }
}

// The current row repeats geometry n: an error, or summed into it when averaging.
void WideRows::add_duplicate(std::size_t n) {
  if (!r_.options.average_duplicates) {
    r_.reader.fail(angles_.column[0],
                   fmt::format("duplicate geometry: same angles as line {} ({})", row_lines_[n], duplicates_hint()));
  }
  auto& brdf = d_.brdf;
  if (multiplicity_.empty()) {
    // Per cell: how many of the duplicates measured it (missing cells are not averaged in).
    multiplicity_.resize(brdf.size());
    for (std::size_t k = 0; k < brdf.size(); ++k) multiplicity_[k] = std::isnan(brdf[k]) ? 0 : 1;
  }
  ++r_.stats.averaged_duplicate_rows;
  auto [range, first] = ranges_.try_emplace(n);
  if (first) {  // the geometry's first row, still on its own
    for (std::size_t j = 0; j < m_; ++j) {
      const double v = brdf[n * m_ + j];
      range->second.push_back({v, v, v, 0.0});
    }
  }
  for (std::size_t j = 0; j < m_; ++j) {
    if (std::isnan(row_[j])) continue;
    auto& [lo, hi, mean, squares] = range->second[j];
    lo = std::isnan(lo) ? row_[j] : std::min(lo, row_[j]);
    hi = std::isnan(hi) ? row_[j] : std::max(hi, row_[j]);
    double& v = brdf[n * m_ + j];
    v = multiplicity_[n * m_ + j]++ == 0 ? row_[j] : v + row_[j];
    if (multiplicity_[n * m_ + j] == 1) {
      mean = row_[j];
      squares = 0.0;
    } else {
      const double delta = row_[j] - mean;
      mean += delta / multiplicity_[n * m_ + j];
      squares += delta * (row_[j] - mean);
    }
    if (with_sigma_) {
      double& s = d_.sigma[n * m_ + j];
      s = multiplicity_[n * m_ + j] == 1 ? srow_[j] * srow_[j] : s + srow_[j] * srow_[j];
    }
  }
}

// When averaging: the sums become means (uncertainty: root of the summed squares over the count).
void WideRows::finish() {
  if (!r_.options.average_duplicates) return;
  for (std::size_t n = 0; n < d_.geometries.size(); ++n) {
    for (std::size_t j = 0; j < m_; ++j) {
      // A cell no duplicate measured stays missing (NaN); 0/0 is never formed.
      const double c = multiplicity_.empty() ? 1.0 : std::max<double>(1.0, multiplicity_[n * m_ + j]);
      d_.brdf[n * m_ + j] /= c;
      if (with_sigma_) d_.sigma[n * m_ + j] = std::sqrt(d_.sigma[n * m_ + j]) / c;
    }
  }
  if (r_.stats.averaged_duplicate_rows)
    d_.metadata["averaged_duplicate_rows"] = std::to_string(r_.stats.averaged_duplicate_rows);
  std::vector<std::vector<double>> spreads(m_);
  for (const auto& [n, range] : ranges_) {
    for (std::size_t j = 0; j < m_; ++j) {
      if (multiplicity_[n * m_ + j] < 2) continue;
      spreads[j].push_back(relative_spread(range[j].lo, range[j].hi, d_.brdf[n * m_ + j]));
    }
  }
  r_.stats.repeatability = repeatability_of(spreads, ranges_.size());
  if (ranges_.empty()) return;
  // Squared deviations relative to the cell's mean, pooled per wavelength.
  std::vector<double> squares(m_, 0.0);
  std::vector<std::size_t> dof(m_, 0);
  for (const auto& [n, range] : ranges_) {
    for (std::size_t j = 0; j < m_; ++j) {
      const int count = multiplicity_[n * m_ + j];
      const double mean = d_.brdf[n * m_ + j];
      if (count < 2 || mean == 0.0) continue;
      squares[j] += range[j].squares / (mean * mean);
      dof[j] += static_cast<std::size_t>(count - 1);
    }
  }
  set_pooled_relative_sd(r_.stats.repeatability, squares, dof);
  r_.stats.repeatability.cell_counts.assign(multiplicity_.begin(), multiplicity_.end());
}

SpectralDataset read_wide(Reading& r, std::string_view header, const std::vector<HeaderCell>& names,
                          std::size_t column_count) {
  CsvReader& reader = r.reader;
  SpectralDataset d;
  read_metadata(r, d);
  const WideColumns columns = wide_columns(r, header, names, column_count, d);
  WideRows rows(r, d, columns);
  std::string_view line;
  while (reader.next_line(line)) rows.read(line);
  if (d.geometries.empty())
    throw FileError(reader.path(), reader.line_number(), 0, "file has a header but no data rows");
  rows.finish();
  return d;
}

}  // namespace

namespace {

SpectralDataset read_csv_dataset(const std::string& path, const DatasetReadOptions& options, DatasetReadStats& stats) {
  CsvReader reader(path);
  std::string_view first;
  if (!reader.next_line(first))
    throw FileError(reader.path(), reader.line_number(), 0, "file is empty (no header line)");
  const std::string header(first);  // the reader reuses its line buffer
  char delimiter = options.delimiter;
  if (delimiter == 0) {
    try {
      delimiter = detect_delimiter(header, &known_name);
    } catch (const FileError&) {
      throw;
    } catch (const InputError& e) {
      throw FileError(reader.path(), reader.line_number(), 0, e.what());
    }
  }
  Reading r{options, stats, reader, delimiter, NumberParser(delimiter, options.decimal), {}, {}, {}, 0.0, {},
            false,   {},    {},     {}};
  std::size_t column_count = 0;
  bool is_long = false;
  const std::vector<HeaderCell> names = header_names(r, header, column_count, is_long);
  SpectralDataset d;
  if (is_long) {
    AngleConvention convention = AngleConvention::kZenithAzimuth;
    const std::vector<std::size_t> angle_columns = angle_columns_of(r, names, reader.line_number(), convention);
    std::vector<LongColumn> columns;
    for (const auto& n : names) {
      if (std::find(angle_columns.begin(), angle_columns.end(), n.index) == angle_columns.end()) {
        columns.push_back({n.canonical, std::string(n.text), n.column, n.index});
      }
    }
    // Numeric header cells have no place in a long file.
    if (columns.size() + 4 != column_count) {
      CellScanner cells(header, delimiter);
      std::string_view text;
      long column = 0;
      for (std::size_t k = 0; cells.next(text, column); ++k) {
        const bool named = std::any_of(names.begin(), names.end(), [&](const HeaderCell& n) { return n.index == k; });
        if (!named) columns.push_back({std::string(text), std::string(text), column, k});
      }
    }
    d = read_long(r, columns, column_count, angle_columns, convention);
  } else {
    d = read_wide(r, header, names, column_count);
  }
  finish_warnings(r, d);
  return d;
}

}  // namespace

SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options, DatasetReadStats& stats) {
  validate_read_options(options);
  stats = {};
  SpectralDataset d = is_openmaterial3d_path(path) ? read_openmaterial3d(path, options, stats)  // JSON, not CSV
                                                   : read_csv_dataset(path, options, stats);
  convert_to_brdf(d, options.quantity, path, options.warn);
  return d;
}

SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options) {
  DatasetReadStats stats;
  return read_dataset(path, options, stats);
}

}  // namespace roadbrdf
