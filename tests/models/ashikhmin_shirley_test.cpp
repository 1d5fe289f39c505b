// Tests of the Ashikhmin-Shirley model (Ashikhmin & Shirley, J. Graphics Tools 5(2) 2000, eqs. 4-5).
// Reference values are closed forms derived by hand below and independent numerical integrals.
#include "roadbrdf/models/ashikhmin_shirley.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

std::unique_ptr<Model> make() { return make_model("ashikhmin-shirley", {}); }

// Parameters in declaration order: rd, rs, nu, nv.
std::vector<double> params(double rd, double rs, double nu, double nv) { return {rd, rs, nu, nv}; }

double schlick(double c, double rs) { return rs + (1.0 - rs) * std::pow(1.0 - c, 5); }
double diffuse(double rd, double rs, double ci, double cr) {
  return 28.0 * rd / (23.0 * kPi) * (1.0 - rs) * (1.0 - std::pow(1.0 - ci / 2.0, 5)) *
         (1.0 - std::pow(1.0 - cr / 2.0, 5));
}

// Directional albedo int f cos(theta_r) d omega_r by composite Simpson in theta_r and the periodic
// trapezoid rule in phi_r (independent of any quadrature in the library).
double directional_albedo(const Model& m, const std::vector<double>& p, double theta_i_deg, int n_theta, int n_phi) {
  const double h = (kPi / 2) / n_theta;  // n_theta even
  double sum = 0.0;
  for (int a = 0; a <= n_theta; ++a) {
    const double t = a * h;
    const double w = (a == 0 || a == n_theta) ? 1.0 : (a % 2 == 1 ? 4.0 : 2.0);
    double ring = 0.0;
    for (int b = 0; b < n_phi; ++b) {
      const double phi = 2.0 * kPi * (b + 0.5) / n_phi;
      ring += m.evaluate(p.data(), geometry_from_radians(theta_i_deg * kDegree, 0.0, t, phi));
    }
    sum += w * ring * (2.0 * kPi / n_phi) * std::cos(t) * std::sin(t);
  }
  return sum * h / 3.0;
}

TEST(AshikhminShirley, Description) {
  const auto m = make();
  const auto& d = m->description();
  EXPECT_EQ(d.name, "ashikhmin-shirley");
  ASSERT_EQ(d.parameters.size(), 4u);
  EXPECT_EQ(d.parameters[0].name, "rd");
  EXPECT_EQ(d.parameters[1].name, "rs");
  EXPECT_EQ(d.parameters[2].name, "nu");
  EXPECT_EQ(d.parameters[3].name, "nv");
  EXPECT_TRUE(d.reciprocal);
  EXPECT_FALSE(d.has_delta);
}

TEST(AshikhminShirley, NormalIncidenceNormalView) {
  // theta_i = theta_r = 0: h = n, so the exponent is irrelevant ((n.h)^e = 1), h.k = 1, max(...) = 1,
  // F(1) = R_s: f_s = sqrt((nu+1)(nv+1))/(8 pi) R_s. Diffuse: (1 - (1 - 1/2)^5)^2 = (31/32)^2.
  const auto m = make();
  const auto p = params(0.3, 0.05, 20.0, 40.0);
  const double expected =
      std::sqrt(21.0 * 41.0) / (8.0 * kPi) * 0.05 + 28.0 * 0.3 / (23.0 * kPi) * 0.95 * (31.0 / 32.0) * (31.0 / 32.0);
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(0, 0, 0, 0)), expected, 1e-14);
}

TEST(AshikhminShirley, ExactMirror) {
  // theta_i = theta_r = 40 deg, dphi = 180: h = n (lobe 1), h.k = cos 40, max = cos 40:
  // f_s = sqrt((nu+1)(nv+1))/(8 pi) F(cos 40) / cos^2 40.
  const auto m = make();
  const auto p = params(0.2, 0.1, 50.0, 5.0);
  const double c = std::cos(40.0 * kDegree);
  const double expected = std::sqrt(51.0 * 6.0) / (8.0 * kPi) * schlick(c, 0.1) / (c * c) + diffuse(0.2, 0.1, c, c);
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(40, 15, 40, 195)), expected, 1e-12 * expected);
}

TEST(AshikhminShirley, AnisotropyFollowsTangentAxes) {
  // w_i at theta 30 deg and w_r at theta 10 deg on the forward side in one azimuthal plane: the angle
  // between them is 40 deg, so |w_i + w_r| = 2 cos 20, h.k = cos 20 and n.h = (cos 30 + cos 10)/(2 cos 20).
  // Plane phi = 0/180 (x axis): h has no y component, exponent = n_u exactly. Plane phi = 90/270 (y axis):
  // exponent = n_v. Denominator: max(cos 30, cos 10) = cos 10.
  const auto m = make();
  const double nu = 200.0, nv = 10.0, rd = 0.4, rs = 0.06;
  const auto p = params(rd, rs, nu, nv);
  const double ci = std::cos(30.0 * kDegree), cr = std::cos(10.0 * kDegree);
  const double hk = std::cos(20.0 * kDegree);
  const double nh = (ci + cr) / (2.0 * hk);
  const double norm = std::sqrt((nu + 1.0) * (nv + 1.0)) / (8.0 * kPi);
  const double along_u = norm * std::pow(nh, nu) * schlick(hk, rs) / (hk * cr) + diffuse(rd, rs, ci, cr);
  const double along_v = norm * std::pow(nh, nv) * schlick(hk, rs) / (hk * cr) + diffuse(rd, rs, ci, cr);
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(30, 0, 10, 180)), along_u, 1e-12 * along_u);
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(30, 90, 10, 270)), along_v, 1e-12 * along_v);
  EXPECT_LT(along_u, along_v);  // larger exponent along u: narrower lobe in that plane
}

TEST(AshikhminShirley, DiffuseTermFarFromTheLobe) {
  // Retro side, theta_i = 60, theta_r = 30: n.h = (cos 60 + cos 30)/|w_i + w_r| with w_i . w_r =
  // cos 60 cos 30 + sin 60 sin 30 = cos 30, |w_i + w_r| = 2 cos 15 -> n.h = 0.7071 and (n.h)^10000 underflows:
  // the value is the diffuse term alone.
  const auto m = make();
  const auto p = params(0.7, 0.2, 10000.0, 10000.0);
  const double expected = diffuse(0.7, 0.2, 0.5, std::cos(30.0 * kDegree));
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(60, 0, 30, 0)), expected, 1e-15);
}

TEST(AshikhminShirley, DiffuseAlbedoClosedForm) {
  // The model is linear in rd, so f(rd = 1) - f(rd = 0) is exactly the diffuse term, whose directional
  // albedo is (1 - R_s)(1 - (1 - cos(theta_i)/2)^5): 2 pi 28/(23 pi) int_0^1 (1 - (1 - mu/2)^5) mu d mu =
  // (56/23)(1/2 - 5/56) = 1, by hand: int_0^1 mu (1 - mu/2)^5 d mu = 4 int_{1/2}^1 (t^5 - t^6) dt = 5/56.
  const auto m = make();
  for (double theta_i : {0.0, 35.0, 70.0}) {
    const auto with = params(1.0, 0.25, 30.0, 30.0);
    const auto without = params(0.0, 0.25, 30.0, 30.0);
    const double a = directional_albedo(*m, with, theta_i, 200, 64) - directional_albedo(*m, without, theta_i, 200, 64);
    const double expected = 0.75 * (1.0 - std::pow(1.0 - std::cos(theta_i * kDegree) / 2.0, 5));
    EXPECT_NEAR(a, expected, 1e-9) << theta_i;
  }
}

TEST(AshikhminShirley, EnergyBoundedOverParameterRange) {
  // Total directional albedo (white substrate rd = 1) stays <= 1, as the paper claims. Numerical
  // integral: Simpson 400 x trapezoid 360 resolves lobes with n <= 100 to about 1e-3.
  const auto m = make();
  struct Case {
    double rs, nu, nv;
  };
  for (const Case& c : {Case{0.0, 0.0, 0.0}, Case{0.0, 1.0, 1.0}, Case{0.05, 10.0, 10.0}, Case{0.5, 1.0, 100.0},
                        Case{1.0, 5.0, 5.0}, Case{0.04, 100.0, 100.0}}) {
    for (double theta_i : {0.0, 45.0, 75.0, 85.0}) {
      const double a = directional_albedo(*m, params(1.0, c.rs, c.nu, c.nv), theta_i, 400, 360);
      EXPECT_LE(a, 1.0 + 2e-3) << "rs " << c.rs << " nu " << c.nu << " nv " << c.nv << " theta_i " << theta_i;
      EXPECT_GT(a, 0.0);
    }
  }
}

TEST(AshikhminShirley, Reciprocity) {
  const auto m = make();
  const auto p = params(0.4, 0.08, 30.0, 7.0);
  const double angles[][4] = {{10, 0, 50, 200}, {70, 30, 20, 100}, {45, 10, 45, 190}, {85, 0, 5, 300}, {0, 0, 60, 40}};
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const double f = m->evaluate(p.data(), g);
    EXPECT_NEAR(f, m->evaluate(p.data(), g.swapped()), 1e-13 * f);
  }
}

TEST(AshikhminShirley, FiniteAndNonNegativeEverywhereIncludingSpecialGeometries) {
  const auto m = make();
  const std::vector<std::vector<double>> sets = {params(0, 0, 0, 0), params(1, 1, 10000, 10000), params(1, 0, 0, 10000),
                                                 params(0.5, 0.05, 20, 20)};
  const double thetas[] = {0.0, 10.0, 45.0, 80.0, 89.9, 90.0};
  const double dphis[] = {0.0, 45.0, 90.0, 180.0};
  for (const auto& p : sets) {
    for (double ti : thetas) {
      for (double tr : thetas) {
        for (double dphi : dphis) {
          const double f = m->evaluate(p.data(), geometry_from_degrees(ti, 0.0, tr, dphi));
          EXPECT_TRUE(std::isfinite(f)) << ti << ' ' << tr << ' ' << dphi;
          EXPECT_GE(f, 0.0) << ti << ' ' << tr << ' ' << dphi;
        }
      }
    }
  }
  // Exact grazing mirror: w_r = -w_i, both in the surface; the specular term carries no power and is 0.
  const auto p = params(0.5, 0.05, 20, 20);
  EXPECT_EQ(m->evaluate(p.data(), geometry_from_degrees(90, 0, 90, 180)), 0.0);
  // Near-grazing mirror stays finite: 1/cos^2(89.9 deg) ~ 3.3e5.
  const double c = std::cos(89.9 * kDegree);
  const double expected = std::sqrt(21.0 * 21.0) / (8.0 * kPi) * schlick(c, 0.05) / (c * c) + diffuse(0.5, 0.05, c, c);
  EXPECT_NEAR(m->evaluate(p.data(), geometry_from_degrees(89.9, 0, 89.9, 180)), expected, 1e-9 * expected);
}

TEST(AshikhminShirley, GradientMatchesFiniteDifferences) {
  const auto m = make();
  const std::vector<double> p = params(0.35, 0.07, 25.0, 60.0);
  const Geometry geometries[] = {geometry_from_degrees(30, 10, 25, 200), geometry_from_degrees(60, 0, 55, 175),
                                 geometry_from_degrees(0, 0, 0, 0), geometry_from_degrees(40, 0, 40, 180),
                                 geometry_from_degrees(80, 0, 10, 30)};
  for (const Geometry& g : geometries) {
    std::vector<double> grad(p.size());
    const double f = m->evaluate_with_gradient(p.data(), g, grad.data());
    EXPECT_NEAR(f, m->evaluate(p.data(), g), 1e-14 * std::fabs(f));
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double h = 1e-6 * std::fmax(1.0, std::fabs(p[k]));
      std::vector<double> up = p, down = p;
      up[k] += h;
      down[k] -= h;
      const double fd = (m->evaluate(up.data(), g) - m->evaluate(down.data(), g)) / (2.0 * h);
      EXPECT_NEAR(grad[k], fd, 1e-6 * std::fmax(1.0, std::fabs(fd))) << "parameter " << k;
    }
  }
}

}  // namespace
}  // namespace roadbrdf
