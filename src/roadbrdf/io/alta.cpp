#include "roadbrdf/io/alta.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <span>
#include <utility>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf {

namespace {

// The input parametrisations (kUnknown: not stated yet), named as ALTA names them.
enum class AltaInput { kUnknown, kTlTvProjDphi, kSphericalTlPlTvPv };
constexpr EnumName<AltaInput> kAltaInputNames[] = {
    {AltaInput::kTlTvProjDphi, "ISOTROPIC_TL_TV_PROJ_DPHI", ""},
    {AltaInput::kSphericalTlPlTvPv, "SPHERICAL_TL_PL_TV_PV", ""},
};
constexpr std::span<const EnumName<AltaInput>> enum_names(AltaInput) { return kAltaInputNames; }
static_assert(entries_are_distinct(kAltaInputNames));

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

// The reader of one ALTA file, a line at a time: the '#' header lines, then the data lines (one
// geometry each: the input angles and one output value).
class AltaParser {
 public:
  AltaParser(const std::string& path, const AltaReadOptions& options) : path_(path), options_(options) {}

  void read_line(const std::string& line) {
    ++n_;
    const auto b = line.find_first_not_of(kBlankCharacters);
    if (b == std::string::npos) return;
    if (line[b] == '#') {
      header_line(line, b);
      return;
    }
    if (!header_done_) begin_data();
    data_line(line);
  }

  SpectralDataset finish();

 private:
  void header_line(const std::string& line, std::size_t b);
  void begin_data();
  void data_line(const std::string& line);
  double zenith(double t, const CsvCell& cell, const char* what) const;
  void add_sample(const Geometry& g, double value);
  void warn(const std::string& m) const {
    if (options_.warn) {
      options_.warn(m);
    } else {
      route_warning(m);
    }
  }

  const std::string& path_;
  const AltaReadOptions& options_;
  SpectralDataset d_;
  AltaInput input_ = AltaInput::kUnknown;
  std::optional<AltaOutput> output_;  // not stated yet
  int dim_in_ = -1, dim_out_ = -1;
  bool header_done_ = false;
  long n_ = 0;  // line number
  std::size_t negative_ = 0, grazing_ = 0;
  std::string first_negative_, first_grazing_;
  // Quantised directions -> (geometry index, line of its first sample).
  std::map<std::array<long long, 4>, std::pair<std::size_t, long>> seen_;
  std::vector<int> multiplicity_;  // samples per geometry, once a duplicate was averaged
};

// A '#KEY value' line: b is the position of the '#'.
void AltaParser::header_line(const std::string& line, std::size_t b) {
  const auto cells = split_whitespace(std::string_view(line).substr(b + 1));
  if (cells.empty()) return;
  const std::string key(cells[0].text);
  // Cell columns are 1-based within the text after '#' (spaces after '#' are allowed).
  const std::size_t key_start = b + static_cast<std::size_t>(cells[0].column);
  const std::string rest = trim(line.substr(key_start + cells[0].text.size()));
  const long col = static_cast<long>(key_start) + 1;
  const bool header_key = key == "DIM" || key == "PARAM_IN" || key == "PARAM_OUT" || key == "VS";
  if (header_key && header_done_) {
    throw FileError(path_, n_, col,
                    fmt::format("#{} after the data: the header must come before the first data line", key));
  }
  if (key == "DIM") {
    if (cells.size() != 3) throw FileError(path_, n_, col, "#DIM expects two numbers (inputs, outputs)");
    dim_in_ = dimension(path_, n_, static_cast<long>(b + 1), cells[1]);
    dim_out_ = dimension(path_, n_, static_cast<long>(b + 1), cells[2]);
    if (dim_out_ != 1) {
      throw FileError(
          path_, n_, static_cast<long>(b + 1) + cells[2].column,
          fmt::format("{} output values per line: only single-channel ALTA files are supported", cells[2].text));
    }
  } else if (key == "VS") {
    if (rest != "0") {
      throw FileError(path_, n_, col, fmt::format("'#VS {}': vertical segments are not supported (only #VS 0)", rest));
    }
  } else if (key == "PARAM_IN") {
    input_ = find_name<AltaInput>(rest).value_or(AltaInput::kUnknown);
    if (input_ == AltaInput::kUnknown) {
      throw FileError(path_, n_, col,
                      fmt::format("input parametrisation '{}' is not supported ({})", rest,
                                  fmt::join(names_of<AltaInput>(), ", ")));
    }
  } else if (key == "PARAM_OUT") {
    output_ = find_name<AltaOutput>(rest);
    if (!output_) {
      throw FileError(
          path_, n_, col,
          fmt::format("output unit '{}' is not supported ({})", rest, fmt::join(names_of<AltaOutput>(), ", ")));
    }
  } else if (key == "SAMPLE" || key == "ORIGIN" || key == "URL") {
    std::string k = key;
    for (auto& c : k) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    d_.metadata[k] = rest;
  }
}

// At the first data line the header is complete: the parametrisation must be known, agree with
// #DIM, and the output unit be stated (or assumed by the caller).
void AltaParser::begin_data() {
  header_done_ = true;
  if (input_ == AltaInput::kUnknown) throw FileError(path_, n_, 0, "data before any #PARAM_IN line");
  const int expected_in = input_ == AltaInput::kTlTvProjDphi ? 3 : 4;
  if (dim_in_ >= 0 && dim_in_ != expected_in) {
    throw FileError(path_, n_, 0,
                    fmt::format("#DIM gives {} inputs but the parametrisation has {}", dim_in_, expected_in));
  }
  if (!output_) {
    output_ = find_name<AltaOutput>(options_.assumed_output);
    if (!output_) {
      throw FileError(path_, n_, 0,
                      "file has no #PARAM_OUT line: state the output unit (" + names_text<AltaOutput>() + ")");
    }
    d_.metadata["alta_output_assumed"] = options_.assumed_output;
  }
}

// A zenith angle [rad] of a data line in [0, pi/2] (a rounding excess up to 1e-9 is clamped).
double AltaParser::zenith(double t, const CsvCell& cell, const char* what) const {
  if (t < 0.0 || t > kPi / 2 + 1e-9) {
    throw FileError(path_, n_, cell.column,
                    fmt::format("{} = {} rad is outside [0, pi/2] (text '{}')", what, t, cell.text));
  }
  return std::fmin(t, kPi / 2);
}

void AltaParser::data_line(const std::string& line) {
  const auto cells = split_whitespace(line);
  const std::size_t n_in = input_ == AltaInput::kTlTvProjDphi ? 3 : 4;
  if (cells.size() != n_in + 1) {
    throw FileError(
        path_, n_, cells.size() > n_in + 1 ? cells[n_in + 1].column : cells.back().column,
        fmt::format("expected {} values per line ({} inputs, 1 output), found {}", n_in + 1, n_in, cells.size()));
  }
  double v[5];
  for (std::size_t k = 0; k <= n_in; ++k) {
    if (!parse_finite_double(cells[k].text, v[k])) {
      throw FileError(path_, n_, cells[k].column, fmt::format("'{}' is not a finite number", cells[k].text));
    }
  }
  double theta_l = v[0], phi_l = 0.0, theta_v = 0.0, phi_v = 0.0, value = v[n_in];
  if (input_ == AltaInput::kTlTvProjDphi) {
    theta_v = std::hypot(v[1], v[2]);
    phi_v = theta_v > 0.0 ? std::atan2(v[2], v[1]) : 0.0;
  } else {
    phi_l = v[1];
    theta_v = v[2];
    phi_v = v[3];
  }
  theta_l = zenith(theta_l, cells[0], "theta_l");
  theta_v = zenith(theta_v, cells[input_ == AltaInput::kTlTvProjDphi ? 1 : 2], "theta_v");
  const Geometry g = geometry_from_radians(theta_l, phi_l, theta_v, phi_v);
  if (*output_ == AltaOutput::kInvSteradianCosine) {
    const double c = g.cos_theta_r();
    if (c < 1e-6) {
      if (!options_.exclude_grazing) {
        throw FileError(path_, n_, cells[n_in].column,
                        fmt::format("BRDF x cos(theta_v) at grazing view (theta_v = {:.6f} deg) cannot be "
                                    "converted to a BRDF; exclude such rows explicitly (`exclude_grazing`)",
                                    rad_to_deg(theta_v)));
      }
      if (grazing_++ == 0) first_grazing_ = fmt::format("{}:{}", path_, n_);
      return;
    }
    value /= c;
  }
  if (value < 0.0 && negative_++ == 0) first_negative_ = fmt::format("{}:{}:{}", path_, n_, cells[n_in].column);
  add_sample(g, value);
}

// A new geometry, or (when averaging is asked for) one more sample of a geometry already seen.
void AltaParser::add_sample(const Geometry& g, double value) {
  auto q = [](double x) { return static_cast<long long>(std::llround(x * 1e9)); };
  const std::array<long long, 4> key{q(g.wi.x), q(g.wi.y), q(g.wr.x), q(g.wr.y)};
  const auto [it, inserted] = seen_.emplace(key, std::make_pair(d_.geometries.size(), n_));
  if (!inserted) {
    if (!options_.average_duplicates) {
      throw FileError(path_, n_, 1,
                      fmt::format("duplicate geometry: same directions as line {} (ask for averaging of duplicates "
                                  "(`average_duplicates`) to average them)",
                                  it->second.second));
    }
    if (multiplicity_.empty()) multiplicity_.assign(d_.geometries.size(), 1);
    ++multiplicity_[it->second.first];
    d_.brdf[it->second.first] += value;
    return;
  }
  d_.geometries.push_back(g);
  d_.brdf.push_back(value);
  if (!multiplicity_.empty()) multiplicity_.push_back(1);
}

// The dataset once every line is read: duplicate averages, metadata, warnings.
SpectralDataset AltaParser::finish() {
  SpectralDataset& d = d_;
  if (d.geometries.empty()) throw FileError(path_, n_, 0, "file has no data lines");
  if (!multiplicity_.empty()) {
    std::size_t extra = 0;
    for (std::size_t k = 0; k < d.brdf.size(); ++k) {
      d.brdf[k] /= multiplicity_[k];
      extra += static_cast<std::size_t>(multiplicity_[k] - 1);
    }
    d.metadata["averaged_duplicate_rows"] = std::to_string(extra);
    warn(fmt::format("{}: {} duplicate geometry rows were averaged", path_, extra));
  }
  d.wavelengths = {options_.wavelength_nm};
  d.metadata["units"] = "sr^-1";
  d.metadata["source"] = "ALTA text format";
  d.metadata["alta_conversion"] = *output_ == AltaOutput::kInvSteradianCosine
                                      ? name_of(*output_) + " divided by cos(theta_v) (viewing zenith)"
                                      : name_of(*output_) + " (BRDF as stored)";
  if (grazing_ > 0) {
    d.metadata["alta_grazing_rows_excluded"] = std::to_string(grazing_);
    warn(
        fmt::format("{}: {} rows at grazing view (cos theta_v < 1e-6) excluded: BRDF x cos theta_v cannot be "
                    "converted there (first at {})",
                    path_, grazing_, first_grazing_));
  }
  if (negative_ > 0) {
    warn(fmt::format("{}: {} of {} BRDF values are negative (kept: measurement noise; first at {})", path_, negative_,
                     d.brdf.size(), first_negative_));
  }
  return std::move(d_);
}

}  // namespace

SpectralDataset read_alta(const std::string& path, const AltaReadOptions& options) {
  if (!(options.wavelength_nm > 0.0)) {
    throw InputError(path + ": ALTA files carry no wavelength: give the wavelength [nm] of the measurement");
  }
  InputFile in(path);
  AltaParser parser(path, options);
  std::string line;
  while (in.read_line(line)) parser.read_line(line);
  return parser.finish();
}

}  // namespace roadbrdf
