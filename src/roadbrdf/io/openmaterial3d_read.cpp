// Reader of ASAM OpenMATERIAL 3D BRDF look-up tables (openmaterial3d.h).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/io/openmaterial3d.h"

namespace roadbrdf {

namespace {

// The schema's wavelength range [m] (from 1 nm up to the 20 kHz of its upper limit).
constexpr double kMinWavelengthM = 1e-9;
constexpr double kMaxWavelengthM = 17.16e-3;

double nanometres(double metres) { return std::round(metres * 1e15) / 1e6; }

std::string metadata_text(const JsonNode& value) {
  if (value.is_string()) return value.string();
  if (value.is_number()) return fmt::format("{}", value.number());
  if (value.is_array()) {
    std::string joined;
    for (const std::string& s : value.strings()) joined += (joined.empty() ? "" : "; ") + s;
    return joined;
  }
  value.fail("expected a string or a list of strings");
}

double wavelength_of(const JsonNode& node) {
  const double m = node.number();
  if (!(m >= kMinWavelengthM && m <= kMaxWavelengthM)) {
    node.fail(fmt::format("wavelength {} m lies outside the schema's range [1e-9, 17.16e-3] m", m));
  }
  return m;
}

// Angles are stored in radians, rounded to a few decimals in practice: 90 deg is written 1.570796
// (the ASAM example asphalt, i.e. 89.99997 deg, whose cosine 3.3e-7 no grazing rule would take for 0)
// or 1.5707964 (just above pi/2). A value within half a unit of the sixth decimal of the upper end
// (pi/2 for a zenith, 2 pi for the azimuth) is that end, read exactly, so that the grazing rules of
// core/geometry.h apply; `rounded` counts them for the reader's warning.
constexpr double kRadianRounding = 5e-7;

double angle_of(const JsonNode& node, double max, const char* what, std::size_t& rounded) {
  if (node.is_null()) node.fail(std::string(what) + " is null");
  const double a = node.number();
  if (a != max && std::abs(a - max) <= kRadianRounding) {
    ++rounded;
    return max;
  }
  if (!(a >= 0.0 && a <= max)) node.fail(fmt::format("{} {} rad lies outside [0, {}] rad", what, a, max));
  return a;
}

}  // namespace

bool is_openmaterial3d_path(std::string_view path) {
  constexpr std::string_view ext = ".xompt";
  return path.size() > ext.size() && path.substr(path.size() - ext.size()) == ext;
}

SpectralDataset read_openmaterial3d(const std::string& path, const DatasetReadOptions& options,
                                    DatasetReadStats& stats) {
  const Json document = parse_json_file(path);
  const JsonNode root(document, path);
  if (!root.is_object()) root.fail("expected an object with \"metadata\" and \"brdf\"");
  SpectralDataset d;
  d.convention = AngleConvention::kZenithAzimuth;
  d.metadata["source_format"] = "openmaterial3d";
  if (const auto metadata = root.find("metadata")) {
    for (const auto& [key, value] : metadata->members()) d.metadata["openmaterial3d." + key] = metadata_text(value);
  } else {
    root.fail("\"metadata\" is missing (the schema requires it)");
  }
  const JsonNode brdf = root.at("brdf");
  brdf.check_keys({"wavelengths", "receiverSolidAngles", "lookupTable"});

  // The listed wavelengths, in metres as written (rows name them exactly), and their order.
  const JsonNode listed = brdf.at("wavelengths");
  std::map<double, std::size_t> column_of;
  for (std::size_t k = 0; k < listed.size(); ++k) {
    const double m = wavelength_of(listed[k]);
    if (!column_of.emplace(m, 0).second) listed[k].fail(fmt::format("wavelength {} m is listed twice", m));
  }
  if (column_of.empty()) listed.fail("no wavelength is listed");
  for (auto& [m, column] : column_of) {
    column = d.wavelengths.size();
    const double nm = nanometres(m);
    if (!d.wavelengths.empty() && nm <= d.wavelengths.back()) {
      listed.fail(fmt::format("wavelengths {} nm and {} nm are the same to 1e-6 nm", d.wavelengths.back(), nm));
    }
    d.wavelengths.push_back(nm);
  }
  if (const auto solid = brdf.find("receiverSolidAngles")) {
    for (const JsonNode& item : solid->elements()) {
      item.check_keys({"wavelength", "solidAngle"});
      const double m = wavelength_of(item.at("wavelength"));
      const JsonNode omega = item.at("solidAngle");
      if (!(omega.number() > 0.0)) omega.fail("the receiver solid angle must be positive [sr]");
      const std::string key = fmt::format("receiver_solid_angle_sr.{}", nanometres(m));
      if (d.metadata.count(key)) item.fail(fmt::format("a second solid angle for {} m", m));
      d.metadata[key] = fmt::format("{}", omega.number());
    }
  }

  // Rows: geometry key (incident zenith, exit zenith, exit azimuth) -> index, values by column.
  const JsonNode table = brdf.at("lookupTable");
  const std::size_t m = d.wavelengths.size();
  std::map<std::tuple<double, double, double>, std::size_t> geometry_of;
  std::vector<double> values, counts;
  std::size_t rounded_angles = 0;
  for (std::size_t r = 0; r < table.size(); ++r) {
    const JsonNode row = table[r];
    if (row.size() != 5) row.fail(fmt::format("a row holds 5 numbers, this one {}", row.size()));
    if (row[0].is_null()) row[0].fail("the wavelength is null");
    const double wl = wavelength_of(row[0]);
    const auto column = column_of.find(wl);
    if (column == column_of.end()) row[0].fail(fmt::format("wavelength {} m is not in \"brdf.wavelengths\"", wl));
    const double ti = angle_of(row[1], std::numbers::pi / 2, "the incident zenith", rounded_angles);
    const double tr = angle_of(row[2], std::numbers::pi / 2, "the exit zenith", rounded_angles);
    const double phi = angle_of(row[3], 2.0 * std::numbers::pi, "the exit azimuth", rounded_angles);
    const auto [it, added] = geometry_of.emplace(std::make_tuple(ti, tr, phi), d.geometries.size());
    if (added) {
      d.geometries.push_back(geometry_from_radians(ti, 0.0, tr, phi));
      values.resize(values.size() + m, 0.0);
      counts.resize(counts.size() + m, 0.0);
    }
    const std::size_t cell = it->second * m + column->second;
    double f = std::numeric_limits<double>::quiet_NaN();
    if (row[4].is_null()) {
      if (!options.allow_missing) row[4].fail("the BRDF is null (a value that was not measured)");
    } else {
      f = row[4].number();
      if (f < 0.0) ++stats.negative_values;
      if (f > 1e3) ++stats.implausible_values;
    }
    if (counts[cell] > 0.0 && !options.average_duplicates) {
      row.fail(
          "this wavelength and geometry were given by an earlier row too (average them with "
          "`average_duplicates`)");
    }
    if (counts[cell] > 0.0) ++stats.averaged_duplicate_rows;
    values[cell] += f;  // NaN stays NaN: a missing duplicate makes the average missing
    counts[cell] += 1.0;
  }
  if (d.geometries.empty()) table.fail("the look-up table has no row");
  d.brdf.resize(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (counts[k] == 0.0) {
      if (!options.allow_missing) {
        table.fail(fmt::format("no row for wavelength {} nm at geometry {}", d.wavelengths[k % m], k / m));
      }
      ++stats.absent_rows;
      d.brdf[k] = std::numeric_limits<double>::quiet_NaN();
    } else {
      d.brdf[k] = values[k] / counts[k];
    }
  }
  stats.missing_values = missing_value_count(d);
  if (stats.averaged_duplicate_rows > 0) {
    d.metadata["averaged_duplicate_rows"] = std::to_string(stats.averaged_duplicate_rows);
  }
  const auto warn = [&options](const std::string& message) {
    if (options.warn) {
      options.warn(message);
    } else {
      route_warning(message);  // the front end's sink (core/diagnostics.h), as the CSV readers do
    }
  };
  if (stats.negative_values > 0) {
    warn(fmt::format("{}: {} negative BRDF values kept as they are (the schema's minimum is 0)", path,
                     stats.negative_values));
  }
  if (stats.missing_values > 0) {
    warn(fmt::format("{}: {} (geometry, wavelength) values are not given (no row or null): kept as missing", path,
                     stats.missing_values));
  }
  if (stats.averaged_duplicate_rows > 0) {
    warn(fmt::format("{}: {} repeated rows averaged", path, stats.averaged_duplicate_rows));
  }
  if (rounded_angles > 0) {
    d.metadata["rounded_radian_angles"] = std::to_string(rounded_angles);
    warn(
        fmt::format("{}: {} angles within {:g} rad of 90 deg (or of 360 deg for the azimuth) read as exactly that "
                    "angle: radians rounded to six decimals (1.570796 is 89.99997 deg)",
                    path, rounded_angles, kRadianRounding));
  }
  validate_dataset(d);
  return d;
}

}  // namespace roadbrdf
