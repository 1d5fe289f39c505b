// Writer of ASAM OpenMATERIAL 3D BRDF look-up tables (openmaterial3d.h), and the fresh uuid and
// creation date its metadata needs.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/io/openmaterial3d.h"

namespace roadbrdf {

namespace {

struct Row {
  double wavelength_m, theta_i, theta_r, phi, brdf;
};

// A JSON number with round-trip precision (the reader gets the same double back); null for NaN.
std::string number(double x) { return std::isnan(x) ? "null" : fmt::format("{}", x); }

void require(bool ok, const char* field, const std::string& detail) {
  if (!ok) throw FieldError(field, detail);
}

}  // namespace

void validate_openmaterial_metadata(const OpenMaterialMetadata& m) {
  static const std::regex uuid("^[0-9a-fA-F]{8}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{12}$");
  static const std::regex version("^[0-9]+\\.[0-9]+\\.[0-9]+$");
  static const std::regex date("^[0-9]{8}T[0-9]{6}Z$");
  require(!m.name.empty(), "name", "the material's name is required");
  require(std::regex_match(m.uuid, uuid), "uuid", "'" + m.uuid + "' is not an 8-4-4-4-12 hexadecimal uuid");
  require(std::regex_match(m.material_version, version), "material_version",
          "'" + m.material_version + "' is not a version MAJOR.MINOR.PATCH");
  require(std::regex_match(m.openmaterial_version, version), "openmaterial_version",
          "'" + m.openmaterial_version + "' is not a version MAJOR.MINOR.PATCH");
  require(!m.copyrights.empty(), "copyrights", "at least one copyright line is required");
  require(!m.license.empty(), "license", "a license (an SPDX identifier or a URL) is required");
  require(!m.authors.empty(), "authors", "at least one author is required");
  require(m.creation_date.empty() || std::regex_match(m.creation_date, date), "creation_date",
          "'" + m.creation_date + "' is not a UTC time YYYYMMDDTHHMMSSZ");
  require(!m.sources.empty(), "sources", "the sources of the data are required (e.g. measurement, simulation)");
  for (const auto& [nm, sr] : m.receiver_solid_angles) {
    require(std::isfinite(sr) && sr > 0.0, "receiver_solid_angles",
            fmt::format("the solid angle at {} nm must be positive [sr], got {}", nm, sr));
  }
}

void write_openmaterial3d(const SpectralDataset& d, const OpenMaterialMetadata& metadata, const std::string& path) {
  validate_openmaterial_metadata(metadata);
  validate_dataset(d);
  const std::size_t m = d.wavelength_count();
  for (const double nm : d.wavelengths) {
    if (!(nm * 1e-9 >= 1e-9 && nm * 1e-9 <= 17.16e-3)) {
      throw InputError(fmt::format("wavelength {} nm lies outside the schema's range (1 nm to 17.16 mm)", nm));
    }
  }
  std::vector<Row> rows;
  rows.reserve(d.geometry_count() * m);
  for (std::size_t n = 0; n < d.geometry_count(); ++n) {
    const Geometry& g = d.geometries[n];
    if (g.theta_i > kOpenMaterialMaxZenith || g.theta_r > kOpenMaterialMaxZenith) {
      throw InputError(
          fmt::format("geometry {} (theta_i {} deg, theta_r {} deg) lies beyond the schema's largest "
                      "zenith angle, 1.570796 rad (89.99997 deg)",
                      n, g.theta_i * 180.0 / std::numbers::pi, g.theta_r * 180.0 / std::numbers::pi));
    }
    double phi = std::fmod(g.phi_r - g.phi_i, 2.0 * std::numbers::pi);
    if (phi < 0.0) phi += 2.0 * std::numbers::pi;
    for (std::size_t j = 0; j < m; ++j) {
      const double f = d.value(n, j);
      if (f < 0.0) {
        throw InputError(fmt::format("BRDF {} sr^-1 at geometry {}, {} nm is negative: the schema's minimum is 0", f, n,
                                     d.wavelengths[j]));
      }
      rows.push_back({d.wavelengths[j] / 1e9, g.theta_i, g.theta_r, phi, f});
    }
  }
  // Sorted by the columns from the first (the schema's rule); NaN never occurs in the four keys.
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return std::tie(a.wavelength_m, a.theta_i, a.theta_r, a.phi) <
           std::tie(b.wavelength_m, b.theta_i, b.theta_r, b.phi);
  });
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const Row& a = rows[k - 1];
    const Row& b = rows[k];
    if (std::tie(a.wavelength_m, a.theta_i, a.theta_r, a.phi) ==
        std::tie(b.wavelength_m, b.theta_i, b.theta_r, b.phi)) {
      throw InputError("two geometries of the dataset are the same relative to the incident azimuth");
    }
  }

  nlohmann::ordered_json meta;
  meta["name"] = metadata.name;
  if (!metadata.description.empty()) meta["description"] = metadata.description;
  meta["uuid"] = metadata.uuid;
  meta["materialVersion"] = metadata.material_version;
  if (!metadata.creation_date.empty()) meta["creationDate"] = metadata.creation_date;
  meta["openMaterial3dVersion"] = metadata.openmaterial_version;
  meta["copyrights"] = metadata.copyrights;
  meta["license"] = metadata.license;
  meta["authors"] = metadata.authors;
  meta["sources"] = metadata.sources;
  if (!metadata.typical_sensor_technology.empty()) meta["typicalSensorTechnology"] = metadata.typical_sensor_technology;

  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "{\n  \"$schema\": \"" << kOpenMaterialSchemaUrl << "\",\n  \"metadata\": " << dump_json(meta)
      << ",\n  \"brdf\": {\n    \"wavelengths\": [";
  for (std::size_t j = 0; j < m; ++j) out << (j ? ", " : "") << number(d.wavelengths[j] / 1e9);
  out << "],\n";
  if (!metadata.receiver_solid_angles.empty()) {
    out << "    \"receiverSolidAngles\": [";
    bool first = true;
    for (const auto& [nm, sr] : metadata.receiver_solid_angles) {
      out << (first ? "" : ", ") << "{\"wavelength\": " << number(nm / 1e9) << ", \"solidAngle\": " << number(sr)
          << "}";
      first = false;
    }
    out << "],\n";
  }
  out << "    \"lookupTable\": [\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    out << "      [" << number(r.wavelength_m) << ", " << number(r.theta_i) << ", " << number(r.theta_r) << ", "
        << number(r.phi) << ", " << number(r.brdf) << (k + 1 < rows.size() ? "],\n" : "]\n");
  }
  out << "    ]\n  }\n}\n";
  file.commit();
}

std::string random_uuid() {
  // 16 bytes from the kernel's entropy pool, then the version (4) and variant (10xx) bits of RFC 4122
  // section 4.4.
  std::array<unsigned char, 16> bytes{};
  std::ifstream urandom("/dev/urandom", std::ios::binary);
  if (!urandom.read(reinterpret_cast<char*>(bytes.data()), bytes.size())) {
    throw InputError("cannot read /dev/urandom for a new uuid");
  }
  bytes[6] = static_cast<unsigned char>((bytes[6] & 0x0F) | 0x40);
  bytes[8] = static_cast<unsigned char>((bytes[8] & 0x3F) | 0x80);
  std::string s;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    if (k == 4 || k == 6 || k == 8 || k == 10) s += '-';
    s += fmt::format("{:02x}", bytes[k]);
  }
  return s;
}

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  return fmt::format("{:04d}{:02d}{:02d}T{:02d}{:02d}{:02d}Z", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                     utc.tm_hour, utc.tm_min, utc.tm_sec);
}

}  // namespace roadbrdf
