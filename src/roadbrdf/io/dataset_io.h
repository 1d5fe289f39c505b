// Reading and writing spectral BRDF datasets (SpectralDataset, io/dataset.h) as CSV.
//
// Wide CSV (the default):
//   # free comment lines
//   # sample: bitumen            <- "# key: value" lines before the header are metadata
//   # units: sr^-1               <- optional; only sr^-1 (BRDF) is accepted by read_dataset
//   theta_i,phi_i,theta_r,phi_r,400,410,...,sigma_400,sigma_410,...
//   (or gamma,alpha,beta,delta for the road convention; all angles in degrees)
//   Each wavelength column is named by its value in nm; the wavelengths must be strictly
//   increasing. The optional sigma_<nm> block holds standard uncertainties [sr^-1] and must list
//   exactly the same wavelengths in the same order.
//
// Foreign tables (laboratory goniometers, spreadsheets): DatasetReadOptions maps header names to the
// dataset's columns (`columns`), fixes angles the file has no column for (`fixed_angles`) and converts
// the quantity stored (`quantity`: BRF, BRDF cos theta_i, percent). With a mapping or fixed angles,
// the other header columns are not read, with a warning listing them.
//
// Long CSV: the four angle columns plus wavelength,brdf[,sigma]; one row per (geometry, wavelength).
//   The wavelengths are those of all rows; a (geometry, wavelength) pair without a row is a
//   missing cell (NaN), like an empty one. Two rows of the same pair are duplicates.
//
// Files as people write them are read alike: ';' or tab delimiters, decimal commas, a byte order
// mark, CRLF, header names in any case, with units or aliases (io/dataset_dialect.h).
//
// Both are streamed line by line. Every problem is reported as FileError (file:line:column and
// the offending text); nothing is dropped silently. Negative BRDF values are kept, counted and
// reported as a warning (measurement noise is real). Implausible files are read as they are, with a
// warning: BRDF values above 1e3 sr^-1, wavelengths that all look like micrometres (below 30),
// angles that all look like radians (within +-1.6).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

// The layouts of a dataset CSV file (see above).
enum class DatasetFormat { kWide, kLong };
inline constexpr EnumName<DatasetFormat> kDatasetFormatNames[] = {
    {DatasetFormat::kWide, "wide", "one row per geometry, one column per wavelength"},
    {DatasetFormat::kLong, "long", "one row per geometry and wavelength"},
};
constexpr std::span<const EnumName<DatasetFormat>> enum_names(DatasetFormat) { return kDatasetFormatNames; }

// The quantity a file's values hold; the reader converts them to BRDF [sr^-1] (and their sigma alike)
// and records the quantity in the dataset's metadata `quantity_read`.
//   brdf        BRDF [sr^-1] (no conversion)
//   brf         reflectance factor R = pi BRDF (Nicodemus et al. 1977, NBS Monograph 160, eq. 5.1 for a
//               Lambertian reference), most remote-sensing and laboratory goniometers
//   brdf-cos    BRDF cos(theta_i) [sr^-1] (ALTA's INV_STERADIAN_COSINE_FACTOR): divided by cos(theta_i);
//               a value at theta_i = 90 deg (no irradiance) becomes missing (NaN), counted in a warning
//   percent-brf 100 R (reflectance factor in percent)
enum class DatasetQuantity { kBrdf, kBrf, kBrdfCos, kPercentBrf };
inline constexpr EnumName<DatasetQuantity> kDatasetQuantityNames[] = {
    {DatasetQuantity::kBrdf, "brdf", "BRDF in sr^-1"},
    {DatasetQuantity::kBrf, "brf", "reflectance factor, pi x BRDF"},
    {DatasetQuantity::kBrdfCos, "brdf-cos", "BRDF x cos(theta_i) in sr^-1"},
    {DatasetQuantity::kPercentBrf, "percent-brf", "reflectance factor in percent, 100 pi x BRDF"},
};
constexpr std::span<const EnumName<DatasetQuantity>> enum_names(DatasetQuantity) { return kDatasetQuantityNames; }
// The factor f(cos theta_i) with BRDF = value / f: pi, cos(theta_i), 100 pi or 1.
double quantity_factor(DatasetQuantity quantity, double cos_theta_i);

// How a dataset file is read. The same options, validated by validate_read_options, are offered
// by every command that reads datasets (cli/dataset_flags.h) and by Python (read_dataset, fit, ...).
struct DatasetReadOptions {
  // Dialect (io/dataset_dialect.h): cell delimiter ',', ';' or '\t', 0 = detect from the header
  // line; decimal separator '.' or ',' (not with ','), 0 = detect from the numbers.
  char delimiter = 0;
  char decimal = 0;
  // Two rows with the same four angles: error (default), or average them (sigma of the mean
  // = sqrt(sum sigma^2)/n when sigmas are given; the count is recorded in metadata
  // "averaged_duplicate_rows").
  bool average_duplicates = false;
  // Empty cells and "nan"/"NA" in BRDF and sigma columns are measurements that were not made:
  // kept as NaN (default; counted in DatasetReadStats and the warning, never replaced by a value),
  // or an error when false. Angles and wavelengths can never be missing. Averaged duplicates
  // average the values that were measured (a cell missing in every duplicate stays missing). A
  // long file's (geometry, wavelength) pair without a row is missing too (DatasetReadStats
  // absent_rows).
  bool allow_missing = true;
  // What the values are (see DatasetQuantity); converted to BRDF on reading.
  DatasetQuantity quantity = DatasetQuantity::kBrdf;
  // Column mapping: dataset field (theta_i, phi_i, theta_r, phi_r, gamma, alpha, beta, delta,
  // wavelength, brdf, sigma) -> the file's header name (compared as written, then ignoring case and
  // surrounding blanks). A mapped name that is not in the header is an error naming the nearest one.
  std::map<std::string, std::string> columns;
  // Angles the file has no column for, one value [deg] for every row: field -> value. An angle given
  // here and present as a column is an error.
  std::map<std::string, double> fixed_angles;
  // Accept any "# units:" metadata (e.g. radiances read by `calibrate`); otherwise only sr^-1.
  bool any_units = false;
  // Where warnings go (negative values, missing values, averaged duplicates). Default: the front
  // end's sink (core/diagnostics.h route_warning); the library never prints.
  std::function<void(const std::string&)> warn;
};

// Values of `quantity` (read from `source`) converted to BRDF in place, sigma alike; the quantity is
// recorded in metadata `quantity_read` (a units line becomes `source_units`). A dataset whose metadata
// already has `quantity_read` was converted before: an error. brdf-cos values at theta_i = 90 deg become
// missing, counted through `warn` (default: the front end's sink).
void convert_to_brdf(SpectralDataset& dataset, DatasetQuantity quantity, const std::string& source,
                     const std::function<void(const std::string&)>& warn = {});

// Throws InputError/FieldError for contradictory options (e.g. decimal ',' with delimiter ',').
void validate_read_options(const DatasetReadOptions& options);
// The part of it that checks `columns` and `fixed_angles` (FieldError "columns" / "set").
void validate_mapping_options(const DatasetReadOptions& options);

// How far repeated measurements of one geometry (duplicate rows, averaged when asked) disagree: per
// wavelength, the relative spread (max - min) / |mean| of each duplicated cell, and its median and
// largest value over the duplicated geometries. The first estimate of the measurement noise a user has
// (a relative spread of two normal deviates of standard deviation s has mean 2 s / sqrt(pi) = 1.13 s).
struct Repeatability {
  std::size_t geometries = 0;                  // geometries with more than one row
  std::vector<double> median_relative_spread;  // per wavelength (NaN where no duplicated cell is measured)
  std::vector<double> max_relative_spread;     // per wavelength
  // The repeatability standard deviation of one measurement relative to its value, per wavelength:
  // the pooled estimate of ISO 5725-2:1994 (s_r^2 = sum_g (n_g - 1) s_g^2 / sum_g (n_g - 1)) applied to
  // the relative deviations (y_gk - mean_g) / mean_g of the duplicated cells, i.e.
  //   s_rel^2 = sum_g sum_k ((y_gk - mean_g) / mean_g)^2 / sum_g (n_g - 1),
  // with its degrees of freedom sum_g (n_g - 1) (0 and NaN where no duplicated cell is measured; a cell
  // whose mean is 0 has no relative deviation and is left out). Single files only (not combined runs).
  std::vector<double> pooled_relative_sd;
  std::vector<std::size_t> degrees_of_freedom;
  // Measured rows averaged into each cell (geometry-major like SpectralDataset::brdf); empty when no
  // geometry is duplicated.
  std::vector<std::uint32_t> cell_counts;
};

// Counts found while reading (also in the warnings).
struct DatasetReadStats {
  std::size_t negative_values = 0;
  std::size_t missing_values = 0;  // missing cells written as such (empty, nan, NA)
  std::size_t absent_rows = 0;     // long files: (geometry, wavelength) pairs without a row, also missing
  std::size_t averaged_duplicate_rows = 0;
  std::size_t implausible_values = 0;  // BRDF values above 1e3 sr^-1
  // Averaged duplicates: how far the rows of one geometry disagree (see Repeatability).
  Repeatability repeatability;
  bool micrometre_wavelengths = false;  // every wavelength below 30 "nm": probably micrometres
  bool metre_wavelengths = false;       // every wavelength below 1e-4 "nm": probably metres
  bool radian_angles = false;           // zeniths within 1.6 "deg" and azimuths within +-6.3 "deg": probably radians
};

// Number of missing (NaN) BRDF values of a dataset.
std::size_t missing_value_count(const SpectralDataset& dataset);

// Read a wide or long CSV dataset: the format is detected from the header (a "wavelength" column
// means long). Throws FileError.
SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options = {});
SpectralDataset read_dataset(const std::string& path, const DatasetReadOptions& options, DatasetReadStats& stats);

// Write wide or long CSV atomically (temporary file, then rename). Angles are written in the
// dataset's convention, values with round-trip precision. Metadata keys become "# key: value"
// lines ("units: sr^-1" is always written). Throws InputError / FileError.
void write_dataset(const SpectralDataset& dataset, const std::string& path,
                   DatasetFormat format = DatasetFormat::kWide);
// Same to a stream (e.g. standard output).
void write_dataset(const SpectralDataset& dataset, std::ostream& out, DatasetFormat format = DatasetFormat::kWide);
// The output of a task that makes a dataset (calibrate, resample, simulate, convert): written to its
// request's `output` when one is given ("-" = standard output; "" = not written), in the format named
// by `format` (a name of kDatasetFormatNames, read as the request field `format_field`).
void write_dataset_output(const SpectralDataset& dataset, const std::string& output, const std::string& format,
                          const std::string& format_field = "format");

// The four angles (degrees) of a geometry in a convention, in the column order of that convention.
void angle_values_of_geometry(const Geometry& g, AngleConvention convention, double out[4]);

// Check the dataset's internal consistency: sizes, finite angles, finite positive strictly
// increasing wavelengths, no infinite BRDF value (NaN = not measured), sigma finite and >= 0 (or
// NaN). Throws InputError.
void validate_dataset(const SpectralDataset& dataset);
// validate_dataset and what a file must hold to read back the same: metadata keys and values as in
// is_metadata_key, on one line; comments on one line and not of the form "key: value".
void validate_dataset_for_writing(const SpectralDataset& dataset);

// Comment lines of a dataset file: "# key: value", with a key of letters, digits, '_', '-' and '.',
// is metadata (SpectralDataset::metadata); any other comment is a free comment
// (SpectralDataset::comments), kept in order by the writers.
bool is_metadata_key(std::string_view key);
bool is_metadata_comment(std::string_view comment_text);
// The first comment line the writers put in a dataset file (followed by the format); not kept as a
// free comment when read back.
inline constexpr std::string_view kDatasetBanner = "roadbrdf spectral BRDF dataset";

}  // namespace roadbrdf
