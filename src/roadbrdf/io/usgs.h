// USGS Spectral Library Version 7 ASCII spectra ("splib07a"; Kokaly et al. 2017, USGS Data Series
// 1035, doi:10.3133/ds1035; data release doi:10.5066/F7RR1WDJ).
//
// Format (DS1035, "ASCII data"; checked on the files under ../shared/real-data/usgs-splib07a-mixtures):
// - a spectrum file: one title line " splib07a Record=NNNNN: <title>", then one value per line
//   (reflectance, 1 = 100 %), one per channel of the instrument;
// - the channel wavelengths are not in the spectrum file but in a separate file of the same layout,
//   e.g. "splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt" (values in micrometres);
// - a missing (deleted) channel is written -1.23e+34.
// The library's "AREF" spectra are absolute directional reflectance of a lab set-up whose geometry is
// not recorded per file: usgs_dataset() stores them at a geometry the caller states, as the
// BRDF R / pi of a surface of reflectance factor R (exact for a Lambertian sample, the usual
// approximation otherwise; docs/mixing.md "Real intimate mixtures (USGS, Dalton et al. 2002)" says which geometry was
// assumed).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

// Values below this are the library's "deleted channel" marker (-1.23e+34).
inline constexpr double kUsgsMissingBelow = -1e30;

struct UsgsSpectrum {
  std::string path;                 // spectrum file
  std::string wavelength_path;      // wavelength file
  long record = 0;                  // splib07a record number of the spectrum
  std::string title;                // title after "Record=NNNNN:"
  long wavelength_record = 0;       // record number of the wavelength file
  std::string wavelength_title;     // its title
  std::vector<double> wavelengths;  // [nm], strictly increasing, missing channels removed
  std::vector<double> reflectance;  // [1], same length
  std::size_t channels = 0;         // channels in the files (including missing ones)
  std::size_t missing = 0;          // channels dropped (missing in the spectrum or the wavelength file)

  // Keys: the members' names.
  nlohmann::json to_json() const;
};

// Parse a spectrum and its wavelength file held in memory (`spectrum_name`, `wavelength_name` are
// used in errors). Throws FileError naming the file, line and column: a title line that is not
// "splib07a Record=N: ...", a value that is not a number, channel counts that differ (named with
// the line of the first extra or missing value), wavelengths not strictly increasing.
UsgsSpectrum parse_usgs_spectrum(std::string_view spectrum_text, const std::string& spectrum_name,
                                 std::string_view wavelength_text, const std::string& wavelength_name);

// Read both files. Throws FileError.
UsgsSpectrum read_usgs_spectrum(const std::string& path, const std::string& wavelength_path);

// A one-geometry dataset of BRDF = R / pi [sr^-1] (metadata: record, title, files, "usgs.quantity"
// = "reflectance factor / pi"). Throws InputError when the spectrum has no channel left.
SpectralDataset usgs_dataset(const UsgsSpectrum& spectrum, const Geometry& geometry, AngleConvention convention);

}  // namespace roadbrdf
