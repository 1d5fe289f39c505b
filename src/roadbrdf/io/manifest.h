// Instrument manifest: one CSV file that maps each instrument file of a goniometric run to its
// geometry and role, so that the whole run becomes one dataset (`convert --from manifest`) or one
// calibrated BRDF dataset (`calibrate --manifest`):
//
//   # sample: asphalt AC10          <- "# key: value" lines become dataset metadata
//   file,role,gamma,alpha,beta,delta     (or theta_i,phi_i,theta_r,phi_r; degrees)
//   white_000.asd,white,,,,              <- no angles: this white reference serves every sample
//   dark_000.asd,dark,,,,
//   run_001.asd,sample,30,60,0,0
//   run_002.asd,sample,45,60,0,0
//
// - file: relative to the manifest's folder (or absolute); .asd, .sed or .sig (io/instrument.h).
// - role: sample, white (white reference panel) or dark. An optional `comment` column is ignored.
// - Sample rows need all four angles; two samples at the same geometry are an error.
// - White rows: none -> every sample is divided by the reference stored in its own file
//   ("embedded"; an error for a file without one); one row without angles -> used for every
//   sample; rows with angles -> matched to the samples by geometry (each sample needs one).
//   Dark rows follow the same rule (none -> no dark subtraction).
// - Every file must share the first sample's wavelengths and signal quantity; for raw counts
//   ("DN") a sample and its white reference must have the same integration times and gains.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/instrument.h"

namespace roadbrdf {

enum class ManifestRole { kSample, kWhite, kDark };

struct ManifestEntry {
  std::string file;  // as written
  std::string path;  // resolved against the manifest's folder
  ManifestRole role = ManifestRole::kSample;
  bool has_geometry = false;
  Geometry geometry;
  long line = 0;
};

struct Manifest {
  std::string path;
  AngleConvention convention = AngleConvention::kZenithAzimuth;
  std::vector<ManifestEntry> entries;
  std::map<std::string, std::string> metadata;  // "# key: value" lines
};

// Throws FileError (file:line:column) for a malformed manifest; the instrument files are not read.
// A manifest is a regular file of at most kManifestMaxBytes, lines of at most kManifestLineMaxBytes.
inline constexpr std::uintmax_t kManifestMaxBytes = std::uintmax_t{64} << 20;
inline constexpr std::size_t kManifestLineMaxBytes = std::size_t{1} << 16;
Manifest read_manifest(const std::string& path);

// Every file a manifest lists (each entry's resolved path, named by its role and line), for
// check_distinct_files: a command that reads a manifest reads all of them.
std::vector<FileArgument> manifest_input_files(const Manifest& manifest);

struct ManifestOptions {
  InstrumentReadOptions read;
  // Where warnings go (detector overlaps, dark rows for dark-corrected files). Default: the front
  // end's sink (core/diagnostics.h route_warning); the library never prints.
  std::function<void(const std::string&)> warn;
};

// One row per sample entry holding the chosen signal of its file (target, its stored reference,
// or its stored reflectance), in the file's units (metadata "units"). White and dark rows are
// not used. Throws InputError / FileError.
SpectralDataset manifest_dataset(const Manifest& manifest, InstrumentQuantity quantity,
                                 const ManifestOptions& options = {});

// The sample, reference and dark signals of the run for calibrate() (io/calibration.h); the panel
// spectra are left empty for the caller.
CalibrationInput manifest_calibration_input(const Manifest& manifest, const ManifestOptions& options = {});

// The calibrated BRDF of the run: manifest_calibration_input + calibrate(), with the run's
// description in the metadata. `panel_brf` as in CalibrationInput.
SpectralDataset calibrate_manifest(const Manifest& manifest, const spectra::Spectrum& panel_reflectance,
                                   const std::optional<spectra::Spectrum>& panel_brf = std::nullopt,
                                   const ManifestOptions& options = {});

}  // namespace roadbrdf
