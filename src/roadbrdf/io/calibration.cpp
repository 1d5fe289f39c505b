#include "roadbrdf/io/calibration.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/resample.h"

namespace roadbrdf {

std::optional<Spectrum> read_panel_brf(const std::string& path, std::optional<double> first_wavelength,
                                       std::optional<double> step) {
  if (path.empty()) {
    if (first_wavelength) throw FieldError("panel_brf_start", "needs the panel BRF file (panel_brf)");
    if (step) throw FieldError("panel_brf_step", "needs the panel BRF file (panel_brf)");
    return std::nullopt;
  }
  SpectrumReadOptions o;
  o.first_wavelength = first_wavelength;
  o.step = step;
  return read_spectrum(path, o);
}

Spectrum read_spectrum(const std::string& path, const SpectrumReadOptions& options) {
  InputFile in(path);
  Spectrum s;
  s.source = path;
  std::string line;
  long n = 0;
  std::size_t columns = 0;
  bool first_row = true;
  while (in.read_line(line)) {
    ++n;
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    std::string normalized = line;
    std::replace(normalized.begin(), normalized.end(), ',', ' ');
    std::replace(normalized.begin(), normalized.end(), ';', ' ');
    const auto cells = split_whitespace(normalized);
    double v0 = 0.0;
    if (first_row && !parse_finite_double(cells[0].text, v0)) {
      first_row = false;  // a header line
      continue;
    }
    first_row = false;
    if (columns == 0) {
      columns = cells.size();
      if (columns > 3) throw FileError(path, n, cells[3].column, "expected 1 to 3 columns: [wavelength] value [sigma]");
      if (columns == 1 && !(options.first_wavelength && options.step)) {
        throw FileError(path, n, 0, "one-column spectrum: give the wavelength of the first line and the step [nm]");
      }
    }
    if (cells.size() != columns) {
      throw FileError(path, n, cells.size() > columns ? cells[columns].column : cells.back().column,
                      fmt::format("row has {} values, the first row had {}", cells.size(), columns));
    }
    double v[3];
    for (std::size_t k = 0; k < columns; ++k) {
      if (!parse_finite_double(cells[k].text, v[k])) {
        throw FileError(path, n, cells[k].column, fmt::format("'{}' is not a finite number", cells[k].text));
      }
    }
    double wl = 0.0, value = 0.0;
    if (columns == 1) {
      wl = *options.first_wavelength + static_cast<double>(s.values.size()) * *options.step;
      value = v[0];
    } else {
      wl = v[0];
      value = v[1];
      if (!s.wavelengths.empty() && wl <= s.wavelengths.back()) {
        throw FileError(path, n, cells[0].column,
                        fmt::format("wavelength '{}' nm is not above the previous {} nm (must be strictly increasing)",
                                    cells[0].text, s.wavelengths.back()));
      }
      if (columns == 3) {
        if (v[2] < 0)
          throw FileError(path, n, cells[2].column, fmt::format("'{}': negative uncertainty", cells[2].text));
        s.sigma.push_back(v[2]);
      }
    }
    s.wavelengths.push_back(wl);
    s.values.push_back(value);
  }
  if (s.values.empty()) throw FileError(path, n, 0, "file is empty (no values)");
  return s;
}

namespace {

// Row index into `other` for each geometry of `sample`: same geometry (by directions), or row 0
// of a one-row dataset.
std::vector<std::size_t> match_rows(const SpectralDataset& sample, const SpectralDataset& other,
                                    const std::string& what) {
  std::vector<std::size_t> rows(sample.geometries.size(), 0);
  if (other.geometries.size() == 1) return rows;
  auto close = [](const Geometry& a, const Geometry& b) {
    return length(a.wi - b.wi) < 1e-6 && length(a.wr - b.wr) < 1e-6;
  };
  for (std::size_t g = 0; g < sample.geometries.size(); ++g) {
    bool found = false;
    // Same order is the common case.
    if (g < other.geometries.size() && close(sample.geometries[g], other.geometries[g])) {
      rows[g] = g;
      continue;
    }
    for (std::size_t k = 0; k < other.geometries.size() && !found; ++k) {
      if (close(sample.geometries[g], other.geometries[k])) {
        rows[g] = k;
        found = true;
      }
    }
    if (!found) {
      const Geometry& s = sample.geometries[g];
      throw InputError(fmt::format(
          "{} has no row for the sample geometry {} (theta_i {:.4g}, phi_i {:.4g}, theta_r "
          "{:.4g}, phi_r {:.4g} deg): give the same geometries, or a single row",
          what, g + 1, rad_to_deg(s.theta_i), rad_to_deg(s.phi_i), rad_to_deg(s.theta_r), rad_to_deg(s.phi_r)));
    }
  }
  return rows;
}

void same_wavelengths(const SpectralDataset& a, const SpectralDataset& b, const std::string& what) {
  if (a.wavelengths.size() != b.wavelengths.size()) {
    throw InputError(fmt::format("{} has {} wavelengths, the sample {}: radiances must share the wavelengths", what,
                                 b.wavelengths.size(), a.wavelengths.size()));
  }
  for (std::size_t j = 0; j < a.wavelengths.size(); ++j) {
    if (std::fabs(a.wavelengths[j] - b.wavelengths[j]) > 1e-9 * a.wavelengths[j]) {
      throw InputError(
          fmt::format("{} wavelength {} nm differs from the sample's {} nm", what, b.wavelengths[j], a.wavelengths[j]));
    }
  }
}

}  // namespace

SpectralDataset calibrate(const CalibrationInput& in) {
  validate_dataset(in.sample);
  validate_dataset(in.reference);
  same_wavelengths(in.sample, in.reference, "reference radiance");
  const std::vector<std::size_t> ref_rows = match_rows(in.sample, in.reference, "reference radiance");
  std::vector<std::size_t> dark_rows;
  if (in.dark) {
    validate_dataset(*in.dark);
    same_wavelengths(in.sample, *in.dark, "dark signal");
    dark_rows = match_rows(in.sample, *in.dark, "dark signal");
  }
  const std::size_t n = in.sample.geometries.size(), m = in.sample.wavelengths.size();
  // Panel factor c(lambda) = rho/pi (or BRF/pi) and its uncertainty, on the sample wavelengths.
  const Spectrum& panel = in.panel_brf ? *in.panel_brf : in.panel_reflectance;
  const std::string panel_what = in.panel_brf ? "panel BRF" : "panel reflectance";
  std::vector<double> c(m), c_sigma(m, 0.0);
  double correction_sum = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    const double wl = in.sample.wavelengths[j];
    c[j] = interpolate_linear(panel.wavelengths, panel.values, wl, panel_what + " (" + panel.source + ")") / kPi;
    if (!panel.sigma.empty()) {
      c_sigma[j] = interpolate_linear(panel.wavelengths, panel.sigma, wl, panel_what) / kPi;
    }
    if (in.panel_brf) {
      const double rho = interpolate_linear(in.panel_reflectance.wavelengths, in.panel_reflectance.values, wl,
                                            "panel reflectance (" + in.panel_reflectance.source + ")");
      correction_sum += c[j] * kPi / rho;
    }
  }
  SpectralDataset out;
  out.geometries = in.sample.geometries;
  out.wavelengths = in.sample.wavelengths;
  out.convention = in.sample.convention;
  out.metadata = in.sample.metadata;
  out.metadata["units"] = "sr^-1";
  out.brdf.assign(n * m, 0.0);
  const bool any_sigma =
      in.sample.has_sigma() || in.reference.has_sigma() || (in.dark && in.dark->has_sigma()) || !panel.sigma.empty();
  if (any_sigma) out.sigma.assign(n * m, 0.0);
  for (std::size_t g = 0; g < n; ++g) {
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t rs = ref_rows[g] * m + j;
      const double ls = in.sample.brdf[g * m + j];
      const double lr = in.reference.brdf[rs];
      double ld = 0.0, sd = 0.0;
      if (in.dark) {
        ld = in.dark->brdf[dark_rows[g] * m + j];
        if (in.dark->has_sigma()) sd = in.dark->sigma[dark_rows[g] * m + j];
      }
      const double N = ls - ld, D = lr - ld;
      if (std::isnan(N) || std::isnan(D)) {
        // A sample, reference or dark value that was not measured: the result is missing too.
        out.brdf[g * m + j] = std::numeric_limits<double>::quiet_NaN();
        if (any_sigma) out.sigma[g * m + j] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      if (!(D > 0.0)) {
        throw InputError(
            fmt::format("reference radiance {} is not above the dark signal {} at geometry {} and {} nm: "
                        "cannot calibrate",
                        lr, ld, g + 1, out.wavelengths[j]));
      }
      const double f = N / D * c[j];
      out.brdf[g * m + j] = f;
      if (any_sigma) {
        const double ss = in.sample.has_sigma() ? in.sample.sigma[g * m + j] : 0.0;
        const double sr = in.reference.has_sigma() ? in.reference.sigma[rs] : 0.0;
        const double d_s = c[j] / D, d_r = -c[j] * N / (D * D), d_d = c[j] * (N - D) / (D * D), d_c = N / D;
        out.sigma[g * m + j] = std::sqrt(sqr(d_s * ss) + sqr(d_r * sr) + sqr(d_d * sd) + sqr(d_c * c_sigma[j]));
      }
    }
  }
  out.metadata["calibration"] = fmt::format("f = (L_sample - L_dark)/(L_ref - L_dark) * {}/pi; {} from {}",
                                            in.panel_brf ? "BRF_panel" : "rho_ref", panel_what, panel.source);
  if (in.panel_brf) {
    out.metadata["panel_brf_correction_mean"] = fmt::format("{:.6g} (mean of BRF_panel / rho_ref over the wavelengths)",
                                                            correction_sum / static_cast<double>(m));
  }
  return out;
}

}  // namespace roadbrdf
