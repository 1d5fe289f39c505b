#include "roadbrdf/io/alta.h"

#include <fmt/core.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {

namespace {

enum class AltaInput { kUnknown, kTlTvProjDphi, kSphericalTlPlTvPv };
enum class AltaOutput { kUnknown, kInvSteradian, kInvSteradianCosine };

AltaOutput parse_output(const std::string& name) {
  if (name == "INV_STERADIAN") return AltaOutput::kInvSteradian;
  if (name == "INV_STERADIAN_COSINE_FACTOR") return AltaOutput::kInvSteradianCosine;
  return AltaOutput::kUnknown;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\"");
  return s.substr(b, e - b + 1);
}

// A #DIM count: a whole number 1..16 (no trailing text such as "1junk").
int dimension(const std::string& path, long line, long offset, const CsvCell& cell) {
  int v = 0;
  const auto [ptr, ec] = std::from_chars(cell.text.data(), cell.text.data() + cell.text.size(), v);
  if (cell.text.empty() || ec != std::errc() || ptr != cell.text.data() + cell.text.size() || v < 1 || v > 16) {
    throw FileError(path, line, offset + cell.column,
                    fmt::format("#DIM count '{}' is not a whole number in 1..16", cell.text));
  }
  return v;
}

}  // namespace

SpectralDataset read_alta(const std::string& path, const AltaReadOptions& options) {
  if (!(options.wavelength_nm > 0.0)) {
    throw InputError(path + ": ALTA files carry no wavelength: give the wavelength [nm] of the measurement");
  }
  InputFile in(path);
  SpectralDataset d;
  AltaInput input = AltaInput::kUnknown;
  AltaOutput output = AltaOutput::kUnknown;
  int dim_in = -1, dim_out = -1;
  bool header_done = false;
  std::string line;
  long n = 0;
  std::size_t negative = 0, grazing = 0;
  std::string first_negative, first_grazing;
  std::map<std::array<long long, 4>, std::pair<std::size_t, long>> seen;
  std::vector<int> multiplicity;
  auto warn = [&](const std::string& m) {
    if (options.warn) {
      options.warn(m);
    } else {
      fmt::print(stderr, "roadbrdf: warning: {}\n", m);
    }
  };
  while (in.read_line(line)) {
    ++n;
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    if (line[b] == '#') {
      const auto cells = split_whitespace(std::string_view(line).substr(b + 1));
      if (cells.empty()) continue;
      const std::string key(cells[0].text);
      // Cell columns are 1-based within the text after '#' (spaces after '#' are allowed).
      const std::size_t key_start = b + static_cast<std::size_t>(cells[0].column);
      const std::string rest = trim(line.substr(key_start + cells[0].text.size()));
      const long col = static_cast<long>(key_start) + 1;
      const bool header_key = key == "DIM" || key == "PARAM_IN" || key == "PARAM_OUT" || key == "VS";
      if (header_key && header_done) {
        throw FileError(path, n, col,
                        fmt::format("#{} after the data: the header must come before the first data line", key));
      }
      if (key == "DIM") {
        if (cells.size() != 3) throw FileError(path, n, col, "#DIM expects two numbers (inputs, outputs)");
        dim_in = dimension(path, n, static_cast<long>(b + 1), cells[1]);
        dim_out = dimension(path, n, static_cast<long>(b + 1), cells[2]);
        if (dim_out != 1) {
          throw FileError(
              path, n, static_cast<long>(b + 1) + cells[2].column,
              fmt::format("{} output values per line: only single-channel ALTA files are supported", cells[2].text));
        }
      } else if (key == "VS") {
        if (rest != "0") {
          throw FileError(path, n, col,
                          fmt::format("'#VS {}': vertical segments are not supported (only #VS 0)", rest));
        }
      } else if (key == "PARAM_IN") {
        if (rest == "ISOTROPIC_TL_TV_PROJ_DPHI") {
          input = AltaInput::kTlTvProjDphi;
        } else if (rest == "SPHERICAL_TL_PL_TV_PV") {
          input = AltaInput::kSphericalTlPlTvPv;
        } else {
          throw FileError(path, n, col,
                          fmt::format("input parametrisation '{}' is not supported (ISOTROPIC_TL_TV_PROJ_DPHI, "
                                      "SPHERICAL_TL_PL_TV_PV)",
                                      rest));
        }
      } else if (key == "PARAM_OUT") {
        output = parse_output(rest);
        if (output == AltaOutput::kUnknown) {
          throw FileError(
              path, n, col,
              fmt::format("output unit '{}' is not supported (INV_STERADIAN, INV_STERADIAN_COSINE_FACTOR)", rest));
        }
      } else if (key == "SAMPLE" || key == "ORIGIN" || key == "URL") {
        std::string k = key;
        for (auto& c : k) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        d.metadata[k] = rest;
      }
      continue;
    }
    if (!header_done) {
      header_done = true;
      if (input == AltaInput::kUnknown) throw FileError(path, n, 0, "data before any #PARAM_IN line");
      const int expected_in = input == AltaInput::kTlTvProjDphi ? 3 : 4;
      if (dim_in >= 0 && dim_in != expected_in) {
        throw FileError(path, n, 0,
                        fmt::format("#DIM gives {} inputs but the parametrisation has {}", dim_in, expected_in));
      }
      if (output == AltaOutput::kUnknown) {
        output = parse_output(options.assumed_output);
        if (output == AltaOutput::kUnknown) {
          throw FileError(path, n, 0,
                          "file has no #PARAM_OUT line: state the output unit (INV_STERADIAN or "
                          "INV_STERADIAN_COSINE_FACTOR)");
        }
        d.metadata["alta_output_assumed"] = options.assumed_output;
      }
    }
    const auto cells = split_whitespace(line);
    const std::size_t n_in = input == AltaInput::kTlTvProjDphi ? 3 : 4;
    if (cells.size() != n_in + 1) {
      throw FileError(
          path, n, cells.size() > n_in + 1 ? cells[n_in + 1].column : cells.back().column,
          fmt::format("expected {} values per line ({} inputs, 1 output), found {}", n_in + 1, n_in, cells.size()));
    }
    double v[5];
    for (std::size_t k = 0; k <= n_in; ++k) {
      if (!parse_finite_double(cells[k].text, v[k])) {
        throw FileError(path, n, cells[k].column, fmt::format("'{}' is not a finite number", cells[k].text));
      }
    }
    double theta_l = v[0], phi_l = 0.0, theta_v = 0.0, phi_v = 0.0, value = v[n_in];
    if (input == AltaInput::kTlTvProjDphi) {
      theta_v = std::hypot(v[1], v[2]);
      phi_v = theta_v > 0.0 ? std::atan2(v[2], v[1]) : 0.0;
    } else {
      phi_l = v[1];
      theta_v = v[2];
      phi_v = v[3];
    }
    auto zenith_check = [&](double t, std::size_t k, const char* what) {
      if (t < 0.0 || t > kPi / 2 + 1e-9) {
        throw FileError(path, n, cells[k].column,
                        fmt::format("{} = {} rad is outside [0, pi/2] (text '{}')", what, t, cells[k].text));
      }
      return std::fmin(t, kPi / 2);
    };
    theta_l = zenith_check(theta_l, 0, "theta_l");
    theta_v = zenith_check(theta_v, input == AltaInput::kTlTvProjDphi ? 1 : 2, "theta_v");
    const Geometry g = geometry_from_radians(theta_l, phi_l, theta_v, phi_v);
    if (output == AltaOutput::kInvSteradianCosine) {
      const double c = g.cos_theta_r();
      if (c < 1e-6) {
        if (!options.exclude_grazing) {
          throw FileError(path, n, cells[n_in].column,
                          fmt::format("BRDF x cos(theta_v) at grazing view (theta_v = {:.6f} deg) cannot be "
                                      "converted to a BRDF; exclude such rows explicitly (--exclude-grazing)",
                                      rad_to_deg(theta_v)));
        }
        if (grazing++ == 0) first_grazing = fmt::format("{}:{}", path, n);
        continue;
      }
      value /= c;
    }
    if (value < 0.0 && negative++ == 0) first_negative = fmt::format("{}:{}:{}", path, n, cells[n_in].column);
    auto q = [](double x) { return static_cast<long long>(std::llround(x * 1e9)); };
    const std::array<long long, 4> key{q(g.wi.x), q(g.wi.y), q(g.wr.x), q(g.wr.y)};
    const auto [it, inserted] = seen.emplace(key, std::make_pair(d.geometries.size(), n));
    if (!inserted) {
      if (!options.average_duplicates) {
        throw FileError(path, n, 1,
                        fmt::format("duplicate geometry: same directions as line {} (ask for averaging of duplicates, "
                                    "e.g. --average-duplicates, to average them)",
                                    it->second.second));
      }
      if (multiplicity.empty()) multiplicity.assign(d.geometries.size(), 1);
      ++multiplicity[it->second.first];
      d.brdf[it->second.first] += value;
      continue;
    }
    d.geometries.push_back(g);
    d.brdf.push_back(value);
    if (!multiplicity.empty()) multiplicity.push_back(1);
  }
  if (d.geometries.empty()) throw FileError(path, n, 0, "file has no data lines");
  if (!multiplicity.empty()) {
    std::size_t extra = 0;
    for (std::size_t k = 0; k < d.brdf.size(); ++k) {
      d.brdf[k] /= multiplicity[k];
      extra += static_cast<std::size_t>(multiplicity[k] - 1);
    }
    d.metadata["averaged_duplicate_rows"] = std::to_string(extra);
    warn(fmt::format("{}: {} duplicate geometry rows were averaged", path, extra));
  }
  d.wavelengths = {options.wavelength_nm};
  d.metadata["units"] = "sr^-1";
  d.metadata["source"] = "ALTA text format";
  d.metadata["alta_conversion"] = output == AltaOutput::kInvSteradianCosine
                                      ? "INV_STERADIAN_COSINE_FACTOR divided by cos(theta_v) (viewing zenith)"
                                      : "INV_STERADIAN (BRDF as stored)";
  if (grazing > 0) {
    d.metadata["alta_grazing_rows_excluded"] = std::to_string(grazing);
    warn(
        fmt::format("{}: {} rows at grazing view (cos theta_v < 1e-6) excluded: BRDF x cos theta_v cannot be "
                    "converted there (first at {})",
                    path, grazing, first_grazing));
  }
  if (negative > 0) {
    warn(fmt::format("{}: {} of {} BRDF values are negative (kept: measurement noise; first at {})", path, negative,
                     d.brdf.size(), first_negative));
  }
  return d;
}

}  // namespace roadbrdf
