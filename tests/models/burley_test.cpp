// Burley (Disney) model (models/burley.h): closed forms of Burley 2012 at special geometries,
// consistency between distributions, reciprocity, finiteness, gradients vs finite differences.
#include "roadbrdf/models/burley.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

TEST(Burley, RegisteredNotEnergyConserving) {
  auto m = make_model("burley");
  const auto& d = m->description();
  EXPECT_FALSE(d.energy_conserving);
  ASSERT_EQ(d.parameters.size(), 4u);
  EXPECT_EQ(d.parameters[0].name, "albedo");
  EXPECT_EQ(d.parameters[1].name, "roughness");
  EXPECT_EQ(d.parameters[2].name, "specular");
  EXPECT_EQ(d.parameters[3].name, "ior");
  auto gtr = make_model("burley", {{"distribution", "gtr"}});
  ASSERT_EQ(gtr->description().parameters.size(), 5u);
  EXPECT_EQ(gtr->description().parameters[4].name, "gtr_gamma");
}

TEST(Burley, NormalIncidenceClosedForm) {
  // l = v = n: (1 - cos)^5 = 0, so f_d = rho/pi; h = n: D_GGX = 1/(pi alpha^2), G = 1, F = F0.
  const Geometry g = geometry_from_degrees(0, 0, 0, 0);
  auto m = make_model("burley");
  const double r = 0.6, alpha = r * r, n = 1.5;
  const double f0 = std::pow((n - 1) / (n + 1), 2);
  const double p[] = {0.3, r, 0.8, n};
  EXPECT_NEAR(m->evaluate(p, g), 0.3 / kPi + 0.8 * f0 / (4.0 * kPi * alpha * alpha), 1e-12);
}

TEST(Burley, DiffuseRetroReflectionClosedForm) {
  // Specular weight 0; w_i = w_r at theta: h = w_i, cos theta_d = 1, F_D90 = 0.5 + 2 r, and
  // f = rho/pi (1 + (F_D90 - 1)(1 - cos theta)^5)^2 (Burley 2012 section 5.3).
  auto m = make_model("burley");
  for (double r : {0.1, 0.5, 1.0}) {
    for (double deg : {30.0, 60.0, 85.0}) {
      const double c = std::cos(deg * kDegree);
      const double fd90 = 0.5 + 2.0 * r;
      const double expected = 0.5 / kPi * std::pow(1.0 + (fd90 - 1.0) * std::pow(1.0 - c, 5), 2);
      const double p[] = {0.5, r, 0.0, 1.5};
      EXPECT_NEAR(m->evaluate(p, geometry_from_degrees(deg, 20, deg, 20)), expected, 1e-13) << r << ' ' << deg;
    }
  }
  // Towards the grazing retro direction (l = v horizontal): (1 - cos)^5 -> 1 and cos theta_d = 1, so each
  // factor tends to F_D90 = 0.5 + 2 r: for a smooth surface about 1/4 of Lambert (Burley's grazing
  // darkening). Exactly there the value is the declared 0 (grazing_zero).
  const double p[] = {1.0, 0.02, 0.0, 1.5};
  const double fd90 = 0.5 + 2.0 * 0.02;
  EXPECT_NEAR(m->evaluate(p, geometry_from_degrees(90.0 - 1e-7, 0, 90, 0)), std::pow(fd90, 2) / kPi, 1e-9);
  EXPECT_EQ(m->evaluate(p, geometry_from_degrees(90, 0, 90, 0)), 0.0);
}

TEST(Burley, SpecularMirrorClosedForm) {
  // Mirror geometry theta_i = theta_r = t: h = n, l.h = cos t; Schlick F; D_GGX(n) = 1/(pi alpha^2);
  // uncorrelated Smith-GGX G1 = 2 cos / (cos + sqrt(alpha^2 + (1 - alpha^2) cos^2)) (Walter 2007 eq. 34).
  auto m = make_model("burley");
  const double r = 0.4, alpha = r * r, n = 1.5;
  const double f0 = std::pow((n - 1) / (n + 1), 2);
  for (double deg : {15.0, 50.0, 80.0}) {
    const double c = std::cos(deg * kDegree);
    const double F = f0 + (1 - f0) * std::pow(1 - c, 5);
    const double g1 = 2 * c / (c + std::sqrt(alpha * alpha + (1 - alpha * alpha) * c * c));
    const double spec = F * g1 * g1 / (kPi * alpha * alpha) / (4 * c * c);
    const double fd90 = 0.5 + 2 * r * c * c;
    const double diff = 0.2 / kPi * std::pow(1 + (fd90 - 1) * std::pow(1 - c, 5), 2);
    const double p[] = {0.2, r, 1.0, n};
    const double f = m->evaluate(p, geometry_from_degrees(deg, 0, deg, 180));
    EXPECT_NEAR(f, diff + spec, 1e-11 * (diff + spec)) << deg;
  }
}

TEST(Burley, GtrGammaTwoIsGgxAndGammaOneIsBerry) {
  auto ggx = make_model("burley");
  auto berry = make_model("burley", {{"distribution", "berry"}});
  auto gtr = make_model("burley", {{"distribution", "gtr"}});
  for (auto a : std::vector<std::array<double, 4>>{{20, 0, 40, 180}, {60, 0, 10, 90}, {80, 0, 80, 170}}) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const double p2[] = {0.4, 0.5, 1.0, 1.5, 2.0};
    const double p1[] = {0.4, 0.5, 1.0, 1.5, 1.0};
    EXPECT_NEAR(gtr->evaluate(p2, g), ggx->evaluate(p2, g), 1e-12 * ggx->evaluate(p2, g));
    EXPECT_NEAR(gtr->evaluate(p1, g), berry->evaluate(p1, g), 1e-12 * berry->evaluate(p1, g));
  }
}

TEST(Burley, FiniteReciprocalNonNegative) {
  const std::vector<Geometry> geometries = {
      geometry_from_degrees(0, 0, 0, 0),     geometry_from_degrees(89.9, 0, 89.9, 180),
      geometry_from_degrees(90, 0, 90, 180), geometry_from_degrees(90, 0, 30, 180),
      geometry_from_degrees(90, 0, 90, 0),   geometry_from_degrees(45, 0, 45, 180),
      geometry_from_degrees(45, 0, 45, 0),   geometry_from_degrees(20, 0, 75, 100),
  };
  for (std::string dist : {"ggx", "berry", "gtr"}) {
    auto m = make_model("burley", {{"distribution", dist}});
    for (double r : {0.02, 0.5, 1.0}) {
      for (double gamma : {0.5, 1.0, 4.0}) {
        const double p[] = {0.7, r, 1.0, 1.5, gamma};
        for (const auto& g : geometries) {
          const double f = m->evaluate(p, g);
          EXPECT_TRUE(std::isfinite(f)) << dist << ' ' << r;
          EXPECT_GE(f, 0.0);
          EXPECT_NEAR(f, m->evaluate(p, g.swapped()), 1e-12 * (1 + f));
        }
      }
    }
  }
}

TEST(Burley, GradientMatchesFiniteDifferences) {
  const std::vector<Geometry> geometries = {geometry_from_degrees(30, 0, 50, 170), geometry_from_degrees(70, 0, 60, 20),
                                            geometry_from_degrees(0, 0, 80, 0)};
  for (std::string dist : {"ggx", "berry", "gtr"}) {
    auto m = make_model("burley", {{"distribution", dist}});
    const std::size_t n = m->parameter_count();
    for (double gamma : {1.0, 1.7}) {
      std::vector<double> p = {0.6, 0.45, 0.9, 1.6, gamma};
      p.resize(n);
      for (const auto& g : geometries) {
        std::vector<double> grad(n);
        m->evaluate_with_gradient(p.data(), g, grad.data());
        for (std::size_t k = 0; k < n; ++k) {
          const double h = 1e-6;
          std::vector<double> hi = p, lo = p;
          hi[k] += h;
          lo[k] -= h;
          const double fd = (m->evaluate(hi.data(), g) - m->evaluate(lo.data(), g)) / (2 * h);
          EXPECT_NEAR(grad[k], fd, 1e-5 * (1.0 + std::fabs(fd))) << dist << " param " << k;
        }
      }
    }
  }
}

}  // namespace
}  // namespace roadbrdf
