#include "roadbrdf/spectra/cie.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <mutex>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::photometry {

namespace {

constexpr double kVMin = 340.0;
constexpr double kVMax = 830.0;

// Sprague (1880) quintic through f[-2..3] at fraction x in [0, 1] of the interval [f0, f1]
// (coefficients as given in CIE 167:2005 / Westland, Ripamonti & Cheung, "Computational Colour
// Science", eq. for Sprague interpolation). At x = 1/2 it reduces to
// (3 f-2 - 25 f-1 + 150 f0 + 150 f1 - 25 f2 + 3 f3) / 256.
double sprague(const double* f, double x) {
  const double fm2 = f[0], fm1 = f[1], f0 = f[2], f1 = f[3], f2 = f[4], f3 = f[5];
  const double a0 = f0;
  const double a1 = (2 * fm2 - 16 * fm1 + 16 * f1 - 2 * f2) / 24.0;
  const double a2 = (-fm2 + 16 * fm1 - 30 * f0 + 16 * f1 - f2) / 24.0;
  const double a3 = (-9 * fm2 + 39 * fm1 - 70 * f0 + 66 * f1 - 33 * f2 + 7 * f3) / 24.0;
  const double a4 = (13 * fm2 - 64 * fm1 + 126 * f0 - 124 * f1 + 61 * f2 - 12 * f3) / 24.0;
  const double a5 = (-5 * fm2 + 25 * fm1 - 50 * f0 + 50 * f1 - 25 * f2 + 5 * f3) / 24.0;
  return a0 + x * (a1 + x * (a2 + x * (a3 + x * (a4 + x * a5))));
}

bool uniformly_spaced(const std::vector<double>& w, double& step) {
  step = w[1] - w[0];
  for (std::size_t k = 2; k < w.size(); ++k) {
    if (std::abs((w[k] - w[k - 1]) - step) > 1e-9 * std::max(1.0, std::abs(step))) return false;
  }
  return true;
}

TabulatedSpectrum load_bundled_column(const std::string& column, const std::string& name, bool zero_outside) {
  const std::string path = data_file("third-party/photometry/cie-1931-v-lambda-illuminants.csv");
  CsvReader reader(path);
  std::vector<CsvCell> cells;
  if (!reader.next_row(cells)) throw FileError(path, 0, 0, "empty file");
  std::size_t index = cells.size();
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (cells[k].text == column) index = k;
  }
  if (index == cells.size()) reader.fail(0, "no column '" + column + "'");
  std::vector<double> w, v;
  while (reader.next_row(cells)) {
    if (cells.size() <= index) reader.fail(0, "missing column '" + column + "'");
    w.push_back(reader.number(cells[0], "wavelength [nm]"));
    v.push_back(reader.number(cells[index], column));
  }
  try {
    return TabulatedSpectrum(name, std::move(w), std::move(v), zero_outside);
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    throw FileError(path, 0, 0, e.what());
  }
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

TabulatedSpectrum::TabulatedSpectrum(std::string name, std::vector<double> wavelengths, std::vector<double> values,
                                     bool zero_outside)
    : name_(std::move(name)),
      wavelengths_(std::move(wavelengths)),
      values_(std::move(values)),
      zero_outside_(zero_outside) {
  if (wavelengths_.size() != values_.size()) {
    throw InputError("spectrum '" + name_ + "': " + std::to_string(wavelengths_.size()) + " wavelengths but " +
                     std::to_string(values_.size()) + " values");
  }
  if (wavelengths_.size() < 2) throw InputError("spectrum '" + name_ + "' needs at least 2 wavelengths");
  for (std::size_t k = 0; k < wavelengths_.size(); ++k) {
    if (!std::isfinite(wavelengths_[k]) || !std::isfinite(values_[k])) {
      throw InputError("spectrum '" + name_ + "': value " + std::to_string(k + 1) + " is not finite");
    }
    if (values_[k] < 0.0) {
      throw InputError("spectrum '" + name_ + "': negative value " + std::to_string(values_[k]) + " at " +
                       std::to_string(wavelengths_[k]) + " nm");
    }
    if (k > 0 && !(wavelengths_[k] > wavelengths_[k - 1])) {
      throw InputError("spectrum '" + name_ + "': wavelengths must be strictly increasing (at " +
                       std::to_string(wavelengths_[k]) + " nm)");
    }
  }
  double step = 0.0;
  sprague_ = wavelengths_.size() >= 6 && uniformly_spaced(wavelengths_, step);
  if (sprague_) {
    step_ = step;
    // Sprague end-point extrapolation (CIE 167:2005): two points before the first and after the last.
    const std::vector<double>& f = values_;
    const std::size_t n = f.size();
    auto ext = [](double c0, double c1, double c2, double c3, double c4, double c5, const double* p) {
      return (c0 * p[0] + c1 * p[1] + c2 * p[2] + c3 * p[3] + c4 * p[4] + c5 * p[5]) / 209.0;
    };
    const double head[6] = {f[0], f[1], f[2], f[3], f[4], f[5]};
    const double tail[6] = {f[n - 1], f[n - 2], f[n - 3], f[n - 4], f[n - 5], f[n - 6]};
    padded_.reserve(n + 4);
    padded_.push_back(ext(884, -1960, 3033, -2648, 1080, -180, head));
    padded_.push_back(ext(508, -540, 488, -367, 144, -24, head));
    padded_.insert(padded_.end(), f.begin(), f.end());
    padded_.push_back(ext(508, -540, 488, -367, 144, -24, tail));
    padded_.push_back(ext(884, -1960, 3033, -2648, 1080, -180, tail));
  }
}

double TabulatedSpectrum::value(double wavelength_nm) const {
  if (!std::isfinite(wavelength_nm)) throw InputError("spectrum '" + name_ + "': wavelength is not finite");
  if (!covers(wavelength_nm)) {
    if (zero_outside_) return 0.0;
    throw InputError("spectrum '" + name_ + "' is not defined at " + std::to_string(wavelength_nm) + " nm (tabulated " +
                     std::to_string(min_wavelength()) + "-" + std::to_string(max_wavelength()) + " nm)");
  }
  const std::size_t n = wavelengths_.size();
  if (sprague_) {
    const double u = (wavelength_nm - wavelengths_.front()) / step_;
    std::size_t j = static_cast<std::size_t>(std::floor(u));
    if (j >= n - 1) j = n - 2;
    const double x = u - static_cast<double>(j);
    if (x <= 0.0) return values_[j];
    if (x >= 1.0) return values_[j + 1];
    // padded_[j + 2] is values_[j]; the six points are values_[j-2 .. j+3].
    const double y = sprague(&padded_[j], x);
    return y > 0.0 ? y : 0.0;
  }
  const auto it = std::upper_bound(wavelengths_.begin(), wavelengths_.end(), wavelength_nm);
  std::size_t k = static_cast<std::size_t>(it - wavelengths_.begin());
  if (k >= n) k = n - 1;
  const std::size_t j = k - 1;
  const double t = (wavelength_nm - wavelengths_[j]) / (wavelengths_[k] - wavelengths_[j]);
  return (1.0 - t) * values_[j] + t * values_[k];
}

const TabulatedSpectrum& v_lambda() {
  static const TabulatedSpectrum table = load_bundled_column("v_lambda", "V(lambda)", true);
  return table;
}

const TabulatedSpectrum& illuminant_a() {
  static const TabulatedSpectrum table = load_bundled_column("illuminant_A", "CIE illuminant A", false);
  return table;
}

const TabulatedSpectrum& illuminant_d65() {
  static const TabulatedSpectrum table = load_bundled_column("illuminant_D65", "CIE illuminant D65", false);
  return table;
}

TabulatedSpectrum read_spectrum_file(const std::string& path) {
  CsvReader reader(path);
  std::vector<CsvCell> cells;
  std::vector<double> w, v;
  bool first = true;
  while (reader.next_row(cells)) {
    if (first) {
      first = false;
      if (!is_number_text(cells[0].text)) continue;  // header row
    }
    if (cells.size() != 2) {
      reader.fail(cells.size() > 2 ? cells[2].column : 0,
                  "expected 2 columns (wavelength [nm], relative spectral power), got " + std::to_string(cells.size()));
    }
    const double wl = reader.number(cells[0], "wavelength [nm]");
    const double p = reader.number(cells[1], "spectral power");
    if (p < 0.0) reader.fail(cells[1].column, "negative spectral power");
    if (!w.empty() && !(wl > w.back())) reader.fail(cells[0].column, "wavelengths must be strictly increasing");
    w.push_back(wl);
    v.push_back(p);
  }
  if (w.size() < 2) throw FileError(path, 0, 0, "a lamp spectrum needs at least 2 rows");
  TabulatedSpectrum s(path, std::move(w), std::move(v), true);
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

TabulatedSpectrum illuminant_from_name(const std::string& name_or_file) {
  const std::string l = lower(name_or_file);
  if (l == "a") return illuminant_a();
  if (l == "d65") return illuminant_d65();
  return read_spectrum_file(name_or_file);
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

double luminous_coverage(double lo_nm, double hi_nm, const TabulatedSpectrum& illuminant) {
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

std::vector<double> photometric_weights(const std::vector<double>& wavelengths, const TabulatedSpectrum& illuminant,
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
