// ASD binary reader. No specification is public; the field offsets below are taken from what
// public readers document, cited per field:
//   [SpecDAL]  EnSpec/SpecDAL, specdal/readers/asd.py (MIT): version at 0, data type at 186,
//              ch1 wavelength/step at 191/195, data format at 199, channels at 204, integration
//              time at 390, splices at 444/448, spectrum at 484, reference block after it.
//   [pyASD]    KaiTastic/pyASD, src/asd_file_reader.py and src/constant.py (MIT), which says it
//              follows "ASD File Format version 8: Revision B": the whole header as one packed
//              struct from offset 3, the reference header, classifier data, dependent variables,
//              calibration header and the code tables (data types, formats, instruments).
//   [PROV]     ../shared/real-data/instrument-files/PROVENANCE.md: offsets 0, 186, 191, 195, 199,
//              204, 390, 431, 484 and the reference block, checked on 15 real files.
//   [files]    inferred here from the 15 real files (where the readers are silent or disagree).
// Nothing was copied: every field is read by this file's own bounds-checked reader.
#include "roadbrdf/io/asd.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace {

// Bounds-checked little-endian reads; every failure names the byte offset and the field.
class Bytes {
 public:
  Bytes(std::string_view data, const std::string& name) : data_(data), name_(name) {}
  std::size_t size() const { return data_.size(); }

  [[noreturn]] void fail(std::size_t offset, const std::string& what) const {
    throw FileError(name_, 0, 0, fmt::format("byte {}: {}", offset, what));
  }
  void need(std::size_t offset, std::size_t count, const char* field) const {
    if (offset > data_.size() || data_.size() - offset < count) {
      fail(offset, fmt::format("file ends inside the {} ({} bytes needed, {} left): truncated ASD file", field, count,
                               offset > data_.size() ? 0 : data_.size() - offset));
    }
  }
  std::uint64_t uint(std::size_t offset, std::size_t count, const char* field) const {
    need(offset, count, field);
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < count; ++k)
      v |= std::uint64_t(static_cast<unsigned char>(data_[offset + k])) << (8 * k);
    return v;
  }
  std::uint8_t u8(std::size_t o, const char* f) const { return static_cast<std::uint8_t>(uint(o, 1, f)); }
  std::uint16_t u16(std::size_t o, const char* f) const { return static_cast<std::uint16_t>(uint(o, 2, f)); }
  std::int16_t i16(std::size_t o, const char* f) const { return static_cast<std::int16_t>(u16(o, f)); }
  std::uint32_t u32(std::size_t o, const char* f) const { return static_cast<std::uint32_t>(uint(o, 4, f)); }
  float f32(std::size_t o, const char* f) const {
    const std::uint32_t bits = u32(o, f);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  double f64(std::size_t o, const char* f) const {
    const std::uint64_t bits = uint(o, 8, f);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  std::string text(std::size_t offset, std::size_t count, const char* field) const {
    need(offset, count, field);
    std::string s(data_.substr(offset, count));
    s.resize(std::strlen(s.c_str()));  // NUL-padded fields
    return printable(s);
  }
  // A string with a 2-byte length in front ([pyASD] __parse_bstr: signed int16 length).
  std::string bstr(std::size_t& offset, const char* field) const {
    const std::int16_t length = i16(offset, field);
    if (length < 0) fail(offset, fmt::format("negative string length {} in the {}: corrupt ASD file", length, field));
    offset += 2;
    need(offset, static_cast<std::size_t>(length), field);
    std::string s(data_.substr(offset, static_cast<std::size_t>(length)));
    offset += static_cast<std::size_t>(length);
    return printable(s);
  }

 private:
  static std::string printable(std::string s) {
    for (char& c : s) {
      const auto u = static_cast<unsigned char>(c);
      if (u < 0x20 || u >= 0x7f) c = (c == '\t') ? ' ' : '?';
    }
    return s;
  }
  std::string_view data_;
  const std::string& name_;
};

// Data types, at byte 186 ([SpecDAL] ASD_DATA_TYPES order, [pyASD] DataType_e).
const char* data_type_name(unsigned type) {
  static const char* const names[] = {"raw",           "reflectance",   "radiance", "no units",  "irradiance",
                                      "quality index", "transmittance", "unknown",  "absorbance"};
  return type < std::size(names) ? names[type] : nullptr;
}

// Instrument types, at byte 431 ([pyASD] InstrumentType_e).
std::string instrument_type_name(unsigned type) {
  switch (type) {
    case 0:
      return "unknown";
    case 1:
      return "PSII";
    case 2:
      return "LabSpec VNIR";
    case 3:
      return "FieldSpec VNIR";
    case 4:
      return "FieldSpec full range";
    case 5:
      return "FieldSpec NIR";
    case 6:
      return "chemistry";
    case 7:
      return "LabSpec Pro";
    case 10:
      return "HandHeld";
    default:
      return "type " + std::to_string(type);
  }
}

// Calibration types in the calibration header ([pyASD] CalibrationType_e).
const char* calibration_type_name(unsigned type) {
  static const char* const names[] = {"absolute reflectance", "base (panel reflectance)", "lamp", "fiber optic"};
  return type < std::size(names) ? names[type] : "unknown";
}

// An OLE automation date (days since 1899-12-30, fraction = time of day) as ISO 8601 text.
std::string ole_date(double days) {
  if (!std::isfinite(days) || days <= 0.0 || days > 2958465.0) return "";  // 0 = not set; past 9999-12-31
  using namespace std::chrono;
  const double whole = std::floor(days);
  const auto seconds = static_cast<long>(std::lround((days - whole) * 86400.0));
  const year_month_day ymd{sys_days{year{1899} / December / 30} + std::chrono::days{static_cast<long>(whole)}};
  return fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}:{:02d}", static_cast<int>(ymd.year()),
                     static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()), seconds / 3600,
                     (seconds / 60) % 60, seconds % 60);
}

std::string version_byte(unsigned v) { return fmt::format("{}.{}", v >> 4, v & 0x0f); }  // [pyASD] __parseVersion

struct Grid {
  std::size_t channels = 0;
  unsigned format = 0;   // 0 float, 1 int32, 2 double ([pyASD] DataFormat_e)
  std::size_t size = 0;  // bytes per value
};

std::vector<double> read_values(const Bytes& b, std::size_t& offset, const Grid& g, const char* field) {
  b.need(offset, g.channels * g.size, field);
  std::vector<double> v(g.channels);
  for (std::size_t k = 0; k < g.channels; ++k) {
    const std::size_t o = offset + k * g.size;
    if (g.format == 0) {
      v[k] = b.f32(o, field);
    } else if (g.format == 1) {
      v[k] = static_cast<std::int32_t>(b.u32(o, field));
    } else {
      v[k] = b.f64(o, field);
    }
    if (!std::isfinite(v[k])) {
      b.fail(o, fmt::format("{} value {} is not a finite number: corrupt ASD file", field, k + 1));
    }
  }
  offset += g.channels * g.size;
  return v;
}

// Classifier data (v6+, [pyASD] __parse_classifierData): two bytes, twenty strings, a 2-byte
// constituent count; a non-empty list has a 10-byte array header before its items and an empty
// one 2 bytes after the count ([pyASD]; the 10-byte header is an array descriptor, [files]).
void read_classifier(const Bytes& b, std::size_t& o, InstrumentSpectrum& s) {
  static const char* const fields[] = {"title",         "subtitle",     "product_name", "vendor",    "lot_number",
                                       "sample",        "model_name",   "operator",     "date_time", "instrument",
                                       "serial_number", "display_mode", "comments",     "units",     "filename",
                                       "username",      "reserved1",    "reserved2",    "reserved3", "reserved4"};
  b.need(o, 2, "classifier data");
  o += 2;  // y code, y model type
  for (const char* f : fields) {
    const std::string v = b.bstr(o, "classifier data");
    if (!v.empty()) s.metadata[std::string("asd.classifier.") + f] = v;
  }
  const unsigned constituents = b.u16(o, "classifier constituent count");
  o += 2;
  if (constituents == 0) {
    b.need(o, 2, "classifier data");
    o += 2;
    return;
  }
  b.need(o, 10, "classifier constituent list");
  o += 10;
  std::string names;
  for (unsigned k = 0; k < constituents; ++k) {
    const std::string name = b.bstr(o, "classifier constituent");
    b.bstr(o, "classifier constituent");  // pass/fail
    // 9 doubles, a 4-byte model type, 2 doubles ([pyASD] __parse_constituantType)
    b.need(o, 9 * 8 + 4 + 2 * 8, "classifier constituent");
    o += 9 * 8 + 4 + 2 * 8;
    names += (names.empty() ? "" : "; ") + name;
  }
  s.metadata["asd.classifier.constituents"] = names;
}

// Dependent variables (v7+, [pyASD] __parse_dependentVariables; absent from the v6 files, [files]).
void read_dependents(const Bytes& b, std::size_t& o, InstrumentSpectrum& s) {
  b.need(o, 4, "dependent variables");
  const std::int16_t count = b.i16(o + 2, "dependent variable count");
  o += 4;
  if (count < 0) b.fail(o - 2, fmt::format("negative dependent variable count {}: corrupt ASD file", count));
  if (count == 0) {
    b.need(o, 4, "dependent variables");
    o += 4;
    return;
  }
  b.need(o, 10, "dependent variable labels");
  o += 10;
  std::vector<std::string> labels;
  labels.reserve(count > 0 ? static_cast<std::size_t>(count) : 0);
  for (int k = 0; k < count; ++k) labels.push_back(b.bstr(o, "dependent variable label"));
  b.need(o, 10, "dependent variable values");
  o += 10;
  std::string list;
  for (int k = 0; k < count; ++k) {
    list += fmt::format("{}{}={:g}", list.empty() ? "" : "; ", labels[static_cast<std::size_t>(k)],
                        b.f32(o, "dependent variable value"));
    o += 4;
  }
  s.metadata["asd.dependent_variables"] = list;
}

// Calibration header and spectra (v7+, [pyASD] __parse_calibrationHeader: a 1-byte count, then per
// entry type (1), name (20), integration time (int32 ms), SWIR1 and SWIR2 gains (int16); then one
// spectrum of doubles per entry, in header order).
void read_calibrations(const Bytes& b, std::size_t& o, const Grid& g, InstrumentSpectrum& s) {
  const unsigned count = b.u8(o, "calibration header");
  ++o;
  std::string list;
  for (unsigned k = 0; k < count; ++k) {
    b.need(o, 29, "calibration header");
    const unsigned type = b.u8(o, "calibration header");
    const std::string name = b.text(o + 1, 20, "calibration header");
    const std::uint32_t it = b.u32(o + 21, "calibration header");
    const unsigned g1 = b.u16(o + 25, "calibration header"), g2 = b.u16(o + 27, "calibration header");
    list += fmt::format("{}{} '{}' (integration {} ms, SWIR gains {}/{})", list.empty() ? "" : "; ",
                        calibration_type_name(type), name, it, g1, g2);
    o += 29;
  }
  const Grid doubles{g.channels, 2, 8};
  for (unsigned k = 0; k < count; ++k) read_values(b, o, doubles, "calibration spectrum");
  s.metadata["asd.calibrations"] = count ? list : "none";
}

}  // namespace

InstrumentSpectrum parse_asd(std::string_view data, const std::string& name) {
  const Bytes b(data, name);
  InstrumentSpectrum s;
  s.path = name;
  s.format = InstrumentFormat::kAsd;
  // Version string at byte 0 ([SpecDAL], [pyASD], [PROV]).
  const std::string version = b.text(0, 3, "version string");
  if (version != "as6" && version != "as7" && version != "as8") {
    b.fail(0, fmt::format("'{}' is not an ASD file version roadbrdf reads (as6, as7, as8)", version));
  }
  const int v = version[2] - '0';
  b.need(0, 484, "header");
  s.metadata["asd.version"] = version;
  if (auto c = b.text(3, 157, "comments"); !c.empty()) s.metadata["asd.comments"] = c;  // [pyASD] 157s at 3
  // Saved time at 160: nine int16 of a C struct tm ([pyASD] __parse_ASDFilewhen).
  s.metadata["asd.saved"] =
      fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}:{:02d}", 1900 + b.i16(170, "time"), b.i16(168, "time") + 1,
                  b.i16(166, "time"), b.i16(164, "time"), b.i16(162, "time"), b.i16(160, "time"));
  s.metadata["asd.program_version"] = version_byte(b.u8(178, "program version"));  // [pyASD] B at 178
  s.metadata["asd.file_version"] = version_byte(b.u8(179, "file version"));        // [pyASD] B at 179
  const bool dark_corrected = b.u8(181, "dark-corrected flag") != 0;               // [pyASD] b at 181
  s.metadata["asd.dark_corrected"] = dark_corrected ? "yes" : "no";
  const unsigned type = b.u8(186, "data type");  // [SpecDAL], [PROV]
  if (!data_type_name(type)) b.fail(186, fmt::format("unknown data type {} (0 to 8 are defined)", type));
  s.metadata["asd.data_type"] = data_type_name(type);
  const double first = b.f32(191, "first wavelength"), step = b.f32(195, "wavelength step");  // [SpecDAL]
  Grid g;
  g.format = b.u8(199, "data format");  // [SpecDAL], [pyASD] DataFormat_e
  if (g.format > 2) b.fail(199, fmt::format("data format {} is not float (0), integer (1) or double (2)", g.format));
  g.size = g.format == 2 ? 8 : 4;
  s.metadata["asd.data_format"] = g.format == 0 ? "float" : g.format == 1 ? "integer" : "double";
  g.channels = b.u16(204, "channel count");  // [SpecDAL] (read there as signed), [PROV]
  if (g.channels == 0) b.fail(204, "channel count is 0");
  if (!(std::isfinite(first) && first > 0.0 && std::isfinite(step) && step > 0.0)) {
    b.fail(191, fmt::format("wavelength grid {} nm + k x {} nm is not increasing and positive", first, step));
  }
  for (std::size_t k = 0; k < g.channels; ++k) s.wavelengths.push_back(first + static_cast<double>(k) * step);
  const std::uint32_t it = b.u32(390, "integration time");  // [SpecDAL], [pyASD], [PROV]
  s.metadata["asd.integration_time_ms"] = std::to_string(it);
  s.metadata["asd.fore_optic_deg"] = std::to_string(b.i16(394, "fore optic"));            // [pyASD] h at 394
  s.metadata["asd.instrument_number"] = std::to_string(b.u16(400, "instrument number"));  // [pyASD] H at 400
  // Flags at 421..424; the second is saturation/alarm bits ([pyASD] __parseSaturationError).
  const unsigned saturation = b.u8(422, "saturation flags");
  std::string saturated;
  const char* const bits[] = {"VNIR saturated", "SWIR1 saturated", "SWIR2 saturated", "SWIR1 TEC alarm",
                              "SWIR2 TEC alarm"};
  for (unsigned k = 0; k < 5; ++k) {
    if (saturation & (1u << k)) saturated += (saturated.empty() ? "" : ", ") + std::string(bits[k]);
  }
  s.metadata["asd.saturation"] = saturated.empty() ? "none" : saturated;
  if (!saturated.empty()) s.notes.push_back(name + ": the header flags " + saturated);
  s.metadata["asd.dark_current_count"] = std::to_string(b.u16(425, "dark count"));  // [pyASD] H H H at 425
  s.metadata["asd.reference_count"] = std::to_string(b.u16(427, "reference count"));
  s.metadata["asd.sample_count"] = std::to_string(b.u16(429, "sample count"));
  const unsigned instrument = b.u8(431, "instrument type");  // [pyASD] b at 431, [PROV]
  s.metadata["asd.instrument_type"] = fmt::format("{} ({})", instrument, instrument_type_name(instrument));
  const unsigned g1 = b.u16(436, "SWIR1 gain"), g2 = b.u16(438, "SWIR2 gain");  // [pyASD] H x 4 at 436
  const unsigned o1 = b.u16(440, "SWIR1 offset"), o2 = b.u16(442, "SWIR2 offset");
  s.metadata["asd.swir1_gain"] = std::to_string(g1);
  s.metadata["asd.swir2_gain"] = std::to_string(g2);
  s.metadata["asd.swir1_offset"] = std::to_string(o1);
  s.metadata["asd.swir2_offset"] = std::to_string(o2);
  s.metadata["asd.splice1_nm"] = fmt::format("{:g}", b.f32(444, "splice 1"));  // [SpecDAL], [pyASD]
  s.metadata["asd.splice2_nm"] = fmt::format("{:g}", b.f32(448, "splice 2"));
  s.metadata["instrument"] = fmt::format("ASD {} #{}", instrument_type_name(instrument), b.u16(400, "instrument"));
  s.target_settings = {{"integration time [ms]", std::to_string(it)},
                       {"SWIR1 gain", std::to_string(g1)},
                       {"SWIR2 gain", std::to_string(g2)},
                       {"SWIR1 offset", std::to_string(o1)},
                       {"SWIR2 offset", std::to_string(o2)}};
  // The raw counts, whatever the data type ([files]: 15 of 15 real files, raw, reflectance and
  // radiance types alike, hold counts of 10^2..10^4 here).
  s.quantity = "DN";
  s.units = "DN";
  std::size_t o = 484;  // [SpecDAL], [PROV]
  s.target = read_values(b, o, g, "spectrum");
  // Reference block ([SpecDAL] 18 bytes then the 2-byte description length; [pyASD]
  // __parse_referenceFileHeader: 2-byte boolean, reference and spectrum times as OLE dates).
  const std::uint16_t flag = b.u16(o, "reference flag");
  if (flag != 0 && flag != 0xffff) b.fail(o, fmt::format("reference flag 0x{:04x} is neither 0 nor 0xffff", flag));
  s.metadata["asd.reference_flag"] = flag ? "true" : "false";
  if (auto t = ole_date(b.f64(o + 2, "reference time")); !t.empty()) s.metadata["asd.reference_time"] = t;
  if (auto t = ole_date(b.f64(o + 10, "spectrum time")); !t.empty()) s.metadata["asd.spectrum_time"] = t;
  o += 18;
  if (auto d = b.bstr(o, "reference description"); !d.empty()) s.metadata["asd.reference_description"] = d;
  s.reference = read_values(b, o, g, "reference spectrum");
  if (v >= 6) read_classifier(b, o, s);
  if (v >= 7) {
    read_dependents(b, o, s);
    read_calibrations(b, o, g, s);
  }
  // Three bytes FF FE FD after the last block: an end marker ([pyASD] strips it before parsing).
  if (b.size() - o == 3 && b.u8(o, "end") == 0xff && b.u8(o + 1, "end") == 0xfe && b.u8(o + 2, "end") == 0xfd) {
    s.metadata["asd.end_marker"] = "FF FE FD";
  } else if (o < b.size()) {
    s.metadata["asd.unread_bytes"] = fmt::format("{} bytes from byte {} ({})", b.size() - o, o,
                                                 v >= 8 ? "audit log and signature" : "unknown content");
  }
  // Reflectance = spectrum / reference, as ASD's own readers form it for reflectance files
  // ([pyASD] reflectance; the PROVENANCE table lists this ratio).
  bool positive = true;
  for (double r : s.reference) positive = positive && r > 0.0;
  if (positive) {
    for (std::size_t k = 0; k < g.channels; ++k) s.reflectance.push_back(s.target[k] / s.reference[k]);
  } else {
    s.notes.push_back(name + ": the reference spectrum has channels <= 0: no reflectance formed");
    bool all_zero = true;
    for (double r : s.reference) all_zero = all_zero && r == 0.0;
    if (all_zero) s.reference.clear();  // no reference stored
  }
  return s;
}

}  // namespace roadbrdf
