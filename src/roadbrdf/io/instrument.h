// Spectroradiometer files read directly: ASD binary .asd (io/asd.h), Spectral Evolution .sed
// (io/sed.h) and Spectra Vista .sig (io/sig.h). Each reader returns one InstrumentSpectrum: the
// target signal, the reference-panel signal when the file carries one, and the reflectance the
// instrument software stored or implies, with the header values kept as metadata.
// No public specification exists for any of the three formats: docs/data.md ("Instrument files")
// says what is certain and what is inferred, and each reader cites its sources.
// A manifest (io/manifest.h) turns many such files into one dataset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

enum class InstrumentFormat { kAsd, kSed, kSig };
inline constexpr EnumName<InstrumentFormat> kInstrumentFormatNames[] = {
    {InstrumentFormat::kAsd, "asd", "ASD binary .asd, versions 6 to 8"},
    {InstrumentFormat::kSed, "sed", "Spectral Evolution .sed"},
    {InstrumentFormat::kSig, "sig", "Spectra Vista .sig"},
};
constexpr std::span<const EnumName<InstrumentFormat>> enum_names(InstrumentFormat) { return kInstrumentFormatNames; }

// What to do where the detectors of an SVC .sig file overlap (the wavelength goes back at a
// detector join, e.g. 1016.6 nm followed by 971.8 nm). Nothing is averaged.
enum class OverlapRule {
  kUpper,  // keep the next detector: drop the previous detector's channels at or above its first wavelength
  kLower,  // keep the previous detector: drop the next detector's channels at or below its last wavelength
  kError,  // refuse the file
};
inline constexpr EnumName<OverlapRule> kOverlapRuleNames[] = {
    {OverlapRule::kUpper, "upper", "keep the next detector's channels"},
    {OverlapRule::kLower, "lower", "keep the previous detector's"},
    {OverlapRule::kError, "error", "refuse the file"},
};
constexpr std::span<const EnumName<OverlapRule>> enum_names(OverlapRule) { return kOverlapRuleNames; }

struct InstrumentReadOptions {
  OverlapRule overlap = OverlapRule::kUpper;
  // Refuse a FIFO or a device (files a manifest lists are read as regular files only).
  bool regular_file_only = false;
};

// The largest instrument file read: the biggest of these formats holds two spectra of a few
// thousand channels and a header, well under a megabyte; a larger file (a sparse or corrupt one) is
// refused from its size, before it is read.
inline constexpr std::uintmax_t kInstrumentFileMaxBytes = std::uintmax_t{16} << 20;
// The longest line of a text instrument file (.sed, .sig): a header line or a row of a few numbers.
inline constexpr std::size_t kInstrumentLineMaxBytes = std::size_t{1} << 16;

struct InstrumentSpectrum {
  std::string path;
  InstrumentFormat format = InstrumentFormat::kAsd;
  std::vector<double> wavelengths;  // [nm], strictly increasing
  std::vector<double> target;       // target signal, as stored (see quantity/units)
  std::vector<double> reference;    // reference-panel signal stored with the target; empty when absent
  std::vector<double>
      reflectance;       // reflectance factor [1] (file's column / 100, or ASD target/reference); may be empty
  std::string quantity;  // of target and reference: "DN", "normalized DN", "radiance", "irradiance"
  std::string units;     // of target and reference, as far as known (e.g. "W/m^2/sr/nm", "DN")
  // Acquisition settings on which a raw signal depends (integration times, gains): a sample and the
  // white reference it is divided by must agree on these when the quantity is a raw "DN".
  std::map<std::string, std::string> target_settings;
  std::map<std::string, std::string> reference_settings;  // of the stored reference (may be empty: unknown)
  std::map<std::string, std::string> metadata;            // header values, keys prefixed by the format ("asd.", ...)
  std::vector<std::string> notes;                         // things worth a warning (overlap dropped, inconsistencies)

  // Keys: path, format, wavelengths, target, reference, reflectance (null when absent), quantity, units,
  // target_settings, reference_settings, metadata.
  nlohmann::json to_json() const;
};

// By the file's first bytes ("as6".."as8" -> ASD; "/*** Spectra Vista" -> SIG; a "Version:" ...
// "Data:" header -> SED), else by the extension. Throws FileError when neither tells.
InstrumentFormat detect_instrument_format(const std::string& path, std::string_view head);
// True when the path's extension is .asd, .sed or .sig (case-insensitive).
bool has_instrument_extension(const std::string& path);

// Read any of the three formats (detected as above). Throws FileError naming the file and the
// byte offset (binary) or line (text) of the problem.
InstrumentSpectrum read_instrument_file(const std::string& path, const InstrumentReadOptions& options = {});
// The same from bytes already in memory (`name` is used in errors); used by the fuzz harnesses.
InstrumentSpectrum read_instrument_bytes(std::string_view bytes, const std::string& name,
                                         const InstrumentReadOptions& options = {});

// Which signal of an instrument file becomes a dataset value.
enum class InstrumentQuantity { kTarget, kReference, kReflectance };
inline constexpr EnumName<InstrumentQuantity> kInstrumentQuantityNames[] = {
    {InstrumentQuantity::kTarget, "target", "the target signal"},
    {InstrumentQuantity::kReference, "reference", "the panel signal stored in the file"},
    {InstrumentQuantity::kReflectance, "reflectance", "the file's reflectance, or ASD target/reference"},
};
constexpr std::span<const EnumName<InstrumentQuantity>> enum_names(InstrumentQuantity) {
  return kInstrumentQuantityNames;
}

// The chosen signal of the file; throws InputError naming the file when it has none (e.g. a .sed
// file without a reflectance column asked for its reflectance).
const std::vector<double>& instrument_signal(const InstrumentSpectrum& spectrum, InstrumentQuantity quantity);
// Units of that signal, as written in a dataset's "# units:" line.
std::string instrument_signal_units(const InstrumentSpectrum& spectrum, InstrumentQuantity quantity);

// A one-geometry dataset holding the chosen signal of the file (metadata: the file's header
// values, "units", "signal", "instrument_file"). Throws InputError.
SpectralDataset instrument_dataset(const InstrumentSpectrum& spectrum, const Geometry& geometry,
                                   AngleConvention convention, InstrumentQuantity quantity);

}  // namespace roadbrdf
