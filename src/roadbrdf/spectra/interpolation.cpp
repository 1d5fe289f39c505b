#include "roadbrdf/spectra/interpolation.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"

namespace roadbrdf::spectra {

std::optional<LinearStencil> linear_stencil(const std::vector<double>& x, double wavelength, Extrapolation outside,
                                            std::string_view what) {
  if (!std::isfinite(wavelength)) throw InputError(fmt::format("{}: wavelength is not finite", what));
  if (x.empty()) throw InputError(fmt::format("{}: empty table", what));
  const double tolerance =
      outside == Extrapolation::kRefuseBeyondRounding ? 1e-9 * std::max(1.0, std::fabs(x.back())) : 0.0;
  if (wavelength < x.front() - tolerance || wavelength > x.back() + tolerance) {
    if (outside == Extrapolation::kZero) return std::nullopt;
    throw InputError(fmt::format("{}: {} nm is outside the tabulated range [{}, {}] nm (no extrapolation)", what,
                                 wavelength, x.front(), x.back()));
  }
  if (x.size() == 1) return LinearStencil{};
  // The interval [x[lower], x[lower + 1]] holding the wavelength (the last one for the last point);
  // within rounding outside the range, t is clamped to the nearest end.
  const auto above = std::upper_bound(x.begin(), x.end(), wavelength);
  std::size_t lower = above == x.begin() ? 0 : static_cast<std::size_t>(above - x.begin()) - 1;
  if (lower + 1 >= x.size()) lower = x.size() - 2;
  const double t = std::clamp((wavelength - x[lower]) / (x[lower + 1] - x[lower]), 0.0, 1.0);
  return LinearStencil{lower, lower + 1, t};
}

double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double wavelength,
                          Extrapolation outside, std::string_view what) {
  if (x.size() != y.size()) {
    throw InputError(fmt::format("{}: {} wavelengths but {} values", what, x.size(), y.size()));
  }
  const std::optional<LinearStencil> s = linear_stencil(x, wavelength, outside, what);
  if (!s) return 0.0;
  return (1.0 - s->t) * y[s->lower] + s->t * y[s->upper];
}

bool sprague_applies(const std::vector<double>& x) {
  if (x.size() < 6) return false;
  const double step = x[1] - x[0];
  for (std::size_t k = 2; k < x.size(); ++k) {
    if (std::abs((x[k] - x[k - 1]) - step) > 1e-9 * std::max(1.0, std::abs(step))) return false;
  }
  return true;
}

namespace {

// Sprague's end-point formulae (CIE 167:2005): a point beyond the end of the table from the six
// points nearest that end, p[0] being the end point itself. The coefficients c give the first
// point beyond the end; those of the second are further below.
double end_point(const double (&c)[6], const double* p) {
  return (c[0] * p[0] + c[1] * p[1] + c[2] * p[2] + c[3] * p[3] + c[4] * p[4] + c[5] * p[5]) / 209.0;
}
constexpr double kNext[6] = {508, -540, 488, -367, 144, -24};
constexpr double kSecond[6] = {884, -1960, 3033, -2648, 1080, -180};

// Sprague's quintic through f[-2..3] at fraction u in (0, 1) of the interval [f0, f1]
// (coefficients of CIE 167:2005 and Westland, Ripamonti & Cheung, "Computational Colour Science").
// At u = 1/2 it reduces to (3 f-2 - 25 f-1 + 150 f0 + 150 f1 - 25 f2 + 3 f3) / 256.
double sprague_quintic(const double (&f)[6], double u) {
  const double fm2 = f[0], fm1 = f[1], f0 = f[2], f1 = f[3], f2 = f[4], f3 = f[5];
  const double a0 = f0;
  const double a1 = (2 * fm2 - 16 * fm1 + 16 * f1 - 2 * f2) / 24.0;
  const double a2 = (-fm2 + 16 * fm1 - 30 * f0 + 16 * f1 - f2) / 24.0;
  const double a3 = (-9 * fm2 + 39 * fm1 - 70 * f0 + 66 * f1 - 33 * f2 + 7 * f3) / 24.0;
  const double a4 = (13 * fm2 - 64 * fm1 + 126 * f0 - 124 * f1 + 61 * f2 - 12 * f3) / 24.0;
  const double a5 = (-5 * fm2 + 25 * fm1 - 50 * f0 + 50 * f1 - 25 * f2 + 5 * f3) / 24.0;
  return a0 + u * (a1 + u * (a2 + u * (a3 + u * (a4 + u * a5))));
}

}  // namespace

double interpolate_sprague(const std::vector<double>& y, double first, double step, double wavelength) {
  const std::size_t n = y.size();
  const double position = (wavelength - first) / step;
  std::size_t j = static_cast<std::size_t>(std::floor(position));
  if (j >= n - 1) j = n - 2;
  const double u = position - static_cast<double>(j);
  if (u <= 0.0) return y[j];
  if (u >= 1.0) return y[j + 1];
  const double head[6] = {y[0], y[1], y[2], y[3], y[4], y[5]};
  const double tail[6] = {y[n - 1], y[n - 2], y[n - 3], y[n - 4], y[n - 5], y[n - 6]};
  // The six points y[j-2 .. j+3], with the end points beyond the table where the window reaches out.
  double f[6];
  for (int m = 0; m < 6; ++m) {
    const long k = static_cast<long>(j) - 2 + m;
    if (k == -2) {
      f[m] = end_point(kSecond, head);
    } else if (k == -1) {
      f[m] = end_point(kNext, head);
    } else if (k == static_cast<long>(n)) {
      f[m] = end_point(kNext, tail);
    } else if (k == static_cast<long>(n) + 1) {
      f[m] = end_point(kSecond, tail);
    } else {
      f[m] = y[static_cast<std::size_t>(k)];
    }
  }
  return sprague_quintic(f, u);
}

}  // namespace roadbrdf::spectra
