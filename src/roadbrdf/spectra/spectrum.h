// A tabulated function of wavelength: a lamp's or the sun's spectral power, a panel's reflectance,
// V(lambda), a model parameter per wavelength. Wavelengths are in nm; the values have whatever unit
// the quantity has. How the table is read between and beyond its wavelengths is part of the
// spectrum (spectra/interpolation.h): the CIE tables are Sprague-interpolated, measured spectra
// linearly, and V(lambda) is 0 where it is not tabulated while a panel's reflectance has no value
// there.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/spectra/interpolation.h"

namespace roadbrdf::spectra {

class Spectrum {
 public:
  Spectrum() = default;
  // Wavelengths finite and strictly increasing (>= 1), as many finite values, `sigma` (standard
  // uncertainties of the values) empty or as many, finite and >= 0. Throws InputError naming
  // `name` (the name used in messages: a file's path, "CIE illuminant A", ...).
  Spectrum(std::string name, std::vector<double> wavelengths, std::vector<double> values,
           Interpolation interpolation = Interpolation::kLinear, Extrapolation outside = Extrapolation::kRefuse,
           std::vector<double> sigma = {});

  const std::string& name() const { return name_; }
  const std::vector<double>& wavelengths() const { return wavelengths_; }
  const std::vector<double>& values() const { return values_; }
  const std::vector<double>& sigma() const { return sigma_; }  // empty: no uncertainties
  std::size_t size() const { return wavelengths_.size(); }
  bool empty() const { return wavelengths_.empty(); }
  double min_wavelength() const { return wavelengths_.front(); }
  double max_wavelength() const { return wavelengths_.back(); }
  bool covers(double wavelength_nm) const {
    return !wavelengths_.empty() && wavelength_nm >= wavelengths_.front() && wavelength_nm <= wavelengths_.back();
  }
  Interpolation interpolation() const { return interpolation_; }
  Extrapolation extrapolation() const { return outside_; }
  // True when the Sprague rule applies (Interpolation::kSprague on a uniform grid of >= 6 points).
  bool uses_sprague() const { return sprague_; }

  // The interpolated value. A table with no negative value never gives one (Sprague's polynomial
  // can dip below 0 next to zeros, e.g. in the tails of V(lambda); such a dip is 0). Outside the
  // range: 0 or InputError, as the extrapolation policy says; messages name `what`.
  double value(double wavelength_nm, std::string_view what) const;
  double value(double wavelength_nm) const { return value(wavelength_nm, name_); }
  double operator()(double wavelength_nm) const { return value(wavelength_nm); }
  // The standard uncertainty, linearly interpolated (the same policy outside); 0 without sigma().
  double sigma_at(double wavelength_nm, std::string_view what) const;

 private:
  std::string name_;
  std::vector<double> wavelengths_;
  std::vector<double> values_;
  std::vector<double> sigma_;
  Interpolation interpolation_ = Interpolation::kLinear;
  Extrapolation outside_ = Extrapolation::kRefuse;
  bool sprague_ = false;
  bool non_negative_ = true;
};

// Trapezoid integral of the values over the spectrum's own grid (value unit x nm).
double trapezoid_integral(const Spectrum& spectrum);

}  // namespace roadbrdf::spectra
