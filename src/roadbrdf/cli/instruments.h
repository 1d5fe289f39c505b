// Instrument files on the command line of convert: ASD .asd, Spectral Evolution .sed, SVC .sig and
// run manifests (io/instrument.h, io/manifest.h).
#pragma once

#include <CLI/CLI.hpp>
#include <span>
#include <string>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/instrument_options.h"

namespace roadbrdf::cli {

// The shared instrument-reading fields (io/instrument_options.h: overlap) and convert's own.
struct InstrumentArgs : InstrumentOptions {
  std::string geometry;          // "theta_i=..,phi_i=..,theta_r=..,phi_r=.." or "gamma=..,alpha=..,beta=..,delta=.."
  std::string quantity;          // "" = target (instrument files) or brdf (dataset CSV)
  std::string usgs_wavelengths;  // --from usgs: the splib07a wavelength file of the spectrum
};

// What `convert` reads (its --from). The instrument formats are named as InstrumentFormat names them
// (io/instrument.h), which the file read must then be.
enum class ConvertSource { kAuto, kWide, kLong, kCuret, kAlta, kAsd, kSed, kSig, kInstrument, kManifest, kUsgs };
inline constexpr EnumName<ConvertSource> kConvertSourceNames[] = {
    {ConvertSource::kAuto, "auto", "wide or long CSV, or an instrument file by its extension"},
    {ConvertSource::kWide, "wide", ""},
    {ConvertSource::kLong, "long", ""},
    {ConvertSource::kCuret, "curet", ""},
    {ConvertSource::kAlta, "alta", ""},
    {ConvertSource::kAsd, "asd", ""},
    {ConvertSource::kSed, "sed", ""},
    {ConvertSource::kSig, "sig", ""},
    {ConvertSource::kInstrument, "instrument", "any of the three, by its content"},
    {ConvertSource::kManifest, "manifest", "a run of instrument files: docs/data.md"},
    {ConvertSource::kUsgs, "usgs",
     "a USGS splib07a ASCII spectrum: needs --usgs-wavelengths and --geometry; stored as BRDF = R/pi"},
};
constexpr std::span<const EnumName<ConvertSource>> enum_names(ConvertSource) { return kConvertSourceNames; }
static_assert(entries_are_distinct(kConvertSourceNames));

// --geometry, --quantity, --usgs-wavelengths and the rows of InstrumentOptions::fields() (--overlap).
void add_instrument_flags(CLI::App* command, InstrumentArgs& args);

// True when `from` is an instrument format, a manifest or USGS, or is auto and the input has an
// instrument file extension (.asd, .sed, .sig).
bool is_instrument_input(ConvertSource from, const std::string& input);

// `convert` of an instrument file (one row at --geometry) or of a manifest (one row per sample).
// `inputs` and `outputs` are the command's own file arguments: the files a manifest lists are added
// to the inputs and checked against the outputs (check_distinct_files) before any file is read.
SpectralDataset convert_instrument_input(ConvertSource from, const std::string& input, const InstrumentArgs& args,
                                         const std::vector<FileArgument>& inputs,
                                         const std::vector<FileArgument>& outputs);

}  // namespace roadbrdf::cli
