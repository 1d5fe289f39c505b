#include "roadbrdf/io/usgs.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/io/instrument_text.h"

namespace roadbrdf {

namespace {

struct Column {
  long record = 0;
  std::string title;
  std::vector<double> values;
  std::vector<long> lines;  // 1-based line of each value
};

// The title line " splib07a Record=NNNNN: title" and one number per following line; blank lines
// are allowed (a trailing newline), anything else is an error at its line and column.
Column parse_column(std::string_view text, const std::string& name) {
  Column c;
  const std::vector<instrument_text::Line> lines = instrument_text::lines(text);
  const long line_count = static_cast<long>(lines.size());
  bool title_seen = false;
  for (const auto& [line, line_number] : lines) {
    constexpr std::string_view kSpace = kBlankCharacters;
    const std::size_t a = std::min(line.find_first_not_of(kSpace), line.size());
    const std::size_t b = a == line.size() ? a : line.find_last_not_of(kSpace) + 1;
    const std::string_view item = line.substr(a, b - a);
    const long column = static_cast<long>(a) + 1;
    if (!title_seen) {
      constexpr std::string_view kPrefix = "splib07a Record=";
      if (item.substr(0, kPrefix.size()) != kPrefix) {
        throw FileError(name, line_number, column,
                        "not a USGS splib07a ASCII file: the first line must start with 'splib07a Record=N:'");
      }
      const std::size_t colon = item.find(':', kPrefix.size());
      const std::string_view number = item.substr(
          kPrefix.size(), colon == std::string_view::npos ? std::string_view::npos : colon - kPrefix.size());
      double record = 0.0;
      if (colon == std::string_view::npos || !parse_finite_double(number, record) || record < 0.0 ||
          record != std::floor(record) || record > 1e9) {
        throw FileError(name, line_number, column + static_cast<long>(kPrefix.size()),
                        "expected the record number and ':' after 'splib07a Record='");
      }
      c.record = static_cast<long>(record);
      const std::string_view title = item.substr(colon + 1);
      c.title = std::string(title.substr(std::min(title.find_first_not_of(kSpace), title.size())));
      title_seen = true;
      continue;
    }
    if (item.empty()) continue;
    double value = 0.0;
    if (!parse_finite_double(item, value)) {
      throw FileError(name, line_number, column,
                      fmt::format("'{}' is not a number (one value per line)", std::string(item.substr(0, 40))));
    }
    c.values.push_back(value);
    c.lines.push_back(line_number);
  }
  if (!title_seen) throw FileError(name, 1, 1, "empty file: not a USGS splib07a ASCII file");
  if (c.values.empty()) throw FileError(name, line_count, 1, "no values after the title line");
  return c;
}

}  // namespace

UsgsSpectrum parse_usgs_spectrum(std::string_view spectrum_text, const std::string& spectrum_name,
                                 std::string_view wavelength_text, const std::string& wavelength_name) {
  const Column s = parse_column(spectrum_text, spectrum_name);
  const Column w = parse_column(wavelength_text, wavelength_name);
  if (s.values.size() != w.values.size()) {
    const bool spectrum_longer = s.values.size() > w.values.size();
    const Column& longer = spectrum_longer ? s : w;
    const std::size_t n = std::min(s.values.size(), w.values.size());
    throw FileError(spectrum_longer ? spectrum_name : wavelength_name, longer.lines[n], 1,
                    fmt::format("{} values but the {} has {} ({}): wrong wavelength file for this spectrum?",
                                longer.values.size(), spectrum_longer ? "wavelength file" : "spectrum", n,
                                spectrum_longer ? wavelength_name : spectrum_name));
  }
  UsgsSpectrum out;
  out.path = spectrum_name;
  out.wavelength_path = wavelength_name;
  out.record = s.record;
  out.title = s.title;
  out.wavelength_record = w.record;
  out.wavelength_title = w.title;
  out.channels = s.values.size();
  double previous = -1.0;
  long previous_line = 0;
  for (std::size_t i = 0; i < s.values.size(); ++i) {
    if (s.values[i] < kUsgsMissingBelow || w.values[i] < kUsgsMissingBelow) {
      ++out.missing;
      continue;
    }
    // The wavelength files are in micrometres, written in single precision (~1e-7 relative): rounded to
    // 1e-3 nm so that 0.34999999 um is 350 nm.
    const double nm = std::round(w.values[i] * 1e6) / 1e3;
    // 1e6 um (1 m) bounds any spectrometer and keeps the conversion finite (1e303 um would be inf nm).
    if (!(nm > 0.0) || !(w.values[i] < 1e6)) {
      throw FileError(wavelength_name, w.lines[i], 1, "wavelength must be > 0 and < 1e6 (micrometres)");
    }
    if (nm <= previous) {
      throw FileError(wavelength_name, w.lines[i], 1,
                      fmt::format("wavelengths must increase: {} um after {} um on line {}", w.values[i],
                                  previous / 1000.0, previous_line));
    }
    previous = nm;
    previous_line = w.lines[i];
    out.wavelengths.push_back(nm);
    out.reflectance.push_back(s.values[i]);
  }
  return out;
}

UsgsSpectrum read_usgs_spectrum(const std::string& path, const std::string& wavelength_path) {
  // One number per line for a few thousand channels: a few tens of kB.
  InputLimits limits;
  limits.what = "a USGS splib07a file";
  limits.max_bytes = std::uintmax_t{64} << 20;
  const std::string spectrum = read_text_file(path, limits);
  const std::string wavelengths = read_text_file(wavelength_path, limits);
  return parse_usgs_spectrum(spectrum, path, wavelengths, wavelength_path);
}

SpectralDataset usgs_dataset(const UsgsSpectrum& s, const Geometry& geometry, AngleConvention convention) {
  if (s.wavelengths.empty()) throw InputError(fmt::format("{}: every channel is missing", s.path));
  SpectralDataset d;
  d.geometries = {geometry};
  d.wavelengths = s.wavelengths;
  d.brdf.reserve(s.reflectance.size());
  for (double r : s.reflectance) d.brdf.push_back(r / kPi);
  d.convention = convention;
  d.metadata["usgs.record"] = std::to_string(s.record);
  d.metadata["usgs.title"] = s.title;
  d.metadata["usgs.wavelength_record"] = std::to_string(s.wavelength_record);
  d.metadata["usgs.missing_channels"] = std::to_string(s.missing);
  d.metadata["usgs.quantity"] = "reflectance factor / pi";
  d.metadata["units"] = "sr^-1";
  d.metadata["instrument_file"] = s.path;
  d.metadata["wavelength_file"] = s.wavelength_path;
  return d;
}

nlohmann::json UsgsSpectrum::to_json() const {
  return {{"path", path},
          {"wavelength_path", wavelength_path},
          {"record", record},
          {"title", title},
          {"wavelength_record", wavelength_record},
          {"wavelength_title", wavelength_title},
          {"wavelengths", wavelengths},
          {"reflectance", reflectance},
          {"channels", channels},
          {"missing", missing}};
}

}  // namespace roadbrdf
