#include "roadbrdf/spectra/spectrum.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"

namespace roadbrdf::spectra {

Spectrum::Spectrum(std::string name, std::vector<double> wavelengths, std::vector<double> values,
                   Interpolation interpolation, Extrapolation outside, std::vector<double> sigma)
    : name_(std::move(name)),
      wavelengths_(std::move(wavelengths)),
      values_(std::move(values)),
      sigma_(std::move(sigma)),
      interpolation_(interpolation),
      outside_(outside) {
  if (wavelengths_.size() != values_.size()) {
    throw InputError(
        fmt::format("spectrum '{}': {} wavelengths but {} values", name_, wavelengths_.size(), values_.size()));
  }
  if (wavelengths_.empty()) throw InputError(fmt::format("spectrum '{}' has no values", name_));
  if (!sigma_.empty() && sigma_.size() != values_.size()) {
    throw InputError(
        fmt::format("spectrum '{}': {} values but {} uncertainties", name_, values_.size(), sigma_.size()));
  }
  for (std::size_t k = 0; k < wavelengths_.size(); ++k) {
    if (!std::isfinite(wavelengths_[k]) || !std::isfinite(values_[k])) {
      throw InputError(fmt::format("spectrum '{}': value {} is not finite", name_, k + 1));
    }
    if (k > 0 && !(wavelengths_[k] > wavelengths_[k - 1])) {
      throw InputError(
          fmt::format("spectrum '{}': wavelengths must be strictly increasing (at {} nm)", name_, wavelengths_[k]));
    }
    if (!sigma_.empty() && !(std::isfinite(sigma_[k]) && sigma_[k] >= 0.0)) {
      throw InputError(fmt::format("spectrum '{}': uncertainty {} is not finite and >= 0", name_, k + 1));
    }
    if (values_[k] < 0.0) non_negative_ = false;
  }
  sprague_ = interpolation_ == Interpolation::kSprague && sprague_applies(wavelengths_);
}

double Spectrum::value(double wavelength_nm, std::string_view what) const {
  const std::optional<LinearStencil> s = linear_stencil(wavelengths_, wavelength_nm, outside_, what);
  if (!s) return 0.0;
  if (sprague_) {
    // Within rounding of the range (Extrapolation::kRefuseBeyondRounding) the end value holds.
    const double inside = std::clamp(wavelength_nm, wavelengths_.front(), wavelengths_.back());
    const double y = interpolate_sprague(values_, wavelengths_[0], wavelengths_[1] - wavelengths_[0], inside);
    return non_negative_ && !(y > 0.0) ? 0.0 : y;
  }
  return (1.0 - s->t) * values_[s->lower] + s->t * values_[s->upper];
}

double Spectrum::sigma_at(double wavelength_nm, std::string_view what) const {
  if (sigma_.empty()) return 0.0;
  return interpolate_linear(wavelengths_, sigma_, wavelength_nm, outside_, what);
}

double trapezoid_integral(const Spectrum& e) {
  const std::vector<double>& w = e.wavelengths();
  const std::vector<double>& v = e.values();
  double sum = 0.0;
  for (std::size_t k = 1; k < w.size(); ++k) sum += 0.5 * (v[k] + v[k - 1]) * (w[k] - w[k - 1]);
  return sum;
}

}  // namespace roadbrdf::spectra
