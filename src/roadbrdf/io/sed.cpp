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

// The channel count a header may declare. Spectral Evolution instruments have 512 to 2151 channels
// (one per nm from 350 to 2500 nm at most); the bound leaves ample room and keeps the count exact.
constexpr std::size_t kMaxSedChannels = 1'000'000;

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

// The "Key: value" header up to the "Data:" line, into s.metadata as "sed.<key>". Returns the
// index of the "Data:" line; the channel count (0 when not stated) and its line come back in
// channels and channels_line.
std::size_t read_header(const std::vector<instrument_text::Line>& lines, const std::string& name, InstrumentSpectrum& s,
                        std::size_t& channels, long& channels_line) {
  std::size_t k = 0;
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
      // Compared as a double before the cast: converting a double beyond the integer's range is undefined.
      if (!parse_finite_double(value, c) || c < 1 || c != std::floor(c)) {
        throw FileError(name, lines[k].number, 0, fmt::format("'Channels: {}' is not a positive whole number", value));
      }
      if (c > static_cast<double>(kMaxSedChannels)) {
        throw FileError(name, lines[k].number, 0,
                        fmt::format("'Channels: {}' is more than the {} channels a spectrometer file may hold", value,
                                    kMaxSedChannels));
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
  return k;
}

// The column-name line: every column's meaning, and the index of each role's column (-1 if absent).
struct ColumnLayout {
  long line = 0;
  std::vector<Column> columns;
  int wavelength = -1, reference = -1, target = -1, percent = -1, fraction = -1;
};

ColumnLayout read_column_names(const instrument_text::Line& header, const std::string& name) {
  ColumnLayout l;
  l.line = header.number;
  // Tab-separated ([SpecDAL] sep='\t').
  for (const auto& cell : split_cells(header.text, '\t')) {
    Column c{};
    if (!classify(cell.text, c)) {
      throw FileError(name, l.line, cell.column,
                      fmt::format("unknown column '{}' (known: Wvl, Chan.#, Norm. DN/DN/Rad./Irrad. (Ref.) and "
                                  "(Target), Reflect. %, Tgt./Ref. %, Reflect. [1.0])",
                                  instrument_text::printable(cell.text)));
    }
    const int index = static_cast<int>(l.columns.size());
    int* slot = c.role == Role::kWavelength            ? &l.wavelength
                : c.role == Role::kReference           ? &l.reference
                : c.role == Role::kTarget              ? &l.target
                : c.role == Role::kReflectancePercent  ? &l.percent
                : c.role == Role::kReflectanceFraction ? &l.fraction
                                                       : nullptr;
    if (slot) {
      if (*slot >= 0) throw FileError(name, l.line, cell.column, fmt::format("second '{}' column", cell.text));
      *slot = index;
    }
    l.columns.push_back(c);
  }
  if (l.wavelength < 0) throw FileError(name, l.line, 0, "no 'Wvl' column");
  if (l.target < 0 && l.percent < 0 && l.fraction < 0)
    throw FileError(name, l.line, 0, "no target or reflectance column");
  if (l.percent >= 0 && l.fraction >= 0) throw FileError(name, l.line, 0, "two reflectance columns");
  if (l.reference >= 0 && l.target >= 0 &&
      l.columns[static_cast<std::size_t>(l.reference)].quantity !=
          l.columns[static_cast<std::size_t>(l.target)].quantity) {
    throw FileError(name, l.line, 0, "the reference and target columns hold different quantities");
  }
  return l;
}

// The measured quantity is that of the target column (else the reference); radiometric ones take
// their unit from the "Units:" header line.
void set_quantity(const ColumnLayout& l, InstrumentSpectrum& s) {
  const int signal = l.target >= 0 ? l.target : l.reference;
  if (signal >= 0) s.quantity = l.columns[static_cast<std::size_t>(signal)].quantity;
  const auto units = s.metadata.find("sed.units");
  if (s.quantity == "radiance" || s.quantity == "irradiance") {
    s.units = units != s.metadata.end() && units->second != "None" ? units->second : s.quantity + " (unit not stated)";
  } else if (!s.quantity.empty()) {
    s.units = s.quantity;
  }
}

// One data row: every cell a finite number, wavelengths strictly increasing.
void read_row(const instrument_text::Line& row, const ColumnLayout& l, const std::string& name, InstrumentSpectrum& s) {
  const auto cells = split_cells(row.text, '\t');
  if (cells.size() != l.columns.size()) {
    throw FileError(
        name, row.number, cells.back().column,
        fmt::format("row has {} values, the column line {} names {}", cells.size(), l.line, l.columns.size()));
  }
  std::vector<double> v(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (!parse_finite_double(cells[c].text, v[c])) {
      throw FileError(name, row.number, cells[c].column,
                      fmt::format("'{}' is not a finite number", instrument_text::printable(cells[c].text)));
    }
  }
  const double wl = v[static_cast<std::size_t>(l.wavelength)];
  if (!s.wavelengths.empty() && !(wl > s.wavelengths.back())) {
    throw FileError(name, row.number, cells[static_cast<std::size_t>(l.wavelength)].column,
                    fmt::format("wavelength {} nm is not above the previous {} nm", wl, s.wavelengths.back()));
  }
  s.wavelengths.push_back(wl);
  if (l.target >= 0) s.target.push_back(v[static_cast<std::size_t>(l.target)]);
  if (l.reference >= 0) s.reference.push_back(v[static_cast<std::size_t>(l.reference)]);
  if (l.percent >= 0) s.reflectance.push_back(v[static_cast<std::size_t>(l.percent)] / 100.0);
  if (l.fraction >= 0) s.reflectance.push_back(v[static_cast<std::size_t>(l.fraction)]);
}

// Scan settings from the header lists: integration times per scan, and the instrument name.
void set_scan_settings(InstrumentSpectrum& s) {
  std::string ref_it, tgt_it, ref_avg, tgt_avg;
  if (auto it = s.metadata.find("sed.integration"); it != s.metadata.end()) halves(it->second, ref_it, tgt_it);
  if (auto it = s.metadata.find("sed.averages"); it != s.metadata.end()) halves(it->second, ref_avg, tgt_avg);
  if (!tgt_it.empty()) s.target_settings["integration times [ms]"] = tgt_it;
  if (!ref_it.empty()) s.reference_settings["integration times [ms]"] = ref_it;
  if (auto it = s.metadata.find("sed.instrument"); it != s.metadata.end()) s.metadata["instrument"] = it->second;
}

}  // namespace

InstrumentSpectrum parse_sed(std::string_view text, const std::string& name) {
  const auto lines = instrument_text::lines(text);
  InstrumentSpectrum s;
  s.path = name;
  s.format = InstrumentFormat::kSed;
  long channels_line = 0;
  std::size_t channels = 0;
  std::size_t k = read_header(lines, name, s, channels, channels_line);
  ++k;
  while (k < lines.size() && trim(lines[k].text).empty()) ++k;
  if (k == lines.size()) throw FileError(name, lines.back().number, 0, "file ends after 'Data:' (no column names)");
  const ColumnLayout layout = read_column_names(lines[k], name);
  set_quantity(layout, s);
  for (++k; k < lines.size(); ++k) {
    if (!trim(lines[k].text).empty()) read_row(lines[k], layout, name, s);
  }
  if (s.wavelengths.empty()) throw FileError(name, lines.back().number, 0, "no data rows after the column names");
  if (channels && s.wavelengths.size() != channels) {
    throw FileError(name, lines.back().number, 0,
                    fmt::format("{} data rows, but line {} says 'Channels: {}': truncated or corrupt file",
                                s.wavelengths.size(), channels_line, channels));
  }
  set_scan_settings(s);
  return s;
}

}  // namespace roadbrdf
