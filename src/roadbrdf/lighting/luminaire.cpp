#include "roadbrdf/lighting/luminaire.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadbrdf::lighting {

namespace {

// Index i and weight t with x = (1 - t) x[i] + t x[i + 1], for x inside [xs.front(), xs.back()].
void bracket(const std::vector<double>& xs, double x, std::size_t& i, double& t) {
  const auto upper = std::upper_bound(xs.begin(), xs.end(), x);
  if (upper == xs.begin()) {
    i = 0;
    t = 0.0;
    return;
  }
  if (upper == xs.end()) {
    i = xs.size() - 1;
    t = 0.0;
    return;
  }
  i = static_cast<std::size_t>(upper - xs.begin()) - 1;
  t = (x - xs[i]) / (xs[i + 1] - xs[i]);
}

}  // namespace

double IntensityDistribution::intensity(double c, double gamma) const {
  if (gamma < gamma_deg.front() || gamma > gamma_deg.back()) return 0.0;
  std::size_t j = 0;
  double u = 0.0;
  bracket(gamma_deg, gamma, j, u);
  const auto along_gamma = [&](std::size_t i) {
    const double a = at(i, j);
    return u == 0.0 ? a : (1.0 - u) * a + u * at(i, j + 1);
  };
  if (c_deg.size() == 1) return along_gamma(0);
  c = std::fmod(c, 360.0);
  if (c < 0.0) c += 360.0;
  // Between the last plane and 360 (= the first plane again) the interpolation wraps around.
  if (c >= c_deg.back()) {
    const double span = 360.0 - c_deg.back() + c_deg.front();
    const double t = (c - c_deg.back()) / span;
    return (1.0 - t) * along_gamma(c_deg.size() - 1) + t * along_gamma(0);
  }
  if (c < c_deg.front()) {
    const double span = 360.0 - c_deg.back() + c_deg.front();
    const double t = (c + 360.0 - c_deg.back()) / span;
    return (1.0 - t) * along_gamma(c_deg.size() - 1) + t * along_gamma(0);
  }
  std::size_t i = 0;
  double t = 0.0;
  bracket(c_deg, c, i, t);
  return t == 0.0 ? along_gamma(i) : (1.0 - t) * along_gamma(i) + t * along_gamma(i + 1);
}

void IntensityDistribution::check_consistent() const {
  if (c_deg.empty() || gamma_deg.empty()) throw std::logic_error("intensity distribution without angles");
  if (candela.size() != c_deg.size() * gamma_deg.size()) throw std::logic_error("intensity table size mismatch");
  if (!std::is_sorted(c_deg.begin(), c_deg.end()) || c_deg.front() < 0.0 || c_deg.back() >= 360.0) {
    throw std::logic_error("C-planes must increase within [0, 360)");
  }
  if (!std::is_sorted(gamma_deg.begin(), gamma_deg.end()) || gamma_deg.front() < 0.0 || gamma_deg.back() > 180.0) {
    throw std::logic_error("gamma angles must increase within [0, 180]");
  }
}

}  // namespace roadbrdf::lighting

namespace roadbrdf::lighting {

double LuminousArea::projected_m2(double c, double gamma) const {
  constexpr double kDegree = 3.14159265358979323846 / 180.0;
  const double cos_c = std::cos(c * kDegree);
  const double sin_c = std::sin(c * kDegree);
  const double cos_g = std::cos(gamma * kDegree);
  const double sin_g = std::sin(gamma * kDegree);
  const double bottom = circular ? 0.25 * 3.14159265358979323846 * along_c0_m * along_c0_m : along_c0_m * along_c90_m;
  double side = 0.0;
  if (circular) {
    // The height of the cylinder's side towards C, between the two given heights of its quadrant.
    const double h_c = cos_c >= 0.0 ? heights_m[0] : heights_m[2];
    const double h_s = sin_c >= 0.0 ? heights_m[1] : heights_m[3];
    side = along_c0_m * (h_c * cos_c * cos_c + h_s * sin_c * sin_c);
  } else {
    side = along_c90_m * (heights_m[0] * std::max(cos_c, 0.0) + heights_m[2] * std::max(-cos_c, 0.0)) +
           along_c0_m * (heights_m[1] * std::max(sin_c, 0.0) + heights_m[3] * std::max(-sin_c, 0.0));
  }
  return bottom * std::max(cos_g, 0.0) + side * std::max(sin_g, 0.0);
}

}  // namespace roadbrdf::lighting
