// ASAM OpenMATERIAL 3D BRDF look-up tables (`*_brdf.xompt`, JSON; the schema
// material_brdf_schema.json of ASAM OpenMATERIAL 3D 1.0.0), the material files automotive sensor
// simulations (camera, LiDAR, radar) read:
//   {"metadata": {name, description, uuid, materialVersion, openMaterial3dVersion, copyrights[],
//                 license, authors[], creationDate "YYYYMMDDTHHMMSSZ", sources, typicalSensorTechnology},
//    "brdf": {"wavelengths": [m, ...],
//             "receiverSolidAngles": [{"wavelength": m, "solidAngle": sr}, ...]   (optional),
//             "lookupTable": [[wavelength m, incident zenith rad, exit zenith rad,
//                              exit azimuth rad relative to the incident azimuth, BRDF sr^-1], ...]}}
// The rows are sorted by their columns from the first; a BRDF of null is a value that is not given.
//
// Conventions. The schema sets the incident azimuth to 0 and gives the exit azimuth relative to it, in
// [0, 2 pi]. With the incident direction pointing towards the source (Nicodemus' convention, and this
// project's, core/geometry.h), the exit azimuth is phi_r - phi_i: 0 is the retro side, pi the forward
// (specular) side. (The one measured file published with the schema, DIVP's asphalt at 905 nm, is the
// same at 0 and pi, so it cannot tell the two readings apart.) Wavelengths [m] become nm (rounded to
// 1e-6 nm), angles stay angles (the dataset's geometries are in radians; files written from it show
// degrees).
//
// Reading (a dataset, io/dataset.h): one geometry per distinct (incident zenith, exit zenith, exit
// azimuth), one column per listed wavelength; a (geometry, wavelength) pair without a row, or with a
// null BRDF, is a missing value (NaN, or an error without allow_missing, as for a long CSV). The
// metadata block is kept in the dataset's metadata as "openmaterial3d.KEY" (lists joined by "; "), each
// receiver solid angle as "receiver_solid_angle_sr.NM". Errors are FileError with the JSON key path
// ("brdf.lookupTable[12][3]: ...").
//
// Writing: from a dataset and the metadata; rows sorted as the schema requires, numbers with round-trip
// precision, so that the reader reads back the same values. What the schema refuses is refused before
// anything is written: zenith angles above 1.570796 rad (the schema's maximum, just below 90 deg),
// negative BRDF values, a metadata field out of its pattern.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

// The schema's largest zenith angle [rad] (pi/2 rounded down to 6 decimals).
inline constexpr double kOpenMaterialMaxZenith = 1.570796;
inline constexpr std::string_view kOpenMaterialSchemaUrl =
    "https://raw.githubusercontent.com/asam-ev/OpenMATERIAL-3D/refs/tags/v1.0.0/schemas/material_brdf_schema.json";

// Whether a path names an OpenMATERIAL 3D BRDF file (it ends in ".xompt").
bool is_openmaterial3d_path(std::string_view path);

SpectralDataset read_openmaterial3d(const std::string& path, const DatasetReadOptions& options,
                                    DatasetReadStats& stats);

// The metadata block of a written file (the schema's names in comments).
struct OpenMaterialMetadata {
  std::string name;                                // name (required)
  std::string description;                         // description
  std::string uuid;                                // uuid, 8-4-4-4-12 hexadecimal (required)
  std::string material_version = "1.0.0";          // materialVersion, semantic version (required)
  std::string openmaterial_version = "1.0.0";      // openMaterial3dVersion (required)
  std::vector<std::string> copyrights;             // copyrights, at least one (required)
  std::string license;                             // license, an SPDX identifier or a URL (required)
  std::vector<std::string> authors;                // authors, at least one (required)
  std::string creation_date;                       // creationDate, YYYYMMDDTHHMMSSZ ("" = not written)
  std::string sources;                             // sources (required): "measurement", "simulation", ...
  std::string typical_sensor_technology;           // typicalSensorTechnology: "lidar", "camera", ...
  std::map<double, double> receiver_solid_angles;  // wavelength [nm] -> solid angle [sr]
};

// Throws FieldError naming the metadata field ("uuid", "creation_date", ...) for a value the schema
// refuses.
void validate_openmaterial_metadata(const OpenMaterialMetadata& metadata);

// Writes `dataset` (its wavelengths and geometries) atomically to `path` ("-" = standard output).
// Throws InputError (FieldError for the metadata) before writing anything.
void write_openmaterial3d(const SpectralDataset& dataset, const OpenMaterialMetadata& metadata,
                          const std::string& path);

// A new random (version 4) UUID, from the operating system's entropy.
std::string random_uuid();
// The current UTC time as YYYYMMDDTHHMMSSZ.
std::string utc_timestamp();

}  // namespace roadbrdf
