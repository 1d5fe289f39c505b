#include "roadbrdf/spectra/spectrum_file.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf::spectra {

namespace {

// The cells of a line: fields separated by ',' or ';', each split on spaces and tabs. An empty
// field (two separators in a row, one at the end) is an empty cell, which no number reads.
std::vector<CsvCell> split_cells_of(std::string_view line) {
  std::vector<CsvCell> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find_first_of(",;", start);
    const std::string_view field = line.substr(start, end == std::string_view::npos ? end : end - start);
    const std::vector<CsvCell> words = split_whitespace(field);
    if (words.empty()) cells.push_back({field.substr(0, 0), static_cast<long>(start + 1)});
    for (const CsvCell& w : words) cells.push_back({w.text, w.column + static_cast<long>(start)});
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return cells;
}

// Column names of a header row: its fields when it has separators (names may hold spaces), else
// its words.
std::vector<std::string> header_names(std::string_view line) {
  std::vector<std::string> names;
  if (line.find_first_of(",;") == std::string_view::npos) {
    for (const CsvCell& c : split_whitespace(line)) names.emplace_back(c.text);
    return names;
  }
  std::string fields(line);
  std::replace(fields.begin(), fields.end(), ';', ',');
  for (const CsvCell& c : split_cells(fields, ',')) names.emplace_back(c.text);
  return names;
}

// The layout of the rows the options accept, for messages.
std::string layout(const SpectrumReadOptions& o) {
  std::string text = "wavelength [nm], " + o.quantity;
  if (o.uncertainties) text += " [, uncertainty]";
  if (o.one_column) text += ", or " + o.quantity + " alone";
  return text;
}

}  // namespace

Spectrum read_spectrum(const std::string& path, const SpectrumReadOptions& o) {
  CsvReader reader(path, o.input);
  std::vector<double> w, v, sigma;
  std::vector<std::string> names;
  long header_line = 0;
  std::size_t columns = 0;      // cells per data row (set by the first)
  std::size_t value_index = 1;  // the value's cell
  const bool wide = !o.value_column.empty();
  std::string_view line;
  while (reader.next_line(line)) {
    const std::vector<CsvCell> cells = split_cells_of(line);
    if (columns == 0 &&
        std::none_of(cells.begin(), cells.end(), [](const CsvCell& c) { return is_number_text(c.text); })) {
      names = header_names(line);
      header_line = reader.line_number();
      continue;
    }
    if (columns == 0) {
      columns = cells.size();
      if (wide) {
        const auto named = std::find(names.begin(), names.end(), o.value_column);
        if (named == names.end()) throw FileError(reader.path(), header_line, 0, "no column '" + o.value_column + "'");
        value_index = static_cast<std::size_t>(named - names.begin());
        if (value_index == 0 || value_index >= columns) {
          reader.fail(0, fmt::format("column '{}' is column {} of {} cells", o.value_column, value_index + 1, columns));
        }
      } else if (columns > (o.uncertainties ? 3u : 2u)) {
        reader.fail(cells[o.uncertainties ? 3 : 2].column,
                    fmt::format("expected the columns {}, found {}", layout(o), columns));
      } else if (columns == 1) {
        if (!o.one_column) reader.fail(0, fmt::format("expected the columns {}, found 1", layout(o)));
        if (!(o.first_wavelength && o.step)) {
          reader.fail(0, "one-column spectrum: give the wavelength of the first line and the step [nm]");
        }
        if (!(std::isfinite(*o.first_wavelength) && std::isfinite(*o.step) && *o.step > 0.0)) {
          reader.fail(0, fmt::format("one-column spectrum: the first wavelength {} and step {} nm must be finite "
                                     "and the step > 0",
                                     *o.first_wavelength, *o.step));
        }
        value_index = 0;
      }
    }
    if (cells.size() != columns) {
      reader.fail(cells.size() > columns ? cells[columns].column : cells.back().column,
                  fmt::format("row has {} values, the first row had {}", cells.size(), columns));
    }
    const double value = reader.number(cells[value_index], o.quantity);
    if (o.non_negative && value < 0.0) {
      reader.fail(cells[value_index].column, fmt::format("negative {} '{}'", o.quantity, cells[value_index].text));
    }
    double wavelength = 0.0;
    if (columns == 1) {
      wavelength = *o.first_wavelength + static_cast<double>(v.size()) * *o.step;
    } else {
      wavelength = reader.number(cells[0], "wavelength [nm]");
      if (!w.empty() && !(wavelength > w.back())) {
        reader.fail(cells[0].column,
                    fmt::format("wavelength '{}' nm is not above the previous {} nm (must be strictly increasing)",
                                cells[0].text, w.back()));
      }
    }
    if (!wide && columns == 3) {
      const double s = reader.number(cells[2], "uncertainty");
      if (s < 0.0) reader.fail(cells[2].column, fmt::format("'{}': negative uncertainty", cells[2].text));
      sigma.push_back(s);
    }
    w.push_back(wavelength);
    v.push_back(value);
  }
  if (v.empty()) throw FileError(reader.path(), reader.line_number(), 0, "file is empty (no values)");
  if (v.size() < o.min_points) {
    throw FileError(reader.path(), 0, 0,
                    fmt::format("needs at least {} rows of values, found {}", o.min_points, v.size()));
  }
  try {
    Spectrum s(o.name.empty() ? path : o.name, std::move(w), std::move(v), o.interpolation, o.outside,
               std::move(sigma));
    if (o.positive_integral) {
      // Weights E / integral(E) need a finite, positive integral (1e308 values overflow it; an
      // all-zero spectrum has no weights).
      const double total = trapezoid_integral(s);
      if (!(std::isfinite(total) && total > 0.0)) {
        throw FileError(reader.path(), 0, 0,
                        "the " + o.quantity + " integrates to " + std::to_string(total) +
                            " (must be finite and > 0: values too large, or all zero)");
      }
    }
    return s;
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    throw FileError(reader.path(), 0, 0, e.what());  // e.g. a one-column grid beyond the largest double
  }
}

}  // namespace roadbrdf::spectra
