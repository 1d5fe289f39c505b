// Internal to the dataset reader (dataset_read.cpp, dataset_read_long.cpp): the reading state and
// the per-cell helpers shared by the wide and the long format.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf::dataset_read {

// BRDF values above this [sr^-1] are warned about (a mirror or retroreflector peak, or the wrong
// units: radiance, counts, percent).
constexpr double kImplausibleBrdf = 1e3;
// A dataset whose wavelengths are all below this [nm] probably gives micrometres (UV to thermal
// infrared: 0.2-25 um), below the second metres (2e-7 to 2.5e-5 m).
constexpr double kMicrometreLikeWavelength = 30.0;
constexpr double kMetreLikeWavelength = 1e-4;
// A dataset whose zenith angles all lie within this [deg] (pi/2 = 1.571) and whose azimuths lie within
// +-the second (2 pi = 6.283) probably gives radians.
constexpr double kRadianLikeZenith = 1.6;
constexpr double kRadianLikeAzimuth = 6.3;

struct Reading {
  const DatasetReadOptions& options;
  DatasetReadStats& stats;
  CsvReader& reader;
  char delimiter;
  NumberParser numbers;
  std::string first_negative;  // location of the first negative value
  std::string first_missing;
  std::string first_large;  // location of the first value above kImplausibleBrdf
  double largest = 0.0;
  std::string first_absent;  // the first (geometry, wavelength) pair of a long file without a row
  bool long_format = false;  // wavelengths in a column (long) or in the header (wide)
  // Angles without a column, one value for every row (DatasetReadOptions::fixed_angles), in the
  // convention's column order.
  std::array<bool, 4> fixed{};
  std::array<double, 4> fixed_value{};
  // Header cells that are no dataset column, not read (only with a mapping or fixed angles).
  std::vector<std::string> ignored_columns;
};

// The column index standing for an angle that has no column (a fixed value).
constexpr std::size_t kFixedAngle = static_cast<std::size_t>(-1);
// Whether header cells that are no dataset column are ignored (with a note) rather than refused: when
// the options map columns or fix angles, the table is a foreign one.
inline bool ignores_other_columns(const DatasetReadOptions& o) { return !o.columns.empty() || !o.fixed_angles.empty(); }

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
GeometryKey key_of(const Geometry& g);

// The four angle cells of a row, in the convention's column order.
struct AngleCells {
  std::array<std::string_view, 4> text;
  std::array<long, 4> column{};
  std::array<double, 4> value{};
};

// The angle cells of a row before its cells are read: the fixed angles set, the others zero.
AngleCells initial_angles(const Reading& r);
// Metadata from the comment lines seen before the header.
void read_metadata(Reading& r, SpectralDataset& d);
// A finite number (with the file's decimal separator); FileError naming `what` otherwise.
double number(Reading& r, std::string_view text, long column, std::string_view what);
double parse_brdf(Reading& r, std::string_view text, long column);
double parse_sigma(Reading& r, std::string_view text, long column);
Geometry parse_geometry(Reading& r, AngleConvention convention, const AngleCells& angles);
// A row with the wrong number of cells: `extra` = the cell at `column` is one too many, else the
// row ended after it.
[[noreturn]] void ragged(Reading& r, std::string_view line, std::size_t expected, std::string_view text, long column,
                         bool extra);
// What to say about duplicate geometries.
std::string duplicates_hint();
void finish_warnings(Reading& r, const SpectralDataset& d);
// (hi - lo) / |mean| of a duplicated cell (0 when all three are 0).
double relative_spread(double lo, double hi, double mean);
// Repeatability from the relative spreads of the duplicated cells, per wavelength.
Repeatability repeatability_of(std::vector<std::vector<double>>& spreads, std::size_t geometries);
// The pooled relative standard deviation (Repeatability::pooled_relative_sd) from, per wavelength, the
// sum of squared relative deviations and its degrees of freedom.
void set_pooled_relative_sd(Repeatability& out, const std::vector<double>& squares,
                            const std::vector<std::size_t>& degrees_of_freedom);

// A non-angle column of a long file's header.
struct LongColumn {
  std::string canonical;
  std::string text;
  long column;
  std::size_t index;
};
SpectralDataset read_long(Reading& r, const std::vector<LongColumn>& columns, std::size_t column_count,
                          const std::vector<std::size_t>& angle_columns, AngleConvention convention);

}  // namespace roadbrdf::dataset_read
