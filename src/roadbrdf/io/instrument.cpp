#include "roadbrdf/io/instrument.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/io/asd.h"
#include "roadbrdf/io/sed.h"
#include "roadbrdf/io/sig.h"

namespace roadbrdf {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

bool has_instrument_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".asd" || ext == ".sed" || ext == ".sig";
}

InstrumentFormat detect_instrument_format(const std::string& path, std::string_view head) {
  if (starts_with(head, "as6") || starts_with(head, "as7") || starts_with(head, "as8")) return InstrumentFormat::kAsd;
  if (starts_with(head, "/*** Spectra Vista")) return InstrumentFormat::kSig;
  const std::string ext = lower_extension(path);
  if (ext == ".asd") return InstrumentFormat::kAsd;  // the reader names the wrong version string
  if (ext == ".sig") return InstrumentFormat::kSig;
  if (ext == ".sed" || starts_with(head, "Comment:") || starts_with(head, "Version:")) return InstrumentFormat::kSed;
  throw FileError(path, 0, 0, "not a recognized instrument file (ASD .asd v6-v8, Spectral Evolution .sed, SVC .sig)");
}

InstrumentSpectrum read_instrument_bytes(std::string_view bytes, const std::string& name,
                                         const InstrumentReadOptions& options) {
  InstrumentSpectrum s;
  switch (detect_instrument_format(name, bytes.substr(0, 64))) {
    case InstrumentFormat::kAsd:
      s = parse_asd(bytes, name);
      break;
    case InstrumentFormat::kSed:
      s = parse_sed(bytes, name);
      break;
    case InstrumentFormat::kSig:
      s = parse_sig(bytes, name, options.overlap);
      break;
  }
  s.metadata["instrument_file_format"] = name_of(s.format);
  return s;
}

InstrumentSpectrum read_instrument_file(const std::string& path, const InstrumentReadOptions& options) {
  InputLimits limits;
  limits.what = "an instrument file (.asd, .sed, .sig)";
  limits.max_bytes = kInstrumentFileMaxBytes;
  limits.max_line_bytes = kInstrumentLineMaxBytes;
  limits.regular_file_only = options.regular_file_only;
  InputFile in(path, limits);  // "-" = standard input; a directory or a read error is a FileError
  const std::string bytes = in.read_all();
  if (bytes.empty()) throw FileError(in.name(), 0, 0, "file is empty");
  return read_instrument_bytes(bytes, in.name(), options);
}

const std::vector<double>& instrument_signal(const InstrumentSpectrum& s, InstrumentQuantity quantity) {
  const std::vector<double>& v = quantity == InstrumentQuantity::kTarget      ? s.target
                                 : quantity == InstrumentQuantity::kReference ? s.reference
                                                                              : s.reflectance;
  if (v.empty()) {
    throw InputError(
        fmt::format("{}: the file has no {} {}", s.path, name_of(quantity),
                    quantity == InstrumentQuantity::kReflectance ? "column (nor a reference to form it)" : "signal"));
  }
  return v;
}

std::string instrument_signal_units(const InstrumentSpectrum& s, InstrumentQuantity quantity) {
  if (quantity == InstrumentQuantity::kReflectance) return "1 (reflectance factor relative to the reference panel)";
  return s.quantity + (s.units.empty() || s.units == s.quantity ? "" : " [" + s.units + "]");
}

SpectralDataset instrument_dataset(const InstrumentSpectrum& s, const Geometry& geometry, AngleConvention convention,
                                   InstrumentQuantity quantity) {
  SpectralDataset d;
  const std::vector<double>& v = instrument_signal(s, quantity);
  d.geometries = {geometry};
  d.wavelengths = s.wavelengths;
  d.brdf = v;
  d.convention = convention;
  d.metadata = s.metadata;
  d.metadata["units"] = instrument_signal_units(s, quantity);
  d.metadata["signal"] = name_of(quantity);
  d.metadata["instrument_file"] = s.path;
  return d;
}

nlohmann::json InstrumentSpectrum::to_json() const {
  const auto signal = [](const std::vector<double>& v) { return v.empty() ? nlohmann::json() : nlohmann::json(v); };
  return {{"path", path},
          {"format", name_of(format)},
          {"wavelengths", wavelengths},
          {"target", signal(target)},
          {"reference", signal(reference)},
          {"reflectance", signal(reflectance)},
          {"quantity", quantity},
          {"units", units},
          {"target_settings", target_settings},
          {"reference_settings", reference_settings},
          {"metadata", metadata}};
}

}  // namespace roadbrdf
