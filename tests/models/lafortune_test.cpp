// Tests of the Lafortune model (Lafortune et al., SIGGRAPH 1997, eq. 4). Reference values: closed forms
// of the lobe base derived by hand at chosen geometries, the report's dry/wet road parameter sets
// (section 3.6, from Gimonet et al. 2015), and an independent numerical hemispherical integral.
#include "roadbrdf/models/lafortune.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

// Isotropic one-lobe parameters: kd, rho1, cx1, cz1, n1.
const std::vector<double> kDryRoad = {0.2, 0.3, -1.0, 1.0, 5.0};
const std::vector<double> kWetRoad = {0.2, 0.8, -1.0, 1.0, 15.0};

TEST(Lafortune, ParameterNamesAndCounts) {
  const auto iso1 = make_model("lafortune", {});
  std::vector<std::string> names;
  for (const auto& p : iso1->description().parameters) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"kd", "rho1", "cx1", "cz1", "n1"}));
  const auto aniso2 = make_model("lafortune", {{"lobes", "2"}, {"isotropic", "no"}});
  names.clear();
  for (const auto& p : aniso2->description().parameters) names.push_back(p.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"kd", "rho1", "cx1", "cy1", "cz1", "n1", "rho2", "cx2", "cy2", "cz2", "n2"}));
  const auto aniso4 = make_model("lafortune", {{"lobes", "4"}, {"isotropic", "no"}});
  EXPECT_EQ(aniso4->parameter_count(), static_cast<std::size_t>(Lafortune::kMaxParameters));
  EXPECT_EQ(make_model("lafortune", {{"lobes", "4"}})->parameter_count(), 17u);
  EXPECT_TRUE(iso1->description().reciprocal);
  EXPECT_FALSE(iso1->description().energy_conserving);
}

TEST(Lafortune, RejectsBadLobeCounts) {
  for (const char* bad : {"0", "5", "two", "1.5", ""}) {
    EXPECT_THROW(make_model("lafortune", {{"lobes", bad}}), InputError) << bad;
  }
  EXPECT_THROW(make_model("lafortune", {{"isotropic", "maybe"}}), InputError);
}

TEST(Lafortune, RoadSetsAtTheMirrorDirection) {
  // Mirror direction w_r = (-w_ix, -w_iy, w_iz) with C = (-1, -1, 1):
  // base = (-1)(-x)x + (-1)(-y)y + z z = sin^2(theta) cos^2(phi) + sin^2(theta) sin^2(phi) + cos^2(theta) = 1,
  // so f = k_d/pi + rho_s at any incidence: dry 0.2/pi + 0.3, wet 0.2/pi + 0.8.
  const auto m = make_model("lafortune", {});
  for (double ti : {0.0, 30.0, 70.0}) {
    const Geometry g = geometry_from_degrees(ti, 25.0, ti, 205.0);
    EXPECT_NEAR(m->evaluate(kDryRoad.data(), g), 0.2 / kPi + 0.3, 1e-14) << ti;
    EXPECT_NEAR(m->evaluate(kWetRoad.data(), g), 0.2 / kPi + 0.8, 1e-14) << ti;
  }
}

TEST(Lafortune, RoadSetsAtTheRetroDirection) {
  // Retro direction w_r = w_i: base = -sin^2(theta) + cos^2(theta) = cos(2 theta).
  // theta = 30: base = 1/2, dry: 0.2/pi + 0.3 / 2^5, wet: 0.2/pi + 0.8 / 2^15.
  // theta = 60: base = -1/2 < 0, the clamped lobe is 0 (the odd exponents 5, 15 would otherwise give a
  // negative BRDF): f = 0.2/pi.
  const auto m = make_model("lafortune", {});
  const Geometry g30 = geometry_from_degrees(30, 40, 30, 40);
  EXPECT_NEAR(m->evaluate(kDryRoad.data(), g30), 0.2 / kPi + 0.3 / 32.0, 1e-14);
  EXPECT_NEAR(m->evaluate(kWetRoad.data(), g30), 0.2 / kPi + 0.8 / 32768.0, 1e-14);
  const Geometry g60 = geometry_from_degrees(60, 40, 60, 40);
  EXPECT_EQ(m->evaluate(kDryRoad.data(), g60), 0.2 / kPi);
  EXPECT_EQ(m->evaluate(kWetRoad.data(), g60), 0.2 / kPi);
}

TEST(Lafortune, RoadSetsOffSpecular) {
  // theta_i = 40, theta_r = 20 in the plane of incidence, forward side (phi_i = 0, phi_r = 180):
  // base = sin40 sin20 + cos40 cos20 = cos(20 deg). Dry: 0.2/pi + 0.3 cos^5(20 deg) = 0.063662 + 0.219812.
  const auto m = make_model("lafortune", {});
  const Geometry g = geometry_from_degrees(40, 0, 20, 180);
  const double c = std::cos(20.0 * kDegree);
  EXPECT_NEAR(m->evaluate(kDryRoad.data(), g), 0.2 / kPi + 0.3 * std::pow(c, 5), 1e-14);
  EXPECT_NEAR(m->evaluate(kWetRoad.data(), g), 0.2 / kPi + 0.8 * std::pow(c, 15), 1e-14);
}

TEST(Lafortune, AnisotropicTwoLobes) {
  // Lobe 1 (C = (-2, -0.5, 1), n = 3), lobe 2 retro (C = (1, 1, 1), n = 2), at w_i = (theta 45, phi 0),
  // w_r = (theta 45, phi 90): w_i = (s, 0, s), w_r = (0, s, s) with s = 1/sqrt(2) (x of w_r rounds to 4e-17).
  // Lobe 1 base = -2*0 - 0.5*0 + s^2 = 1/2 -> 0.7 / 8; lobe 2 base = 0 + 0 + 1/2 -> 0.25 / 4.
  const auto m = make_model("lafortune", {{"lobes", "2"}, {"isotropic", "no"}});
  const std::vector<double> p = {0.1, 0.7, -2.0, -0.5, 1.0, 3.0, 0.25, 1.0, 1.0, 1.0, 2.0};
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(45, 0, 45, 90)), 0.1 / kPi + 0.7 / 8 + 0.25 / 4, 1e-14);
  // Mirror in the x-z plane: base1 = 2 s^2 + s^2 = 3/2 -> 0.7 * 3.375; base2 = -s^2 + s^2 = 0 -> 0.
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(45, 0, 45, 180)), 0.1 / kPi + 0.7 * 3.375, 1e-13);
  // Mirror in the y-z plane: base1 = 0.5 s^2 + s^2 = 3/4 -> 0.7 * 0.421875.
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(45, 90, 45, 270)), 0.1 / kPi + 0.7 * 0.421875, 1e-13);
}

TEST(Lafortune, CosineLobeAlbedo) {
  // Lobe C = (0, 0, 1), n = 1: f = rho cos(theta_i) cos(theta_r); directional albedo
  // rho cos(theta_i) int cos^2(theta_r) d omega = rho cos(theta_i) 2 pi / 3. Plus k_d from the Lambertian term.
  // Independent integral: composite Simpson in theta_r x trapezoid in phi_r.
  const auto m = make_model("lafortune", {});
  const std::vector<double> p = {0.25, 0.4, 0.0, 1.0, 1.0};
  const double theta_i = 50.0 * kDegree;
  const int n = 200, n_phi = 16;
  const double h = (kPi / 2) / n;
  double sum = 0.0;
  for (int a = 0; a <= n; ++a) {
    const double t = a * h;
    const double w = (a == 0 || a == n) ? 1.0 : (a % 2 == 1 ? 4.0 : 2.0);
    for (int b = 0; b < n_phi; ++b) {
      const double phi = 2.0 * kPi * b / n_phi;
      sum += w * m->evaluate(p.data(), geometry_from_radians(theta_i, 0.0, t, phi)) * std::cos(t) * std::sin(t) *
             (2.0 * kPi / n_phi);
    }
  }
  EXPECT_NEAR(sum * h / 3.0, 0.25 + 0.4 * std::cos(theta_i) * 2.0 * kPi / 3.0, 1e-9);
}

TEST(Lafortune, ReciprocalNonNegativeFinite) {
  const auto m = make_model("lafortune", {{"lobes", "3"}, {"isotropic", "no"}});
  const std::vector<double> p = {0.2, 0.3, -1.0, -0.8, 1.0, 5.0, 0.2, 1.0, 1.2, 0.9, 12.0, 1.0, 0.0, 0.0, 1.0, 0.0};
  const double thetas[] = {0.0, 15.0, 45.0, 80.0, 89.9, 90.0};
  const double phis[] = {0.0, 60.0, 180.0, 270.0};
  for (double ti : thetas) {
    for (double tr : thetas) {
      for (double pr : phis) {
        const Geometry g = geometry_from_degrees(ti, 10.0, tr, 10.0 + pr);
        const double f = m->evaluate(p.data(), g);
        EXPECT_TRUE(std::isfinite(f));
        EXPECT_GE(f, 0.0);
        EXPECT_NEAR(f, m->evaluate(p.data(), g.swapped()), 1e-14 * std::fmax(1.0, f));
      }
    }
  }
}

TEST(Lafortune, GradientMatchesFiniteDifferences) {
  const auto m = make_model("lafortune", {{"lobes", "4"}, {"isotropic", "no"}});
  const std::vector<double> p = {0.2,  0.3,  -1.0, -0.8, 1.0, 5.0,  0.2, 1.0, 1.2, 0.9, 12.0,
                                 0.15, -0.5, -0.6, 0.8,  2.5, 0.05, 0.1, 0.2, 1.1, 1.5};
  ASSERT_EQ(p.size(), m->parameter_count());
  for (const Geometry& g : {geometry_from_degrees(30, 0, 25, 170), geometry_from_degrees(10, 20, 15, 30),
                            geometry_from_degrees(0, 0, 0, 0), geometry_from_degrees(60, 0, 40, 100)}) {
    std::vector<double> grad(p.size());
    const double f = m->evaluate_with_gradient(p.data(), g, grad.data());
    EXPECT_NEAR(f, m->evaluate(p.data(), g), 1e-14 * std::fmax(1.0, f));
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double h = 1e-6;
      std::vector<double> up = p, down = p;
      up[k] += h;
      down[k] -= h;
      const double fd = (m->evaluate(up.data(), g) - m->evaluate(down.data(), g)) / (2.0 * h);
      EXPECT_NEAR(grad[k], fd, 1e-7 * std::fmax(1.0, std::fabs(fd))) << "parameter " << k;
    }
  }
}

// The adapter differentiates a one-lobe Lafortune (5 parameters) with 8-wide jets and a two-lobe one
// (9 parameters) with kMaxParameters-wide ones (model.h, with_jet_size). A second lobe of amplitude 0
// adds exactly 0 to the value and to the first lobe's derivatives, so both give the same numbers, bit
// for bit, for kd and the first lobe, through every gradient path.
TEST(Lafortune, GradientsDoNotDependOnTheJetSize) {
  const auto one = make_model("lafortune", {});
  const auto two = make_model("lafortune", {{"lobes", "2"}});
  ASSERT_EQ(one->parameter_count(), 5u);
  ASSERT_EQ(two->parameter_count(), 9u);
  std::vector<double> p2 = kDryRoad;
  p2.insert(p2.end(), {0.0, -0.8, 1.0, 3.0});  // rho2 = 0
  std::vector<Geometry> geometries;
  for (double ti : {0.0, 20.0, 60.0, 85.0}) {
    for (double tr : {5.0, 45.0, 80.0}) {
      for (double dp : {0.0, 90.0, 180.0}) geometries.push_back(geometry_from_degrees(ti, 0.0, tr, dp));
    }
  }
  const std::size_t n = geometries.size();
  std::vector<double> g1(5), g2(9);
  for (const Geometry& g : geometries) {
    EXPECT_EQ(one->evaluate_with_gradient(kDryRoad.data(), g, g1.data()),
              two->evaluate_with_gradient(p2.data(), g, g2.data()));
    for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(g1[k], g2[k]) << k;
  }
  std::vector<double> v1(n), v2(n), j1(n * 5), j2(n * 9);
  one->evaluate_batch_with_gradient(geometries.data(), n, kDryRoad.data(), v1.data(), j1.data());
  two->evaluate_batch_with_gradient(geometries.data(), n, p2.data(), v2.data(), j2.data());
  const auto prepared1 = one->prepare(geometries.data(), n);
  const auto prepared2 = two->prepare(geometries.data(), n);
  std::vector<double> pv1(n), pv2(n), pj1(n * 5), pj2(n * 9);
  one->evaluate_prepared_with_gradient(*prepared1, kDryRoad.data(), pv1.data(), pj1.data());
  two->evaluate_prepared_with_gradient(*prepared2, p2.data(), pv2.data(), pj2.data());
  for (std::size_t m = 0; m < n; ++m) {
    EXPECT_EQ(v1[m], v2[m]);
    EXPECT_EQ(pv1[m], pv2[m]);
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_EQ(j1[m * 5 + k], j2[m * 9 + k]) << m << ' ' << k;
      EXPECT_EQ(pj1[m * 5 + k], pj2[m * 9 + k]) << m << ' ' << k;
    }
  }
}

}  // namespace
}  // namespace roadbrdf
