#include "roadbrdf/lighting/luminaire_flux.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace roadbrdf::lighting {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// int_p^q I(g) sin(g) dg for I linear from I(p) = a to I(q) = b, p < q in radians.
double linear_times_sine(double p, double q, double a, double b) {
  const double slope = (b - a) / (q - p);
  return a * (std::cos(p) - std::cos(q)) + slope * (std::sin(q) - std::sin(p) - (q - p) * std::cos(q));
}

// int over one C-plane's gamma range of I sin(gamma), split at 90 deg: {below, above}.
void plane_integral(const IntensityDistribution& d, std::size_t plane, double& below, double& above) {
  below = 0.0;
  above = 0.0;
  const std::vector<double>& g = d.gamma_deg;
  for (std::size_t j = 0; j + 1 < g.size(); ++j) {
    const double p = g[j];
    const double q = g[j + 1];
    if (q <= p) continue;  // a zero-width interval holds no flux
    const double a = d.at(plane, j);
    const double b = d.at(plane, j + 1);
    if (q <= 90.0) {
      below += linear_times_sine(p * kDegree, q * kDegree, a, b);
    } else if (p >= 90.0) {
      above += linear_times_sine(p * kDegree, q * kDegree, a, b);
    } else {
      const double middle = a + (b - a) * (90.0 - p) / (q - p);  // the interpolant at the horizontal
      below += linear_times_sine(p * kDegree, 0.5 * kPi, a, middle);
      above += linear_times_sine(0.5 * kPi, q * kDegree, middle, b);
    }
  }
}

}  // namespace

LuminousFlux luminous_flux(const IntensityDistribution& d) {
  d.check_consistent();
  LuminousFlux flux;
  const std::size_t n = d.c_deg.size();
  if (n == 1) {  // the same plane in every azimuth: 2 pi times its integral
    double below = 0.0, above = 0.0;
    plane_integral(d, 0, below, above);
    flux.downward_lm = 2.0 * kPi * below;
    flux.upward_lm = 2.0 * kPi * above;
    return flux;
  }
  // Trapezoidal weights of the periodic piecewise-linear interpolation in C: half the spans to
  // the neighbouring planes, the last plane's right neighbour being the first one + 360 deg.
  for (std::size_t i = 0; i < n; ++i) {
    const double previous = i == 0 ? d.c_deg[n - 1] - 360.0 : d.c_deg[i - 1];
    const double next = i + 1 == n ? d.c_deg[0] + 360.0 : d.c_deg[i + 1];
    const double weight = 0.5 * (next - previous) * kDegree;
    double below = 0.0, above = 0.0;
    plane_integral(d, i, below, above);
    flux.downward_lm += weight * below;
    flux.upward_lm += weight * above;
  }
  return flux;
}

}  // namespace roadbrdf::lighting
