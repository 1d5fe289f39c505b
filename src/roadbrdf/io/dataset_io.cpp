#include "roadbrdf/io/dataset_io.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <ostream>
#include <unordered_map>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

namespace {

std::string fmt_value(double v) {
  if (std::isnan(v)) return "nan";
  return fmt::format("{}", v);
}

std::string fmt_angle(double v) {
  const double r = std::round(v * 1e9) / 1e9 + 0.0;
  return fmt::format("{}", r);
}

}  // namespace

bool is_metadata_key(std::string_view key) {
  if (key.empty()) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

bool is_metadata_comment(std::string_view comment) {
  const auto colon = comment.find(':');
  if (colon == std::string_view::npos) return false;
  std::string_view key = comment.substr(0, colon);
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t')) key.remove_prefix(1);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.remove_suffix(1);
  return is_metadata_key(key);
}

void angle_values_of_geometry(const Geometry& g, AngleConvention convention, double out[4]) {
  if (convention == AngleConvention::kRoad) {
    const RoadAngles a = road_angles_from_geometry(g);
    out[0] = a.gamma;
    out[1] = a.alpha;
    out[2] = a.beta;
    out[3] = a.delta;
  } else {
    out[0] = rad_to_deg(g.theta_i);
    out[1] = rad_to_deg(g.phi_i);
    out[2] = rad_to_deg(g.theta_r);
    out[3] = rad_to_deg(g.phi_r);
  }
}

void validate_read_options(const DatasetReadOptions& o) {
  if (o.delimiter != 0 && o.delimiter != ',' && o.delimiter != ';' && o.delimiter != '\t') {
    throw InputError("the dataset delimiter must be ',', ';' or a tab (or detected)");
  }
  if (o.decimal != 0 && o.decimal != '.' && o.decimal != ',') {
    throw InputError("the decimal separator must be '.' or ',' (or detected)");
  }
  if (o.delimiter == ',' && o.decimal == ',') {
    throw InputError("a decimal comma needs another delimiter: pass `delimiter` ';' (or tab) with `decimal` ','");
  }
  validate_mapping_options(o);
}

void validate_dataset(const SpectralDataset& d) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  if (n == 0 || m == 0) throw InputError("dataset has no geometries or no wavelengths");
  if (d.brdf.size() != n * m) {
    throw InputError(
        fmt::format("dataset holds {} BRDF values for {} geometries x {} wavelengths", d.brdf.size(), n, m));
  }
  if (!d.sigma.empty() && d.sigma.size() != n * m) {
    throw InputError(
        fmt::format("dataset holds {} uncertainties for {} geometries x {} wavelengths", d.sigma.size(), n, m));
  }
  for (std::size_t j = 0; j < m; ++j) {
    if (!(std::isfinite(d.wavelengths[j]) && d.wavelengths[j] > 0.0)) {
      throw InputError(fmt::format("dataset wavelengths[{}] = {} nm: must be finite and > 0", j, d.wavelengths[j]));
    }
  }
  for (std::size_t g = 0; g < n; ++g) {
    const Geometry& x = d.geometries[g];
    if (!(std::isfinite(x.theta_i) && std::isfinite(x.phi_i) && std::isfinite(x.theta_r) && std::isfinite(x.phi_r))) {
      throw InputError(fmt::format("dataset geometry (row) {}: the angles are not finite", g));
    }
  }
  // NaN is a measurement that was not made; an infinite value is no measurement at all.
  for (std::size_t k = 0; k < n * m; ++k) {
    if (std::isinf(d.brdf[k])) {
      throw InputError(
          fmt::format("dataset BRDF is infinite at geometry (row) {}, {} nm", k / m, d.wavelengths[k % m]));
    }
    if (d.has_sigma() && (std::isinf(d.sigma[k]) || d.sigma[k] < 0.0)) {
      throw InputError(fmt::format("dataset sigma is {} at geometry (row) {}, {} nm: must be finite and >= 0",
                                   d.sigma[k], k / m, d.wavelengths[k % m]));
    }
  }
  for (std::size_t j = 1; j < m; ++j) {
    if (!(d.wavelengths[j] > d.wavelengths[j - 1])) {
      throw InputError(fmt::format("dataset wavelengths are not strictly increasing ({} nm then {} nm)",
                                   d.wavelengths[j - 1], d.wavelengths[j]));
    }
  }
}

void validate_dataset_for_writing(const SpectralDataset& d) {
  validate_dataset(d);
  for (const auto& [key, value] : d.metadata) {
    if (!is_metadata_key(key)) {
      throw InputError(
          fmt::format("metadata key '{}': use letters, digits, '_', '-' and '.' only (it would not "
                      "read back)",
                      key));
    }
    if (value.find_first_of("\r\n") != std::string::npos) {
      throw InputError(fmt::format("metadata '{}': the value must be one line", key));
    }
  }
  for (const std::string& comment : d.comments) {
    if (comment.find_first_of("\r\n") != std::string::npos) {
      throw InputError(fmt::format("dataset comment '{}' must be one line", comment));
    }
    if (is_metadata_comment(comment)) {
      throw InputError(
          fmt::format("dataset comment '{}' would read back as metadata: put it in the metadata", comment));
    }
  }
}

void write_dataset(const SpectralDataset& d, std::ostream& out, DatasetFormat format) {
  validate_dataset_for_writing(d);
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  out << "# " << kDatasetBanner << " (" << (format == DatasetFormat::kWide ? "wide" : "long")
      << " CSV); angles in degrees, wavelengths in nm, BRDF and sigma in sr^-1\n";
  if (!d.metadata.count("units")) out << "# units: sr^-1\n";
  for (const std::string& comment : d.comments) out << "# " << comment << '\n';
  for (const auto& [key, value] : d.metadata) out << "# " << key << ": " << value << '\n';
  const bool road = d.convention == AngleConvention::kRoad;
  const char* angle_header = road ? "gamma,alpha,beta,delta" : "theta_i,phi_i,theta_r,phi_r";
  std::string line;
  if (format == DatasetFormat::kWide) {
    line = angle_header;
    for (double wl : d.wavelengths) line += fmt::format(",{}", fmt_value(wl));
    if (d.has_sigma()) {
      for (double wl : d.wavelengths) line += fmt::format(",sigma_{}", fmt_value(wl));
    }
    out << line << '\n';
    for (std::size_t g = 0; g < n; ++g) {
      double a[4];
      angle_values_of_geometry(d.geometries[g], d.convention, a);
      line.clear();
      for (int k = 0; k < 4; ++k) {
        if (k) line += ',';
        line += fmt_angle(a[k]);
      }
      for (std::size_t j = 0; j < m; ++j) {
        line += ',';
        line += fmt_value(d.brdf[g * m + j]);
      }
      if (d.has_sigma()) {
        for (std::size_t j = 0; j < m; ++j) {
          line += ',';
          line += fmt_value(d.sigma[g * m + j]);
        }
      }
      out << line << '\n';
    }
  } else {
    out << angle_header << ",wavelength,brdf" << (d.has_sigma() ? ",sigma" : "") << '\n';
    for (std::size_t g = 0; g < n; ++g) {
      double a[4];
      angle_values_of_geometry(d.geometries[g], d.convention, a);
      std::string prefix;
      for (int k = 0; k < 4; ++k) prefix += fmt::format("{},", fmt_angle(a[k]));
      for (std::size_t j = 0; j < m; ++j) {
        line = fmt::format("{}{},{}", prefix, fmt_value(d.wavelengths[j]), fmt_value(d.brdf[g * m + j]));
        if (d.has_sigma()) line += fmt::format(",{}", fmt_value(d.sigma[g * m + j]));
        out << line << '\n';
      }
    }
  }
}

void write_dataset(const SpectralDataset& d, const std::string& path, DatasetFormat format) {
  AtomicFile file(path);
  write_dataset(d, file.stream(), format);
  file.commit();
}

void write_dataset_output(const SpectralDataset& dataset, const std::string& output, const std::string& format,
                          const std::string& format_field) {
  if (!output.empty()) write_dataset(dataset, output, parse_name<DatasetFormat>(format, format_field));
}

std::size_t missing_value_count(const SpectralDataset& d) {
  return static_cast<std::size_t>(std::count_if(d.brdf.begin(), d.brdf.end(), [](double v) { return std::isnan(v); }));
}

}  // namespace roadbrdf
