// Rahman-Pinty-Verstraete model ("rpv").
//
// Independent references: the paper's equations (Rahman, Pinty & Verstraete, JGR 98(D11):20791, 1993)
// written again here from the spherical angles, in the paper's own form (phase angle g from
// its cosine, F with cos(pi - g), G from the tangents), and closed forms derived by hand: the nadir, the
// hot spot, and the Lambertian special case rho0 = 1, k = 1, Theta = 0 (rho = 1 everywhere).
#include "roadbrdf/models/rpv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

// The paper's reflectance factor at zenith angles t1 (sun), t2 (view) and relative azimuth phi (radians;
// phi = 0: sun and viewer on the same side, the backscattering direction).
double paper_rho(double rho0, double k, double big_theta, double t1, double t2, double phi) {
  const double c1 = std::cos(t1), c2 = std::cos(t2);
  const double m = std::pow(c1, k - 1.0) * std::pow(c2, k - 1.0) / std::pow(c1 + c2, 1.0 - k);
  const double g = std::acos(std::fmin(1.0, c1 * c2 + std::sin(t1) * std::sin(t2) * std::cos(phi)));
  const double f =
      (1.0 - big_theta * big_theta) / std::pow(1.0 + big_theta * big_theta - 2.0 * big_theta * std::cos(kPi - g), 1.5);
  const double tan1 = std::tan(t1), tan2 = std::tan(t2);
  const double big_g = std::sqrt(std::fmax(0.0, tan1 * tan1 + tan2 * tan2 - 2.0 * tan1 * tan2 * std::cos(phi)));
  const double one_plus_r = 1.0 + (1.0 - rho0) / (1.0 + big_g);
  return rho0 * m * f * one_plus_r;
}

double deg(double d) { return d * kPi / 180.0; }

// roadbrdf geometry with theta_i = sun, theta_r = view, dphi = phi_r - phi_i [deg].
Geometry at(double theta_i, double theta_r, double dphi) {
  return geometry_from_degrees(theta_i, 25.0, theta_r, 25.0 + dphi);
}

TEST(Rpv, NamesAndFlags) {
  const auto model = make_model("rpv");
  const ModelDescription& d = model->description();
  ASSERT_EQ(d.parameters.size(), 3u);
  EXPECT_EQ(d.parameters[0].name, "rho0");
  EXPECT_EQ(d.parameters[1].name, "k");
  EXPECT_EQ(d.parameters[2].name, "Theta");
  EXPECT_TRUE(d.reciprocal);
  EXPECT_TRUE(d.non_negative);
  EXPECT_TRUE(d.isotropic);
  EXPECT_FALSE(d.energy_conserving);
  EXPECT_NE(d.citation.find("Rahman"), std::string::npos);
}

// The paper's formula at many geometries and parameter sets, BRDF = rho / pi.
TEST(Rpv, EqualsThePaperFormula) {
  const auto model = make_model("rpv");
  const std::vector<std::vector<double>> parameter_sets = {
      {0.3, 0.8, -0.1}, {0.05, 0.5, -0.3}, {0.6, 1.2, 0.2}, {1.0, 0.0, -0.9}, {0.2, 2.0, 0.9}};
  int checked = 0;
  for (const auto& p : parameter_sets) {
    for (double ti : {0.0, 10.0, 35.0, 60.0, 80.0, 89.0}) {
      for (double tr : {0.0, 20.0, 45.0, 70.0, 88.0}) {
        for (double dphi : {0.0, 30.0, 90.0, 150.0, 180.0, 270.0}) {
          const double expected = paper_rho(p[0], p[1], p[2], deg(ti), deg(tr), deg(dphi)) / kPi;
          const double got = model->evaluate(p.data(), at(ti, tr, dphi));
          EXPECT_NEAR(got, expected, 1e-10 * std::fabs(expected) + 1e-14)
              << "rho0=" << p[0] << " k=" << p[1] << " Theta=" << p[2] << " at " << ti << ", " << tr << ", " << dphi;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 5 * 6 * 5 * 6);
}

// Nadir sun and view: M = 2^(k-1), g = 0, F = (1 - Theta) / (1 + Theta)^2, G = 0 so 1 + R = 2 - rho0.
TEST(Rpv, NadirClosedForm) {
  const auto model = make_model("rpv");
  const double p[] = {0.25, 0.7, -0.2};
  const double expected =
      0.25 * std::pow(2.0, 0.7 - 1.0) * (1.0 + 0.2) / ((1.0 - 0.2) * (1.0 - 0.2)) * (2.0 - 0.25) / kPi;
  EXPECT_NEAR(model->evaluate(p, at(0.0, 0.0, 0.0)), expected, 1e-14);
}

// The hot spot theta_i = theta_r = t, dphi = 0 (the retro side): G = 0 and g = 0, so
// rho = rho0 cos^(2k-2)(t) (2 cos t)^(k-1) (1 - Theta)/(1 + Theta)^2 (2 - rho0); it is the maximum over
// dphi for backward-scattering Theta < 0 (F and 1 + R both largest there).
TEST(Rpv, HotSpotClosedFormAndPeak) {
  const auto model = make_model("rpv");
  const double rho0 = 0.15, k = 0.9, big_theta = -0.25;
  const double p[] = {rho0, k, big_theta};
  for (double t : {15.0, 40.0, 65.0}) {
    const double c = std::cos(deg(t));
    const double expected = rho0 * std::pow(c, 2.0 * k - 2.0) * std::pow(2.0 * c, k - 1.0) * (1.0 - big_theta) /
                            ((1.0 + big_theta) * (1.0 + big_theta)) * (2.0 - rho0) / kPi;
    const double hot = model->evaluate(p, at(t, t, 0.0));
    EXPECT_NEAR(hot, expected, 1e-13) << t;
    for (double dphi : {5.0, 45.0, 90.0, 180.0}) EXPECT_LT(model->evaluate(p, at(t, t, dphi)), hot) << t << " " << dphi;
  }
  // Forward scattering Theta > 0: the specular side (dphi = 180 deg) is brighter than the retro side
  // away from the hot spot's peak (here with rho0 = 1, which switches the hot spot off).
  const double forward[] = {1.0, 1.0, 0.4};
  EXPECT_GT(model->evaluate(forward, at(50.0, 50.0, 180.0)), model->evaluate(forward, at(50.0, 50.0, 0.0)));
}

// rho0 = 1, k = 1, Theta = 0: M = 1, F = 1, R = 0, so rho = 1 and the BRDF is the Lambertian 1/pi.
TEST(Rpv, ReducesToLambertianWhiteSurface) {
  const auto model = make_model("rpv");
  const double p[] = {1.0, 1.0, 0.0};
  for (double ti : {0.0, 30.0, 75.0, 89.9})
    for (double tr : {0.0, 50.0, 89.9})
      for (double dphi : {0.0, 120.0, 180.0}) EXPECT_NEAR(model->evaluate(p, at(ti, tr, dphi)), kInvPi, 1e-15);
}

// The dphi convention: dphi = 0 is the paper's phi = 0 (sun and viewer on the same side, G = |tan_i -
// tan_r|), so the paper's formula with phi = 0 matches dphi = 0, and with phi = pi matches dphi = 180 deg.
TEST(Rpv, AzimuthConventionMatchesThePaper) {
  const auto model = make_model("rpv");
  const double p[] = {0.2, 0.75, -0.3};
  const double retro = model->evaluate(p, at(30.0, 40.0, 0.0));
  const double forward = model->evaluate(p, at(30.0, 40.0, 180.0));
  EXPECT_NEAR(retro, paper_rho(0.2, 0.75, -0.3, deg(30.0), deg(40.0), 0.0) / kPi, 1e-14);
  EXPECT_NEAR(forward, paper_rho(0.2, 0.75, -0.3, deg(30.0), deg(40.0), kPi) / kPi, 1e-14);
  EXPECT_GT(retro, forward);  // Theta < 0 and the hot spot: the retro side is brighter
}

// Exactly grazing directions (90 deg): k < 1 diverges (cos^(k-1)) and k > 1 tends to 0; both give 0. With
// k = 1 the value is the limit rho0 F(g) / pi (G grows without bound, so 1 + R -> 1).
TEST(Rpv, ExactlyGrazingDirections) {
  const auto model = make_model("rpv");
  const double bowl[] = {0.3, 0.6, -0.2};
  const double bell[] = {0.3, 1.4, -0.2};
  for (double other : {0.0, 45.0, 90.0}) {
    for (double dphi : {0.0, 90.0, 180.0}) {
      EXPECT_EQ(model->evaluate(bowl, at(90.0, other, dphi)), 0.0);
      EXPECT_EQ(model->evaluate(bowl, at(other, 90.0, dphi)), 0.0);
      EXPECT_EQ(model->evaluate(bell, at(90.0, other, dphi)), 0.0);
      EXPECT_EQ(model->evaluate(bell, at(other, 90.0, dphi)), 0.0);
    }
  }
  // k < 1 just below the horizon: large but finite, growing like cos^(k-1) (here cos^(-0.4) per direction).
  const double near = model->evaluate(bowl, at(89.999, 30.0, 90.0));
  const double nearer = model->evaluate(bowl, at(89.99999, 30.0, 90.0));
  EXPECT_TRUE(std::isfinite(nearer));
  EXPECT_NEAR(nearer / near, std::pow(std::cos(deg(89.99999)) / std::cos(deg(89.999)), -0.4), 1e-3 * nearer / near);
  // k = 1 at theta_i = 90 deg, theta_r = 30 deg, dphi = 90 deg: cos g = 0, so F = (1 - Theta^2) / (1 +
  // Theta^2)^(3/2).
  const double flat[] = {0.3, 1.0, -0.2};
  const double f = (1.0 - 0.04) / std::pow(1.04, 1.5);
  EXPECT_NEAR(model->evaluate(flat, at(90.0, 30.0, 90.0)), 0.3 * f / kPi, 1e-12);
}

}  // namespace
}  // namespace roadbrdf
