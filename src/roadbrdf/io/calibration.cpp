#include "roadbrdf/io/calibration.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf {

spectra::SpectrumReadOptions panel_read_options() {
  spectra::SpectrumReadOptions o;
  o.input.what = "a panel reflectance file";
  o.input.max_bytes = kPanelFileMaxBytes;
  o.input.max_line_bytes = 1 << 16;
  o.input.regular_file_only = true;
  return o;
}

spectra::Spectrum read_panel_reflectance(const std::string& path) {
  return spectra::read_spectrum(path, panel_read_options());
}

std::optional<spectra::Spectrum> read_panel_brf(const std::string& path, std::optional<double> first_wavelength,
                                                std::optional<double> step) {
  if (path.empty()) {
    if (first_wavelength) throw FieldError("panel_brf_start", "needs the panel BRF file (`panel_brf`)");
    if (step) throw FieldError("panel_brf_step", "needs the panel BRF file (`panel_brf`)");
    return std::nullopt;
  }
  spectra::SpectrumReadOptions o = panel_read_options();
  o.first_wavelength = first_wavelength;
  o.step = step;
  return spectra::read_spectrum(path, o);
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
  const spectra::Spectrum& panel = in.panel_brf ? *in.panel_brf : in.panel_reflectance;
  const std::string panel_what = in.panel_brf ? "panel BRF" : "panel reflectance";
  std::vector<double> c(m), c_sigma(m, 0.0);
  double correction_sum = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    const double wl = in.sample.wavelengths[j];
    c[j] = panel.value(wl, panel_what + " (" + panel.name() + ")") / kPi;
    if (!panel.sigma().empty()) c_sigma[j] = panel.sigma_at(wl, panel_what) / kPi;
    if (in.panel_brf) {
      const double rho = in.panel_reflectance.value(wl, "panel reflectance (" + in.panel_reflectance.name() + ")");
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
      in.sample.has_sigma() || in.reference.has_sigma() || (in.dark && in.dark->has_sigma()) || !panel.sigma().empty();
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
                                            in.panel_brf ? "BRF_panel" : "rho_ref", panel_what, panel.name());
  if (in.panel_brf) {
    out.metadata["panel_brf_correction_mean"] = fmt::format("{:.6g} (mean of BRF_panel / rho_ref over the wavelengths)",
                                                            correction_sum / static_cast<double>(m));
  }
  return out;
}

}  // namespace roadbrdf
