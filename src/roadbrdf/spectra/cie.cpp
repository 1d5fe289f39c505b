#include "roadbrdf/spectra/cie.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf::photometry {

namespace {

constexpr double kVMin = 340.0;
constexpr double kVMax = 830.0;

// A column of the bundled CIE table: Sprague-interpolated, values >= 0.
spectra::Spectrum load_bundled_column(const std::string& column, const std::string& name,
                                      spectra::Extrapolation outside) {
  spectra::SpectrumReadOptions o;
  o.name = name;
  o.quantity = column;
  o.value_column = column;
  o.non_negative = true;
  o.min_points = 6;
  o.interpolation = spectra::Interpolation::kSprague;
  o.outside = outside;
  return spectra::read_spectrum(data_file("third-party/photometry/cie-1931-v-lambda-illuminants.csv"), o);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// 1 nm trapezoid of g over [lo, hi] (ends included even if not integers).
template <typename F>
double integrate_1nm(double lo, double hi, F g) {
  if (!(hi > lo)) return 0.0;
  const std::vector<double> grid = photometric_grid(lo, hi);
  double sum = 0.0;
  for (std::size_t k = 1; k < grid.size(); ++k) {
    sum += 0.5 * (grid[k] - grid[k - 1]) * (g(grid[k]) + g(grid[k - 1]));
  }
  return sum;
}

}  // namespace

const spectra::Spectrum& v_lambda() {
  static const spectra::Spectrum table = load_bundled_column("v_lambda", "V(lambda)", spectra::Extrapolation::kZero);
  return table;
}

const spectra::Spectrum& illuminant_a() {
  static const spectra::Spectrum table =
      load_bundled_column("illuminant_A", "CIE illuminant A", spectra::Extrapolation::kRefuse);
  return table;
}

const spectra::Spectrum& illuminant_d65() {
  static const spectra::Spectrum table =
      load_bundled_column("illuminant_D65", "CIE illuminant D65", spectra::Extrapolation::kRefuse);
  return table;
}

spectra::Spectrum read_lamp_spectrum(const std::string& path) {
  spectra::SpectrumReadOptions o;
  o.quantity = "spectral power";
  o.uncertainties = false;
  o.one_column = false;
  o.non_negative = true;
  o.min_points = 2;
  o.interpolation = spectra::Interpolation::kSprague;
  o.outside = spectra::Extrapolation::kZero;
  const spectra::Spectrum s = spectra::read_spectrum(path, o);
  const double total = integrate_1nm(kVMin, kVMax, [](double l) { return v_lambda().value(l); });
  const double lo = std::max(kVMin, s.min_wavelength());
  const double hi = std::min(kVMax, s.max_wavelength());
  const double inside = integrate_1nm(lo, hi, [](double l) { return v_lambda().value(l); });
  if (inside < 0.99 * total) {
    throw FileError(path, 0, 0,
                    "the lamp spectrum (" + std::to_string(s.min_wavelength()) + "-" +
                        std::to_string(s.max_wavelength()) + " nm) covers only " +
                        std::to_string(100.0 * inside / total) +
                        "% of the V(lambda) integral; at least 99% is needed (e.g. 400-700 nm)");
  }
  double luminous = integrate_1nm(lo, hi, [&](double l) { return v_lambda().value(l) * s.value(l); });
  if (!(luminous > 0.0)) throw FileError(path, 0, 0, "the lamp spectrum has no power where V(lambda) > 0");
  return s;
}

spectra::Spectrum illuminant_from_name(const std::string& name_or_file) {
  const std::string l = lower(name_or_file);
  if (l == "a") return illuminant_a();
  if (l == "d65") return illuminant_d65();
  return read_lamp_spectrum(name_or_file);
}

std::vector<double> photometric_grid(double lo_nm, double hi_nm) {
  const double lo = std::max(lo_nm, kVMin);
  const double hi = std::min(hi_nm, kVMax);
  std::vector<double> grid;
  if (!(hi >= lo)) return grid;
  grid.push_back(lo);
  for (double l = std::floor(lo) + 1.0; l < hi; l += 1.0) {
    if (l > grid.back()) grid.push_back(l);
  }
  if (hi > grid.back()) grid.push_back(hi);
  return grid;
}

double luminous_coverage(double lo_nm, double hi_nm, const spectra::Spectrum& illuminant) {
  const auto vs = [&](double l) {
    const double v = v_lambda().value(l);
    if (v == 0.0 || !illuminant.covers(l)) return 0.0;
    return v * illuminant.value(l);
  };
  const double full_lo = std::max(kVMin, illuminant.min_wavelength());
  const double full_hi = std::min(kVMax, illuminant.max_wavelength());
  const double total = integrate_1nm(full_lo, full_hi, vs);
  if (!(total > 0.0)) throw InputError("illuminant '" + illuminant.name() + "' has no power where V(lambda) > 0");
  const double part = integrate_1nm(std::max(lo_nm, full_lo), std::min(hi_nm, full_hi), vs);
  return part / total;
}

std::vector<double> photometric_weights(const std::vector<double>& wavelengths, const spectra::Spectrum& illuminant,
                                        double min_coverage) {
  const std::size_t n = wavelengths.size();
  if (n < 2) throw InputError("photometric weights need at least 2 wavelengths");
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(wavelengths[k])) throw InputError("photometric weights: wavelength is not finite");
    if (k > 0 && !(wavelengths[k] > wavelengths[k - 1])) {
      throw InputError("photometric weights: wavelengths must be strictly increasing");
    }
  }
  const double coverage = luminous_coverage(wavelengths.front(), wavelengths.back(), illuminant);
  if (coverage < min_coverage) {
    throw InputError("the wavelengths " + std::to_string(wavelengths.front()) + "-" +
                     std::to_string(wavelengths.back()) + " nm cover only " + std::to_string(100.0 * coverage) +
                     "% of the luminous integral under '" + illuminant.name() + "' (at least " +
                     std::to_string(100.0 * min_coverage) + "% needed)");
  }
  std::vector<double> w(n, 0.0);
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double v = v_lambda().value(wavelengths[k]);
    if (v == 0.0 || !illuminant.covers(wavelengths[k])) continue;
    const double left = k > 0 ? wavelengths[k] - wavelengths[k - 1] : 0.0;
    const double right = k + 1 < n ? wavelengths[k + 1] - wavelengths[k] : 0.0;
    w[k] = v * illuminant.value(wavelengths[k]) * 0.5 * (left + right);
    sum += w[k];
  }
  if (!(sum > 0.0)) throw InputError("photometric weights: no grid wavelength where V(lambda) S(lambda) > 0");
  for (double& x : w) x /= sum;
  return w;
}

}  // namespace roadbrdf::photometry
