// The flux integral of an intensity distribution (lighting/luminaire_flux.h) against closed forms:
// a constant intensity I over the lower hemisphere emits 2 pi I, I0 cos(gamma) emits pi I0, and the
// interpolant of a tabulated I0 cos(gamma) has its own closed form (computed here independently, by a
// Gauss-Legendre rule over each interval). Also the luminous area's projection (luminaire.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/luminaire_flux.h"
#include "support/reference_quadrature.h"

namespace roadbrdf::lighting {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (double x = from; x <= to + 1e-9; x += step) out.push_back(x);
  return out;
}

IntensityDistribution tabulate(const std::vector<double>& c, const std::vector<double>& gamma,
                               double (*f)(double, double)) {
  IntensityDistribution d;
  d.c_deg = c;
  d.gamma_deg = gamma;
  for (const double ci : c) {
    for (const double g : gamma) d.candela.push_back(f(ci, g));
  }
  return d;
}

TEST(LuminaireFlux, ConstantIntensityOverTheLowerHemisphereEmitsTwoPiI) {
  const auto constant = [](double, double) { return 500.0; };
  // Every C-plane layout: one plane (rotational), a regular circle, an irregular one.
  for (const std::vector<double>& c :
       {std::vector<double>{0.0}, steps(0.0, 345.0, 15.0), std::vector<double>{0.0, 10.0, 50.0, 90.0, 200.0, 350.0}}) {
    const LuminousFlux flux = luminous_flux(tabulate(c, steps(0.0, 90.0, 5.0), constant));
    EXPECT_NEAR(flux.downward_lm, 2.0 * kPi * 500.0, 1e-9 * 2.0 * kPi * 500.0);
    EXPECT_EQ(flux.upward_lm, 0.0);
  }
  // The whole sphere: 4 pi I, split equally at the horizontal even when 90 deg is no tabulated angle.
  const LuminousFlux sphere = luminous_flux(tabulate({0.0, 120.0, 240.0}, {0.0, 70.0, 100.0, 180.0}, constant));
  EXPECT_NEAR(sphere.downward_lm, 2.0 * kPi * 500.0, 1e-9);
  EXPECT_NEAR(sphere.upward_lm, 2.0 * kPi * 500.0, 1e-9);
}

TEST(LuminaireFlux, CosineIntensityEmitsPiI0WithinTheInterpolationError) {
  const auto cosine = [](double, double g) { return 1000.0 * std::cos(g * kPi / 180.0); };
  for (const double step : {5.0, 2.5, 1.0}) {
    const LuminousFlux flux = luminous_flux(tabulate(steps(0.0, 345.0, 15.0), steps(0.0, 90.0, step), cosine));
    // Linear interpolation of cos between nodes h apart errs by at most h^2/8 (of I0), and on average
    // by h^2/12 below it: the flux is pi I0 (1 - O(h^2 / 12)).
    const double h = step * kPi / 180.0;
    EXPECT_LT(flux.downward_lm, kPi * 1000.0);
    EXPECT_GT(flux.downward_lm, kPi * 1000.0 * (1.0 - h * h / 8.0));
  }
}

TEST(LuminaireFlux, IsTheExactIntegralOfTheInterpolant) {
  // An irregular grid and a distribution varying in C and gamma: the flux equals an independent
  // quadrature of IntensityDistribution::intensity() itself, plane interval by plane interval.
  const auto f = [](double c, double g) {
    return 100.0 + 80.0 * std::cos(g * kPi / 180.0) * (1.0 + 0.5 * std::cos(c * kPi / 180.0)) + g;
  };
  const IntensityDistribution d = tabulate({10.0, 40.0, 95.0, 180.0, 300.0}, {0.0, 20.0, 65.0, 85.0, 120.0, 170.0}, f);
  std::vector<double> x, w;
  test::gauss_legendre_01(8, x, w);  // exact for the degree-1 pieces times sin at this width to ~1e-12
  double down = 0.0, up = 0.0;
  const std::vector<double> c_edges = {10.0, 40.0, 95.0, 180.0, 300.0, 370.0};
  const std::vector<double> g_edges = {0.0, 20.0, 65.0, 85.0, 90.0, 120.0, 170.0};
  for (std::size_t i = 0; i + 1 < c_edges.size(); ++i) {
    for (std::size_t j = 0; j + 1 < g_edges.size(); ++j) {
      const double dc = (c_edges[i + 1] - c_edges[i]) * kPi / 180.0;
      const double dg = (g_edges[j + 1] - g_edges[j]) * kPi / 180.0;
      for (std::size_t a = 0; a < x.size(); ++a) {
        for (std::size_t b = 0; b < x.size(); ++b) {
          const double c = c_edges[i] + x[a] * (c_edges[i + 1] - c_edges[i]);
          const double g = g_edges[j] + x[b] * (g_edges[j + 1] - g_edges[j]);
          const double v = w[a] * w[b] * dc * dg * d.intensity(c, g) * std::sin(g * kPi / 180.0);
          (g_edges[j] < 90.0 ? down : up) += v;
        }
      }
    }
  }
  const LuminousFlux flux = luminous_flux(d);
  EXPECT_NEAR(flux.downward_lm, down, 1e-9 * down);
  EXPECT_NEAR(flux.upward_lm, up, 1e-9 * up);
}

TEST(LuminousArea, ProjectionOfARectangleAndADisc) {
  LuminousArea rect;
  rect.along_c0_m = 0.5;
  rect.along_c90_m = 1.0;
  rect.heights_m = {0.1, 0.2, 0.3, 0.4};
  EXPECT_NEAR(rect.projected_m2(0.0, 0.0), 0.5, 1e-12);  // seen from below: the bottom face
  // Horizontal views: the side faces, (C90 side) h_C0 towards C0, (C0 side) h_C90 towards C90, ...
  EXPECT_NEAR(rect.projected_m2(0.0, 90.0), 1.0 * 0.1, 1e-12);
  EXPECT_NEAR(rect.projected_m2(90.0, 90.0), 0.5 * 0.2, 1e-12);
  EXPECT_NEAR(rect.projected_m2(180.0, 90.0), 1.0 * 0.3, 1e-12);
  EXPECT_NEAR(rect.projected_m2(270.0, 90.0), 0.5 * 0.4, 1e-12);
  // A box seen obliquely: the faces towards the viewer, by cos C and sin C.
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(rect.projected_m2(45.0, 60.0), 0.5 * 0.5 + std::sin(kPi / 3.0) * (1.0 * 0.1 * s + 0.5 * 0.2 * s), 1e-12);
  LuminousArea disc;
  disc.along_c0_m = 0.4;
  disc.circular = true;
  disc.heights_m = {0.05, 0.05, 0.05, 0.05};
  // A cylinder: pi D^2 / 4 cos(gamma) + D h sin(gamma), the same from every azimuth.
  for (const double c : {0.0, 30.0, 135.0, 290.0}) {
    EXPECT_NEAR(disc.projected_m2(c, 70.0),
                kPi * 0.04 * std::cos(70.0 * kPi / 180.0) + 0.4 * 0.05 * std::sin(70.0 * kPi / 180.0), 1e-12);
  }
  EXPECT_EQ(LuminousArea{}.projected_m2(10.0, 20.0), 0.0);
}

}  // namespace
}  // namespace roadbrdf::lighting
