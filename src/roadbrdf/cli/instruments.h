// Instrument files on the command line (convert, calibrate): ASD .asd, Spectral Evolution .sed,
// SVC .sig and run manifests (io/instrument.h, io/manifest.h).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "roadbrdf/io/dataset.h"

namespace roadbrdf::cli {

struct InstrumentArgs {
  std::string geometry;  // "theta_i=..,phi_i=..,theta_r=..,phi_r=.." or "gamma=..,alpha=..,beta=..,delta=.."
  std::string quantity = "target";
  std::string overlap = "upper";
  std::string usgs_wavelengths;  // --from usgs: the splib07a wavelength file of the spectrum
};

// --geometry and --quantity (convert only) and --overlap.
void add_instrument_flags(CLI::App* command, InstrumentArgs& args, bool convert);

// True when `from` names an instrument format, a manifest or "usgs", or is "auto" and the input has an
// instrument file extension (.asd, .sed, .sig).
bool is_instrument_input(const std::string& from, const std::string& input);

// `convert` of an instrument file (one row at --geometry) or of a manifest (one row per sample).
SpectralDataset convert_instrument_input(const std::string& from, const std::string& input, const InstrumentArgs& args);

// `calibrate --manifest`: the calibrated BRDF of the run.
SpectralDataset calibrate_manifest_from_command_line(const std::string& manifest, const std::string& panel,
                                                     const std::string& panel_brf, std::optional<double> brf_start,
                                                     std::optional<double> brf_step, const InstrumentArgs& args);

}  // namespace roadbrdf::cli
