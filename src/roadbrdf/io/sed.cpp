// Spectral Evolution .sed reader. No specification is public. Sources:
//   [SpecDAL] EnSpec/SpecDAL, specdal/readers/sed.py (MIT): "Key: value" header up to "Data:",
//             tab-separated columns, the column-name table (SED_COLUMNS), "Reflect. %" in percent.
//   [files]   the four real files in ../shared/real-data/instrument-files/ (PROVENANCE.md):
//             REFLECTANCE, DIRECT_ENERGY (no reflectance column) and radiance files, CRLF lines,
//             extra or missing header lines.
// Inferred ([files]): in "Integration: a,b,c,d,e,f" and "Averages: r,t" the first half belongs to
// the reference scan, the second to the target (the "Time:" pair lists the reference first).
#include "roadbrdf/io/sed.h"

#include <fmt/core.h>

#include <cctype>
#include <cmath>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/instrument_text.h"

namespace roadbrdf {

namespace {

using instrument_text::trim;

enum class Role { kWavelength, kChannel, kReference, kTarget, kReflectancePercent, kReflectanceFraction };

struct Column {
  Role role;
  std::string quantity;  // for reference/target: "normalized DN", "DN", "radiance", "irradiance"
};

// Column name -> meaning ([SpecDAL] SED_COLUMNS, extended to "DN (...)" by analogy).
bool classify(std::string_view name, Column& c) {
  if (name == "Wvl") return c = {Role::kWavelength, ""}, true;
  if (name == "Chan.#") return c = {Role::kChannel, ""}, true;
  if (name == "Reflect. %" || name == "Tgt./Ref. %") return c = {Role::kReflectancePercent, ""}, true;
  if (name == "Reflect. [1.0]") return c = {Role::kReflectanceFraction, ""}, true;
  Role role;
  std::string_view prefix;
  if (name.size() > 8 && name.substr(name.size() - 7) == " (Ref.)") {
    role = Role::kReference;
    prefix = name.substr(0, name.size() - 7);
  } else if (name.size() > 9 && name.substr(name.size() - 9) == " (Target)") {
    role = Role::kTarget;
    prefix = name.substr(0, name.size() - 9);
  } else {
    return false;
  }
  if (prefix == "Norm. DN") return c = {role, "normalized DN"}, true;
  if (prefix == "DN") return c = {role, "DN"}, true;
  if (prefix == "Rad.") return c = {role, "radiance"}, true;
  if (prefix == "Irrad.") return c = {role, "irradiance"}, true;
  return false;
}

std::string key_name(std::string_view key) {
  std::string k;
  for (char ch : key) {
    const auto u = static_cast<unsigned char>(ch);
    if (std::isalnum(u)) {
      k += static_cast<char>(std::tolower(u));
    } else if (!k.empty() && k.back() != '_') {
      k += '_';
    }
  }
  while (!k.empty() && k.back() == '_') k.pop_back();
  return k;
}

// Split a "ref,ref,..,tgt,tgt,.." list in two halves (inferred, see above).
void halves(const std::string& value, std::string& reference, std::string& target) {
  const auto items = instrument_text::split_list(value);
  if (items.size() % 2 != 0) return;
  for (std::size_t k = 0; k < items.size(); ++k) {
    std::string& out = k < items.size() / 2 ? reference : target;
    out += (out.empty() ? "" : ",") + items[k];
  }
}

}  // namespace

InstrumentSpectrum parse_sed(std::string_view text, const std::string& name) {
  const auto lines = instrument_text::lines(text);
  InstrumentSpectrum s;
  s.path = name;
  s.format = InstrumentFormat::kSed;
  std::size_t k = 0;
  long channels_line = 0;
  std::size_t channels = 0;
  std::vector<long> other_lines;
  for (; k < lines.size(); ++k) {
    const std::string_view line = trim(lines[k].text);
    if (line == "Data:") break;
    const auto colon = line.find(':');
    if (line.empty()) continue;
    if (colon == std::string_view::npos || colon == 0) {
      other_lines.push_back(lines[k].number);
      continue;
    }
    const std::string key = key_name(line.substr(0, colon));
    const std::string value = instrument_text::printable(trim(line.substr(colon + 1)));
    if (key.empty()) {
      other_lines.push_back(lines[k].number);
      continue;
    }
    s.metadata["sed." + key] = value;
    if (key == "channels") {
      double c = 0;
      if (!parse_finite_double(value, c) || c < 1 || c != std::floor(c)) {
        throw FileError(name, lines[k].number, 0, fmt::format("'Channels: {}' is not a positive whole number", value));
      }
      channels = static_cast<std::size_t>(c);
      channels_line = lines[k].number;
    }
  }
  if (k == lines.size()) {
    throw FileError(name, lines.empty() ? 0 : lines.back().number, 0,
                    "no 'Data:' line: not a Spectral Evolution .sed file, or truncated");
  }
  if (!other_lines.empty()) {
    s.metadata["sed.unrecognized_header_lines"] =
        fmt::format("{} (lines {} to {})", other_lines.size(), other_lines.front(), other_lines.back());
  }
  // Column names, tab-separated ([SpecDAL] sep='\t').
  ++k;
  while (k < lines.size() && trim(lines[k].text).empty()) ++k;
  if (k == lines.size()) throw FileError(name, lines.back().number, 0, "file ends after 'Data:' (no column names)");
  const long header_line = lines[k].number;
  std::vector<Column> columns;
  int wavelength = -1, reference = -1, target = -1, percent = -1, fraction = -1;
  for (const auto& cell : split_cells(lines[k].text, '\t')) {
    Column c{};
    if (!classify(cell.text, c)) {
      throw FileError(name, header_line, cell.column,
                      fmt::format("unknown column '{}' (known: Wvl, Chan.#, Norm. DN/DN/Rad./Irrad. (Ref.) and "
                                  "(Target), Reflect. %, Tgt./Ref. %, Reflect. [1.0])",
                                  instrument_text::printable(cell.text)));
    }
    const int index = static_cast<int>(columns.size());
    int* slot = c.role == Role::kWavelength            ? &wavelength
                : c.role == Role::kReference           ? &reference
                : c.role == Role::kTarget              ? &target
                : c.role == Role::kReflectancePercent  ? &percent
                : c.role == Role::kReflectanceFraction ? &fraction
                                                       : nullptr;
    if (slot) {
      if (*slot >= 0) throw FileError(name, header_line, cell.column, fmt::format("second '{}' column", cell.text));
      *slot = index;
    }
    columns.push_back(c);
  }
  if (wavelength < 0) throw FileError(name, header_line, 0, "no 'Wvl' column");
  if (target < 0 && percent < 0 && fraction < 0)
    throw FileError(name, header_line, 0, "no target or reflectance column");
  if (percent >= 0 && fraction >= 0) throw FileError(name, header_line, 0, "two reflectance columns");
  if (reference >= 0 && target >= 0 &&
      columns[static_cast<std::size_t>(reference)].quantity != columns[static_cast<std::size_t>(target)].quantity) {
    throw FileError(name, header_line, 0, "the reference and target columns hold different quantities");
  }
  const int signal = target >= 0 ? target : reference;
  if (signal >= 0) s.quantity = columns[static_cast<std::size_t>(signal)].quantity;
  const auto units = s.metadata.find("sed.units");
  if (s.quantity == "radiance" || s.quantity == "irradiance") {
    s.units = units != s.metadata.end() && units->second != "None" ? units->second : s.quantity + " (unit not stated)";
  } else if (!s.quantity.empty()) {
    s.units = s.quantity;
  }
  for (++k; k < lines.size(); ++k) {
    if (trim(lines[k].text).empty()) continue;
    const auto cells = split_cells(lines[k].text, '\t');
    if (cells.size() != columns.size()) {
      throw FileError(
          name, lines[k].number, cells.back().column,
          fmt::format("row has {} values, the column line {} names {}", cells.size(), header_line, columns.size()));
    }
    std::vector<double> v(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (!parse_finite_double(cells[c].text, v[c])) {
        throw FileError(name, lines[k].number, cells[c].column,
                        fmt::format("'{}' is not a finite number", instrument_text::printable(cells[c].text)));
      }
    }
    const double wl = v[static_cast<std::size_t>(wavelength)];
    if (!s.wavelengths.empty() && !(wl > s.wavelengths.back())) {
      throw FileError(name, lines[k].number, cells[static_cast<std::size_t>(wavelength)].column,
                      fmt::format("wavelength {} nm is not above the previous {} nm", wl, s.wavelengths.back()));
    }
    s.wavelengths.push_back(wl);
    if (target >= 0) s.target.push_back(v[static_cast<std::size_t>(target)]);
    if (reference >= 0) s.reference.push_back(v[static_cast<std::size_t>(reference)]);
    if (percent >= 0) s.reflectance.push_back(v[static_cast<std::size_t>(percent)] / 100.0);
    if (fraction >= 0) s.reflectance.push_back(v[static_cast<std::size_t>(fraction)]);
  }
  if (s.wavelengths.empty()) throw FileError(name, lines.back().number, 0, "no data rows after the column names");
  if (channels && s.wavelengths.size() != channels) {
    throw FileError(name, lines.back().number, 0,
                    fmt::format("{} data rows, but line {} says 'Channels: {}': truncated or corrupt file",
                                s.wavelengths.size(), channels_line, channels));
  }
  std::string ref_it, tgt_it, ref_avg, tgt_avg;
  if (auto it = s.metadata.find("sed.integration"); it != s.metadata.end()) halves(it->second, ref_it, tgt_it);
  if (auto it = s.metadata.find("sed.averages"); it != s.metadata.end()) halves(it->second, ref_avg, tgt_avg);
  if (!tgt_it.empty()) s.target_settings["integration times [ms]"] = tgt_it;
  if (!ref_it.empty()) s.reference_settings["integration times [ms]"] = ref_it;
  if (auto it = s.metadata.find("sed.instrument"); it != s.metadata.end()) s.metadata["instrument"] = it->second;
  return s;
}

}  // namespace roadbrdf
