// A model's BRDF on a grid, written for other tools (`roadbrdf export`, roadbrdf.export in Python),
// made by the request contract (core/request_fields.h): ASAM OpenMATERIAL 3D look-up tables
// (io/openmaterial3d.h) for automotive sensor simulation, the project's wide CSV (io/dataset_io.h), and
// ALTA's text format (io/alta.h) for one wavelength.
//
// The grid: every combination of the wavelengths [nm], incident zeniths theta_i [deg], exit zeniths
// theta_r [deg] and relative azimuths phi = phi_r - phi_i [deg] (0 retro side, 180 forward; at
// theta_r = 0, where the azimuth is undefined, only the first). The
// smooth part of the model is tabulated; an ideal specular (delta) part has no value on a grid and is
// left out, with a note. The presets choose the wavelengths of a sensor: camera 380-780 nm by 10 nm,
// LiDAR 905 and 1550 nm.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/modelfile/model_source.h"

namespace roadbrdf {

enum class ExportFormat { kOpenMaterial3d, kCsv, kAlta };
inline constexpr EnumName<ExportFormat> kExportFormatNames[] = {
    {ExportFormat::kOpenMaterial3d, "openmaterial3d", "ASAM OpenMATERIAL 3D BRDF look-up table (JSON, .xompt)"},
    {ExportFormat::kCsv, "csv", "roadbrdf wide CSV dataset (degrees, nm, sr^-1)"},
    {ExportFormat::kAlta, "alta", "ALTA text data, SPHERICAL_TL_PL_TV_PV in radians, one wavelength"},
};
constexpr std::span<const EnumName<ExportFormat>> enum_names(ExportFormat) { return kExportFormatNames; }

enum class SensorPreset { kNone, kCamera, kLidar };
inline constexpr EnumName<SensorPreset> kSensorPresetNames[] = {
    {SensorPreset::kNone, "none", "the wavelengths given, or the fit's own"},
    {SensorPreset::kCamera, "camera", "380-780 nm by 10 nm"},
    {SensorPreset::kLidar, "lidar", "905 and 1550 nm"},
};
constexpr std::span<const EnumName<SensorPreset>> enum_names(SensorPreset) { return kSensorPresetNames; }

// Largest grid written (geometries x wavelengths), a guard against a mistyped step.
inline constexpr std::size_t kMaxExportValues = 50'000'000;

struct ExportRequest {
  std::string source;  // FIT.json | MIX.json | MODEL
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::string fit;
  std::string format = "openmaterial3d";
  std::string preset = "none";
  std::vector<double> wavelengths;  // [nm]; empty: the preset's, or the fit's own
  std::vector<double> theta_i = default_zeniths();
  std::vector<double> theta_r = default_zeniths();
  std::vector<double> phi = default_azimuths();
  std::string output;
  // OpenMATERIAL 3D metadata.
  std::string name;         // "" = from the source's file name
  std::string description;  // "" = made from the source
  std::string uuid;         // "" = a new random one
  std::string material_version = "1.0.0";
  std::vector<std::string> authors;     // empty = "unknown"
  std::vector<std::string> copyrights;  // empty = "unknown"
  std::string license = "NOASSERTION";  // SPDX: no statement made
  std::string sensor;                   // typicalSensorTechnology; "" = from the preset

  static std::vector<double> default_zeniths();   // 0:89:1
  static std::vector<double> default_azimuths();  // 0:180:5
  static std::span<const RequestField<ExportRequest>> fields();
  // Throws FieldError.
  void validate() const;
  ExportFormat output_format() const;
  SensorPreset sensor_preset() const;
};

struct ExportResult {
  std::string output, format, model, sources;
  std::size_t geometries = 0;
  std::vector<double> wavelengths;  // [nm]
  nlohmann::json metadata;          // what the file says of itself (OpenMATERIAL 3D) or null
  Diagnostics diagnostics;

  nlohmann::json to_json() const;
  std::string summary_text() const;
};

// The model of the request's source on the request's grid, as a dataset (zenith-azimuth convention,
// phi_i = 0). Throws FieldError.
SpectralDataset export_grid(const ExportRequest& request, const SpectralModel& model, Diagnostics& diagnostics);

// Validates, resolves the source (modelfile/model_source.h resolve_model), tabulates and writes.
ExportResult export_model(const ExportRequest& request);

}  // namespace roadbrdf
