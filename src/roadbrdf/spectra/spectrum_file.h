// Spectrum files: the one reader of tabulated spectra (lamp and solar spectra, panel reflectances,
// the bundled CIE and ASTM tables, spectral model parameters).
//
// Format: text lines of cells separated by commas, semicolons, spaces or tabs ("350 0.98 0.005",
// "350,0.98"); '#' starts a comment line; blank lines are skipped; a UTF-8 byte order mark is not
// part of the first cell. Rows before the data in which no cell is a number are header rows, the
// last one naming the columns; a row with any number in it is data, so that a typo such as "4OO,1"
// is an error at its cell rather than a skipped header. The data rows are
//   wavelength [nm], value               (two columns)
//   wavelength [nm], value, uncertainty  (three, when uncertainties are accepted)
//   value                                (one, when the caller gives the grid: first wavelength and step)
// or, in a wider table, the wavelength and the column named by `value_column` in the header.
// Wavelengths strictly increasing, numbers finite. Every error is a FileError naming the file, the
// line and the column of the cell.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "roadbrdf/core/input_file.h"
#include "roadbrdf/spectra/spectrum.h"

namespace roadbrdf::spectra {

struct SpectrumReadOptions {
  std::string name;                        // the spectrum's name; empty: the path
  std::string quantity = "value";          // what the values are, for messages ("irradiance", "spectral power")
  std::string value_column;                // a table of more columns: the header name of the value column
  bool uncertainties = true;               // a third column may hold the values' standard uncertainties (>= 0)
  bool one_column = true;                  // a file may hold values only, on the grid below
  std::optional<double> first_wavelength;  // the grid of a one-column file [nm]: wavelength of the first value
  std::optional<double> step;              // and the step (> 0)
  bool non_negative = false;               // values must be >= 0
  std::size_t min_points = 1;              // at least this many rows of values
  bool positive_integral = false;          // the trapezoid integral of the values must be finite and > 0
  // How the spectrum is interpolated and what it is outside its range (spectra/interpolation.h).
  Interpolation interpolation = Interpolation::kLinear;
  Extrapolation outside = Extrapolation::kRefuseBeyondRounding;
  // What the file may be (core/input_file.h): its size, its line length, a regular file or any.
  InputLimits input;
};

// Read a spectrum file ("-": standard input). Throws FileError.
Spectrum read_spectrum(const std::string& path, const SpectrumReadOptions& options = {});

}  // namespace roadbrdf::spectra
