#include "roadbrdf/io/curet.h"

#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf {

namespace {

double number_or_throw(const std::string& path, long line, const CsvCell& cell, const char* what) {
  double v = 0.0;
  if (!parse_finite_double(cell.text, v)) {
    throw FileError(path, line, cell.column, fmt::format("'{}' is not a {}", cell.text, what));
  }
  return v;
}

bool is_blank_or_comment(const std::string& line) {
  const auto b = line.find_first_not_of(kBlankCharacters);
  return b == std::string::npos || line[b] == '#';
}

// A sample number: an integer >= 1 (compared as a double first: casting an out-of-range double to int
// is undefined).
int sample_number(const std::string& path, long line, const CsvCell& cell) {
  const double v = number_or_throw(path, line, cell, "sample number");
  if (!(v >= 1.0 && v <= static_cast<double>(std::numeric_limits<int>::max())) || v != std::floor(v)) {
    throw FileError(path, line, cell.column, fmt::format("sample number '{}' is not an integer >= 1", cell.text));
  }
  return static_cast<int>(v);
}

}  // namespace

std::vector<int> curet_sample_numbers(const std::string& abrdf_path) {
  InputFile in(abrdf_path);
  std::vector<int> numbers;
  std::string line;
  long n = 0;
  while (in.read_line(line)) {
    ++n;
    if (is_blank_or_comment(line)) continue;
    const auto cells = split_whitespace(line);
    numbers.push_back(sample_number(abrdf_path, n, cells[0]));
  }
  if (numbers.empty()) throw FileError(abrdf_path, n, 0, "file is empty (no sample lines)");
  return numbers;
}

SpectralDataset read_curet(const std::string& abrdf_path, const std::string& table_path, int sample,
                           const CuretReadOptions& options) {
  if (!(options.nominal_wavelength_nm > 0.0)) throw InputError("CUReT nominal wavelength must be positive [nm]");
  SpectralDataset d;
  // Geometry table: index, theta_v, phi_v, theta_i, phi_i (radians).
  {
    InputFile in(table_path);
    std::string line;
    long n = 0;
    while (in.read_line(line)) {
      ++n;
      if (is_blank_or_comment(line)) continue;
      const auto cells = split_whitespace(line);
      if (cells.size() != 5) {
        throw FileError(table_path, n, cells.size() > 5 ? cells[5].column : cells.back().column,
                        fmt::format("expected 5 values (index, theta_v, phi_v, theta_i, phi_i in radians), found {}",
                                    cells.size()));
      }
      const double index = number_or_throw(table_path, n, cells[0], "geometry index");
      if (index != static_cast<double>(d.geometries.size() + 1)) {
        throw FileError(
            table_path, n, cells[0].column,
            fmt::format("geometry index '{}' out of sequence (expected {})", cells[0].text, d.geometries.size() + 1));
      }
      double a[4];
      for (std::size_t k = 0; k < 4; ++k) a[k] = number_or_throw(table_path, n, cells[k + 1], "angle in radians");
      for (std::size_t k : {0u, 2u}) {
        if (a[k] < 0.0 || a[k] > kPi / 2 + 1e-6) {
          throw FileError(table_path, n, cells[k + 1].column,
                          fmt::format("zenith angle '{}' rad is outside [0, pi/2]", cells[k + 1].text));
        }
      }
      // theta_i, phi_i, theta_r = theta_v, phi_r = phi_v
      d.geometries.push_back(geometry_from_radians(std::fmin(a[2], kPi / 2), a[3], std::fmin(a[0], kPi / 2), a[1]));
    }
    if (d.geometries.empty()) throw FileError(table_path, n, 0, "file is empty (no geometry lines)");
  }
  const std::size_t count = d.geometries.size();
  // Sample line.
  {
    InputFile in(abrdf_path);
    std::string line;
    long n = 0;
    bool found = false;
    std::vector<int> present;
    std::size_t negative = 0;
    std::string first_negative;
    while (in.read_line(line)) {
      ++n;
      if (is_blank_or_comment(line)) continue;
      const auto cells = split_whitespace(line);
      const int number = sample_number(abrdf_path, n, cells[0]);
      present.push_back(number);
      if (number != sample) continue;
      if (found) throw FileError(abrdf_path, n, cells[0].column, fmt::format("sample {} appears twice", sample));
      found = true;
      if (cells.size() != count + 1) {
        throw FileError(abrdf_path, n, cells.size() > count + 1 ? cells[count + 1].column : cells.back().column,
                        fmt::format("sample {} has {} values but {} lists {} geometries", sample, cells.size() - 1,
                                    table_path, count));
      }
      for (std::size_t k = 0; k < count; ++k) {
        const double v = number_or_throw(abrdf_path, n, cells[k + 1], "BRDF value");
        if (v < 0.0 && negative++ == 0) first_negative = fmt::format("{}:{}:{}", abrdf_path, n, cells[k + 1].column);
        d.brdf.push_back(v);
      }
    }
    if (!found) {
      std::string list;
      for (int p : present) list += fmt::format("{}{}", list.empty() ? "" : " ", p);
      throw InputError(fmt::format("{}: no sample {} (samples present: {})", abrdf_path, sample, list));
    }
    if (negative > 0) {
      const std::string message = fmt::format(
          "{}: sample {}: {} of {} BRDF values are negative (kept: measurement "
          "noise; first at {})",
          abrdf_path, sample, negative, count, first_negative);
      if (options.warn) {
        options.warn(message);
      } else {
        route_warning(message);
      }
    }
  }
  d.wavelengths = {options.nominal_wavelength_nm};
  d.metadata["sample"] = fmt::format("CUReT sample {}", sample);
  d.metadata["source"] = "CUReT BRDF database (Dana et al., ACM TOG 18(1), 1999)";
  d.metadata["units"] = "sr^-1";
  d.metadata["wavelength_note"] =
      fmt::format("grey (average of the R, G, B channels), stored at a nominal {} nm", options.nominal_wavelength_nm);
  return d;
}

}  // namespace roadbrdf
