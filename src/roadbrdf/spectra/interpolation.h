// Interpolation of tabulated functions of wavelength: the one place where a value between (and
// beyond) tabulated wavelengths is decided.
//
// Rules. Linear: the straight line through the two neighbouring points (exact for linear
// functions; preserves the sign of the table). Sprague: the fifth-order polynomial through the six
// nearest points of a uniform grid (Sprague 1880; CIE 167:2005 recommends it for 10 nm colorimetric
// tables), reproducing polynomials of degree <= 5 exactly; at the ends, two extra points on each
// side come from Sprague's end-point formulae. It needs >= 6 points on a uniform grid; a table
// that is not one is interpolated linearly.
//
// Outside the tabulated range nothing is extrapolated: the policy says whether a wavelength there
// is an error or counts as 0 (a spectrum that is zero where it is not tabulated, e.g. V(lambda)).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace roadbrdf::spectra {

enum class Interpolation {
  kLinear,   // straight lines between neighbouring points
  kSprague,  // Sprague's quintic on uniform grids of >= 6 points, else linear
};

enum class Extrapolation {
  kRefuse,  // a wavelength outside [first, last] is an InputError
  // The same, except that a wavelength within rounding (1e-9 of max(1, |last|)) of the range takes
  // the value at the nearest end: wavelengths written to files with fewer digits still match.
  kRefuseBeyondRounding,
  kZero,  // 0 outside [first, last]
};

// Where a wavelength lies in a table x (strictly increasing, >= 1 point): the value there is
// (1 - t) y[lower] + t y[upper], t in [0, 1] (upper = lower + 1; a one-point table has upper = lower).
struct LinearStencil {
  std::size_t lower = 0, upper = 0;
  double t = 0.0;
};

// The stencil at `wavelength`; std::nullopt outside the range under Extrapolation::kZero. Throws
// InputError naming `what` for a non-finite wavelength, an empty table, or a wavelength outside
// the range under the refusing policies.
std::optional<LinearStencil> linear_stencil(const std::vector<double>& x, double wavelength, Extrapolation outside,
                                            std::string_view what);

// Linear interpolation of the table (x, y) at `wavelength` (0 where the policy says so).
double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double wavelength,
                          Extrapolation outside, std::string_view what);

// True when x has >= 6 points with equal steps (to 1e-9 of the step): the grids Sprague's
// polynomial is defined on.
bool sprague_applies(const std::vector<double>& x);

// Sprague's quintic for values y on the uniform grid x_k = first + k step (y.size() >= 6) at
// `wavelength` in [first, first + (n - 1) step] (the caller checks the range): y[k] at grid points.
double interpolate_sprague(const std::vector<double>& y, double first, double step, double wavelength);

}  // namespace roadbrdf::spectra
