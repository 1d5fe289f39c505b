// Spectra Vista .sig reader. No specification is public. Sources:
//   [SpecDAL] EnSpec/SpecDAL, specdal/readers/sig.py (MIT): "key= value" header up to "data=",
//             whitespace-separated rows wavelength, reference, target, reflectance %; the units
//             line "Counts, Counts" / "Radiance, Radiance" / "Irradiance, Irradiance"; the
//             integration line's first three values for the reference, the last three for the target.
//   [files]   the seven real files in ../shared/real-data/instrument-files/ (PROVENANCE.md):
//             raw files with overlapping detectors, an overlap-removed ("moc") file, extra or
//             missing header lines.
// Inferred: the radiance unit (not in the file; SVC's convention is 10^-10 W cm^-2 nm^-1 sr^-1);
// rows of 3 values are wavelength, reference, target without a reflectance column.
#include "roadbrdf/io/sig.h"

#include <fmt/core.h>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/instrument_text.h"

namespace roadbrdf {

namespace {

using instrument_text::trim;

struct Row {
  double wavelength, reference, target, reflectance;
  long line;
};

// Apply the overlap rule at every join (a wavelength not above the previous one). Each detector
// segment is kept in order; see OverlapRule.
std::vector<Row> resolve_overlaps(const std::vector<Row>& rows, OverlapRule rule, const std::string& name,
                                  InstrumentSpectrum& s) {
  std::vector<std::vector<Row>> segments(1);
  for (const Row& r : rows) {
    if (!segments.back().empty() && !(r.wavelength > segments.back().back().wavelength)) segments.emplace_back();
    segments.back().push_back(r);
  }
  if (segments.size() == 1) {
    s.metadata["sig.overlap"] = "none (wavelengths increase throughout)";
    return rows;
  }
  std::string report;
  std::size_t dropped_total = 0;
  for (std::size_t j = 1; j < segments.size(); ++j) {
    std::vector<Row>& lower = segments[j - 1];
    std::vector<Row>& upper = segments[j];
    const long join_line = upper.front().line;
    if (rule == OverlapRule::kError) {
      throw FileError(name, join_line, 1,
                      fmt::format("detector overlap: wavelength {} nm follows {} nm (choose an overlap rule: upper "
                                  "or lower)",
                                  upper.front().wavelength, lower.back().wavelength));
    }
    std::size_t dropped = 0;
    double from = 0, to = 0;
    if (rule == OverlapRule::kUpper) {
      const double start = upper.front().wavelength;
      while (!lower.empty() && lower.back().wavelength >= start) {
        to = dropped == 0 ? lower.back().wavelength : to;
        from = lower.back().wavelength;
        lower.pop_back();
        ++dropped;
      }
      if (lower.empty()) throw FileError(name, join_line, 1, "a detector segment lies entirely inside the next one");
    } else {
      const double end = lower.back().wavelength;
      std::size_t n = 0;
      while (n < upper.size() && upper[n].wavelength <= end) ++n;
      if (n == upper.size())
        throw FileError(name, join_line, 1, "a detector segment lies entirely inside the previous one");
      if (n) {
        from = upper.front().wavelength;
        to = upper[n - 1].wavelength;
      }
      upper.erase(upper.begin(), upper.begin() + static_cast<long>(n));
      dropped = n;
    }
    dropped_total += dropped;
    report += fmt::format("{}join at line {}: {} channel(s) {:g}-{:g} nm of the {} detector dropped",
                          report.empty() ? "" : "; ", join_line, dropped, from, to,
                          rule == OverlapRule::kUpper ? "lower" : "upper");
  }
  s.metadata["sig.overlap"] = fmt::format("rule '{}': {}", name_of(rule), report);
  s.notes.push_back(fmt::format(
      "{}: detector overlap, rule '{}' kept {} detector's channels ({} channel(s) dropped, "
      "none averaged): {}",
      name, name_of(rule), rule == OverlapRule::kUpper ? "the next" : "the previous", dropped_total, report));
  std::vector<Row> out;
  for (const auto& seg : segments) out.insert(out.end(), seg.begin(), seg.end());
  return out;
}

}  // namespace

InstrumentSpectrum parse_sig(std::string_view text, const std::string& name, OverlapRule overlap) {
  const auto lines = instrument_text::lines(text);
  InstrumentSpectrum s;
  s.path = name;
  s.format = InstrumentFormat::kSig;
  if (lines.empty() || trim(lines[0].text).substr(0, 18) != "/*** Spectra Vista") {
    throw FileError(name, 1, 1, "first line is not '/*** Spectra Vista SIG Data ***/': not an SVC .sig file");
  }
  std::size_t k = 1;
  std::vector<long> other_lines;
  long units_line = 0;
  for (; k < lines.size(); ++k) {
    const std::string_view line = trim(lines[k].text);
    if (line.substr(0, 5) == "data=") break;
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      other_lines.push_back(lines[k].number);
      continue;
    }
    std::string key(trim(line.substr(0, eq)));
    for (char& c : key) c = c == ' ' ? '_' : c;
    if (key == "units") units_line = lines[k].number;
    s.metadata["sig." + instrument_text::printable(key)] = instrument_text::printable(trim(line.substr(eq + 1)));
  }
  if (k == lines.size()) {
    throw FileError(name, lines.back().number, 0, "no 'data=' line: truncated or not an SVC .sig file");
  }
  if (!other_lines.empty()) {
    s.metadata["sig.unrecognized_header_lines"] =
        fmt::format("{} (lines {} to {})", other_lines.size(), other_lines.front(), other_lines.back());
  }
  // Units of the reference and target columns ([SpecDAL]).
  std::string unit_name = "Radiance";
  if (auto it = s.metadata.find("sig.units"); it != s.metadata.end()) {
    const auto units = instrument_text::split_list(it->second);
    if (units.size() != 2 || units[0] != units[1]) {
      throw FileError(name, units_line, 0,
                      fmt::format("units line '{}': expected the same unit twice (reference, target)", it->second));
    }
    unit_name = units[0];
  }
  if (unit_name == "Radiance") {
    s.quantity = "radiance";
    s.units = "1e-10 W/cm^2/nm/sr (SVC convention; not stated in the file)";
  } else if (unit_name == "Irradiance") {
    s.quantity = "irradiance";
    s.units = "1e-10 W/cm^2/nm (SVC convention; not stated in the file)";
  } else if (unit_name == "Counts") {
    s.quantity = "DN";
    s.units = "DN";
  } else {
    throw FileError(name, units_line, 0, fmt::format("unknown units '{}' (Counts, Radiance or Irradiance)", unit_name));
  }
  std::vector<Row> rows;
  std::size_t width = 0;
  long first_data_line = 0;
  for (++k; k < lines.size(); ++k) {
    if (trim(lines[k].text).empty()) continue;
    const auto cells = split_whitespace(lines[k].text);
    if (width == 0) {
      width = cells.size();
      first_data_line = lines[k].number;
      if (width != 3 && width != 4) {
        throw FileError(
            name, lines[k].number, 1,
            fmt::format("{} values in a row: expected wavelength, reference, target[, reflectance %]", cells.size()));
      }
    }
    if (cells.size() != width) {
      throw FileError(name, lines[k].number, cells.back().column,
                      fmt::format("row has {} values, line {} had {}: truncated or corrupt file", cells.size(),
                                  first_data_line, width));
    }
    double v[4] = {0, 0, 0, 0};
    for (std::size_t c = 0; c < width; ++c) {
      if (!parse_finite_double(cells[c].text, v[c])) {
        throw FileError(name, lines[k].number, cells[c].column,
                        fmt::format("'{}' is not a finite number", instrument_text::printable(cells[c].text)));
      }
    }
    if (!(v[0] > 0)) throw FileError(name, lines[k].number, cells[0].column, "wavelength must be positive");
    rows.push_back({v[0], v[1], v[2], v[3], lines[k].number});
  }
  if (rows.empty()) throw FileError(name, lines.back().number, 0, "no data rows after 'data='");
  for (const Row& r : resolve_overlaps(rows, overlap, name, s)) {
    s.wavelengths.push_back(r.wavelength);
    s.reference.push_back(r.reference);
    s.target.push_back(r.target);
    if (width == 4) s.reflectance.push_back(r.reflectance / 100.0);
  }
  if (auto it = s.metadata.find("sig.integration"); it != s.metadata.end()) {
    const auto items = instrument_text::split_list(it->second);
    if (items.size() == 6) {  // [SpecDAL]: [0:3] reference, [3:] target
      s.reference_settings["integration times [ms]"] = items[0] + "," + items[1] + "," + items[2];
      s.target_settings["integration times [ms]"] = items[3] + "," + items[4] + "," + items[5];
    }
  }
  if (auto it = s.metadata.find("sig.instrument"); it != s.metadata.end())
    s.metadata["instrument"] = "SVC " + it->second;
  return s;
}

}  // namespace roadbrdf
