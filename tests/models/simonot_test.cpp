// Tests of the flat interfaced-Lambertian (Simonot 2009) model. Reference values: the closed form of
// the hemispherical Fresnel reflectance of a dielectric (below), Fresnel closed forms at normal
// incidence and at the Brewster angle, and independent numerical hemispherical integrals.
#include "roadbrdf/models/simonot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

std::unique_ptr<Model> make() { return make_model("simonot", {}); }

// Hemispherical (diffuse-illumination) reflectance of a dielectric interface seen from the low-index side,
// r01 = int_0^{pi/2} R(theta) sin(2 theta) d theta, in closed form for n > 1 (Walsh 1926; Judd 1942; the
// form quoted by Egan & Hilgeman, "Optical properties of inhomogeneous materials", 1979):
//   r = 1/2 + (n-1)(3n+1)/(6(n+1)^2) + n^2 (n^2-1)^2/(n^2+1)^3 ln((n-1)/(n+1))
//       - 2 n^3 (n^2+2n-1)/((n^2+1)(n^4-1)) + 8 n^4 (n^4+1)/((n^2+1)(n^4-1)^2) ln n.
// (n = 1.5 gives 0.0918, the familiar "9 % diffuse reflectance of glass".)
double hemispherical_fresnel_closed_form(double n) {
  const double n2 = n * n, n4 = n2 * n2;
  return 0.5 + (n - 1) * (3 * n + 1) / (6 * (n + 1) * (n + 1)) +
         n2 * (n2 - 1) * (n2 - 1) / std::pow(n2 + 1, 3) * std::log((n - 1) / (n + 1)) -
         2 * n2 * n * (n2 + 2 * n - 1) / ((n2 + 1) * (n4 - 1)) +
         8 * n4 * (n4 + 1) / ((n2 + 1) * (n4 - 1) * (n4 - 1)) * std::log(n);
}

// Smooth-part directional albedo int f cos(theta_r) d omega_r: composite Simpson in theta_r (2000
// intervals) times the trapezoid rule in phi_r (the integrand does not depend on phi_r; 4 nodes suffice).
double smooth_albedo(const Model& m, const std::vector<double>& p, double theta_i) {
  const int n = 2000, n_phi = 4;
  const double h = (kPi / 2) / n;
  double sum = 0.0;
  for (int a = 0; a <= n; ++a) {
    const double t = a * h;
    const double w = (a == 0 || a == n) ? 1.0 : (a % 2 == 1 ? 4.0 : 2.0);
    double ring = 0.0;
    for (int b = 0; b < n_phi; ++b) {
      ring += m.evaluate(p.data(), geometry_from_radians(theta_i, 0.3, t, 2.0 * kPi * (b + 0.5) / n_phi));
    }
    sum += w * ring * (2.0 * kPi / n_phi) * std::cos(t) * std::sin(t);
  }
  return sum * h / 3.0;
}

TEST(Simonot, DescriptionHasDeltaPart) {
  const auto m = make();
  const auto& d = m->description();
  EXPECT_EQ(d.name, "simonot");
  ASSERT_EQ(d.parameters.size(), 2u);
  EXPECT_EQ(d.parameters[0].name, "albedo");
  EXPECT_EQ(d.parameters[1].name, "ior");
  EXPECT_TRUE(d.has_delta);
  EXPECT_TRUE(d.reciprocal);
}

TEST(Simonot, HemisphericalFresnelQuadratureMatchesClosedForm) {
  for (double n : {1.05, 1.2, 1.5, 2.0, 2.5, 3.0}) {
    EXPECT_NEAR(simonot_detail::hemispherical_fresnel(n), hemispherical_fresnel_closed_form(n), 1e-12) << n;
  }
  EXPECT_NEAR(hemispherical_fresnel_closed_form(1.5), 0.0918, 1e-4);
  EXPECT_NEAR(simonot_detail::hemispherical_fresnel(1.0), 0.0, 1e-15);
}

TEST(Simonot, DeltaReflectanceIsFresnel) {
  const auto m = make();
  const std::vector<double> p = {0.5, 1.5};
  // Normal incidence: ((n - 1)/(n + 1))^2 = 0.04.
  EXPECT_NEAR(m->delta_reflectance(p.data(), 1.0), 0.04, 1e-15);
  // Grazing: total reflection.
  EXPECT_NEAR(m->delta_reflectance(p.data(), 0.0), 1.0, 1e-15);
  // Brewster angle tan(theta_B) = n: R_p = 0, R_s = sin^2(theta_B - theta_t) with theta_t = 90 - theta_B,
  // so R_s = cos^2(2 theta_B) = ((1 - n^2)/(1 + n^2))^2 and R = R_s / 2.
  const double cos_b = 1.0 / std::sqrt(1.0 + 1.5 * 1.5);
  EXPECT_NEAR(m->delta_reflectance(p.data(), cos_b), 0.5 * std::pow((1 - 2.25) / (1 + 2.25), 2), 1e-15);
}

TEST(Simonot, ClosedFormAtNormalIncidence) {
  // theta_i = theta_r = 0: 1 - R01 = 0.96; r10 = 1 - (1 - r01)/n^2 with r01 from the closed form.
  const auto m = make();
  const double rho = 0.5, n = 1.5;
  const std::vector<double> p = {rho, n};
  const double r10 = 1.0 - (1.0 - hemispherical_fresnel_closed_form(n)) / (n * n);
  const double expected = rho / (n * n) * 0.96 * 0.96 / (kPi * (1.0 - rho * r10));
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(0, 0, 0, 0)), expected, 1e-13);
}

TEST(Simonot, IndexOneIsLambertian) {
  // eta_1 = eta_0: no interface, R01 = 0, r10 = 0, f = rho/pi at every geometry.
  const auto m = make();
  const std::vector<double> p = {0.37, 1.0};
  for (double ti : {0.0, 30.0, 75.0, 89.9}) {
    EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(ti, 0, 50, 123)), 0.37 / kPi, 1e-14);
  }
}

TEST(Simonot, WhiteBackgroundConservesEnergy) {
  // rho = 1: a flat interface over a white Lambertian absorbs nothing, so smooth albedo + R01(theta_i) = 1.
  const auto m = make();
  for (double n : {1.2, 1.5, 2.5}) {
    const std::vector<double> p = {1.0, n};
    for (double ti_deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
      const double ti = ti_deg * kDegree;
      const double total = smooth_albedo(*m, p, ti) + m->delta_reflectance(p.data(), std::cos(ti));
      EXPECT_NEAR(total, 1.0, 1e-9) << "n " << n << " theta_i " << ti_deg;
    }
  }
}

TEST(Simonot, GreyBackgroundAlbedoBelowOneAndMatchesClosedForm) {
  // Albedo = R + (1 - R) rho (1 - r10)/(1 - rho r10) (geometric series of background/interface bounces).
  const auto m = make();
  const double rho = 0.4, n = 1.6;
  const std::vector<double> p = {rho, n};
  const double r10 = 1.0 - (1.0 - hemispherical_fresnel_closed_form(n)) / (n * n);
  for (double ti_deg : {0.0, 45.0, 80.0}) {
    const double ti = ti_deg * kDegree;
    const double r = m->delta_reflectance(p.data(), std::cos(ti));
    const double total = smooth_albedo(*m, p, ti) + r;
    EXPECT_NEAR(total, r + (1 - r) * rho * (1 - r10) / (1 - rho * r10), 1e-9) << ti_deg;
    EXPECT_LT(total, 1.0);
  }
}

TEST(Simonot, ReciprocalNonNegativeFinite) {
  const auto m = make();
  const std::vector<std::vector<double>> sets = {{0.0, 1.0}, {1.0, 3.0}, {0.5, 1.5}, {1.0, 1.0}};
  const double thetas[] = {0.0, 20.0, 60.0, 89.9, 90.0};
  for (const auto& p : sets) {
    for (double ti : thetas) {
      for (double tr : thetas) {
        for (double dphi : {0.0, 180.0}) {  // exact retro and, for ti == tr, exact mirror
          const Geometry g = geometry_from_degrees(ti, 0.0, tr, dphi);
          const double f = m->evaluate(p.data(), g);
          EXPECT_TRUE(std::isfinite(f));
          EXPECT_GE(f, 0.0);
          EXPECT_NEAR(f, m->evaluate(p.data(), g.swapped()), 1e-15);
        }
      }
    }
  }
  // Grazing: 1 - R01(90 deg) = 0, the smooth part vanishes (when the index differs from 1).
  const std::vector<double> p = {0.5, 1.5};
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(90, 0, 30, 0)), 0.0, 1e-15);
}

TEST(Simonot, GradientMatchesFiniteDifferences) {
  const auto m = make();
  const std::vector<double> p = {0.6, 1.55};
  for (const Geometry& g : {geometry_from_degrees(0, 0, 0, 0), geometry_from_degrees(35, 0, 70, 180),
                            geometry_from_degrees(80, 0, 10, 20), geometry_from_degrees(89.9, 0, 45, 90)}) {
    double grad[2];
    const double f = m->evaluate_with_gradient(p.data(), g, grad);
    EXPECT_NEAR(f, m->evaluate(p.data(), g), 1e-15);
    for (int k = 0; k < 2; ++k) {
      const double h = 1e-6;
      std::vector<double> up = p, down = p;
      up[k] += h;
      down[k] -= h;
      const double fd = (m->evaluate(up.data(), g) - m->evaluate(down.data(), g)) / (2.0 * h);
      EXPECT_NEAR(grad[k], fd, 1e-7 * std::fmax(1.0, std::fabs(fd))) << "parameter " << k;
    }
  }
}

}  // namespace
}  // namespace roadbrdf
