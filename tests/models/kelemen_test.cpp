// Kelemen & Szirmay-Kalos coupled model (models/kelemen_szirmay_kalos.h): the tabulated specular
// albedo against an independent integration of the model's own specular lobe, the energy-coupling
// property by independent hemispherical integration, bounds, reciprocity and gradients.
#include "roadbrdf/models/kelemen_szirmay_kalos.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

const std::vector<std::string> kDistributions = {"beckmann", "ward", "phong"};

// Tanh-sinh (double-exponential) rule on [a, b]: x = c + d tanh((pi/2) sinh t), t = k h, |t| <= 3.2.
// It resolves endpoint singularities and boundary layers (square roots, mu log mu, 1/(x + eps)), which
// grazing incidence produces at both ends of the half-vector ranges. f receives the point and its
// distances to a and to b (computed without cancellation).
template <class F>
double tanh_sinh(double a, double b, F f, double h = 0.1) {
  const double half = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = -32; k <= 32; ++k) {
    const double t = k * h;
    const double s = 0.5 * kPi * std::sinh(t);
    const double e = std::exp(-2.0 * std::fabs(s));
    const double near_end = (b - a) * e / (1.0 + e);  // distance to the nearer end
    const double w = half * 0.5 * kPi * std::cosh(t) * 4.0 * e / ((1.0 + e) * (1.0 + e));
    const double x = s < 0 ? a + near_end : b - near_end;
    sum += w * f(x, s < 0 ? near_end : (b - a) - near_end, s < 0 ? (b - a) - near_end : near_end);
  }
  return sum * h;
}

// Directional albedo int f(w_i, w_r) cos theta_r dw_r by the test's own rule: w_r through the half
// vector h = (theta_h, phi_h) about the normal (dw_r = 4 (l.h) dw_h; Walter 2007 eq. 14), phi_h on
// [0, phi_max(theta_h)] where w_r is above the horizon (x 2, symmetry), phi_max from the horizon
// condition 2 (l.h) cos theta_h > cos theta_i solved for cos phi_h; theta_h on pieces split where
// the azimuth range starts to shrink and vanishes and at multiples of the lobe width. Both by tanh-sinh.
double directional_albedo(const Model& m, const double* p, double theta_i, double alpha) {
  const double mu = std::cos(theta_i), sin_i = std::sin(theta_i);
  const Vec3 l = spherical_direction(theta_i, 0.0);
  auto phi_max = [&](double th) {
    const double c = mu * (1.0 - 2.0 * std::cos(th) * std::cos(th)) / (2.0 * std::cos(th) * sin_i * std::sin(th));
    return c <= -1.0 ? kPi : c >= 1.0 ? 0.0 : std::acos(c);
  };
  const double t_full = kPi / 4 - theta_i / 2, t_none = kPi / 4 + theta_i / 2;
  std::vector<double> cuts = {0.0, t_full, t_none};
  for (double k : {1.0, 3.0, 8.0}) {
    if (std::atan(k * alpha) < t_none) cuts.push_back(std::atan(k * alpha));
  }
  std::sort(cuts.begin(), cuts.end());
  double total = 0.0;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    if (cuts[c + 1] - cuts[c] < 1e-12) continue;
    total += tanh_sinh(cuts[c], cuts[c + 1], [&](double th, double, double) {
      const double pm = phi_max(th);
      if (pm <= 0.0) return 0.0;
      const double ring = tanh_sinh(0.0, pm, [&](double ph, double, double) {
        const Vec3 h = spherical_direction(th, ph);
        const double lh = dot(l, h);
        const Vec3 r = 2.0 * lh * h - l;
        if (lh <= 0 || r.z <= 0) return 0.0;
        const Geometry g = geometry_from_radians(theta_i, 0.0, std::acos(std::fmin(1.0, r.z)), std::atan2(r.y, r.x));
        return m.evaluate(p, g) * r.z * 4.0 * lh;
      });
      return 2.0 * ring * std::sin(th);
    });
  }
  return total;
}

TEST(KelemenSzirmayKalos, RegisteredWithDocumentedParameters) {
  auto m = make_model("kelemen-szirmay-kalos");
  const auto& d = m->description();
  ASSERT_EQ(d.parameters.size(), 3u);
  EXPECT_EQ(d.parameters[0].name, "albedo");
  EXPECT_TRUE(d.parameters[0].linear);
  EXPECT_EQ(d.parameters[1].name, "roughness");
  EXPECT_EQ(d.parameters[2].name, "ior");
  EXPECT_TRUE(d.energy_conserving);
}

TEST(KelemenSzirmayKalos, TabulatedSpecularAlbedoMatchesIntegration) {
  // With albedo = 0 the model is its specular term alone; its directional albedo, integrated here,
  // must equal the interpolated table rho_s(mu) = F0 A + B.
  for (const auto& dist : kDistributions) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    const auto& table = ksk::albedo_table(KelemenSzirmayKalos::distribution_of({{"distribution", dist}}));
    for (double alpha : {0.01, 0.05, 0.37, 0.9}) {
      for (double n : {1.0, 2.5}) {  // rho_s is affine in F0: two values test both parts
        const double p[] = {0.0, alpha, n};
        const double f0 = std::pow((n - 1) / (n + 1), 2);
        for (double deg : {0.0, 62.0, 89.0, 89.97}) {
          const double integral = directional_albedo(*m, p, deg * kDegree, alpha);
          const double tabulated = ksk::specular_albedo(table, std::cos(deg * kDegree), alpha, f0);
          EXPECT_NEAR(tabulated, integral, 1e-5) << dist << " alpha " << alpha << " n " << n << " theta " << deg;
          EXPECT_LE(tabulated, 1.0) << dist;
          EXPECT_GE(tabulated, 0.0) << dist;
        }
      }
    }
  }
}

TEST(KelemenSzirmayKalos, EnergyCouplingByIndependentIntegration) {
  // The coupling makes the directional albedo a(theta_i) = rho_s + rho_d (1 - rho_s) (Kelemen &
  // Szirmay-Kalos 2001, section on the matte term): with rho_d = 1 every photon comes back.
  // rho_s is itself measured by integrating the model with rho_d = 0; nothing comes from the table.
  for (const auto& dist : kDistributions) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    for (double alpha : {0.01, 0.05, 0.6}) {
      for (double deg : {0.0, 80.0, 89.0, 89.5}) {
        const double t = deg * kDegree;
        const double p_spec[] = {0.0, alpha, 1.5};
        const double p_white[] = {1.0, alpha, 1.5};
        const double p_grey[] = {0.4, alpha, 1.5};
        const double rho_s = directional_albedo(*m, p_spec, t, alpha);
        EXPECT_NEAR(directional_albedo(*m, p_white, t, alpha), 1.0, 1e-5) << dist << ' ' << alpha << ' ' << deg;
        EXPECT_NEAR(directional_albedo(*m, p_grey, t, alpha), rho_s + 0.4 * (1.0 - rho_s), 1e-5)
            << dist << ' ' << alpha << ' ' << deg;
      }
    }
  }
}

TEST(KelemenSzirmayKalos, AlbedoAtMostOneOverTheParameterBox) {
  for (const auto& dist : kDistributions) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    const auto& table = ksk::albedo_table(KelemenSzirmayKalos::distribution_of({{"distribution", dist}}));
    for (double alpha = ksk::kAlphaMin; alpha <= ksk::kAlphaMax * 1.0000001; alpha *= 1.2) {
      for (double n : {1.0, 1.5, 3.0}) {
        const double f0 = std::pow((n - 1) / (n + 1), 2);
        const double bar = ksk::specular_albedo_average(table, alpha, f0);
        EXPECT_LT(bar, 1.0) << dist << ' ' << alpha;
        for (double mu = 0.0; mu <= 1.0; mu += 0.01) {
          const double r = ksk::specular_albedo(table, mu, alpha, f0);
          EXPECT_LE(r, 1.0) << dist << ' ' << alpha << ' ' << mu;
          EXPECT_GE(r, -1e-8) << dist << ' ' << alpha << ' ' << mu;  // spline overshoot only
        }
      }
    }
    // Independent check of the worst case (roughest, densest facets, grazing).
    const double p[] = {1.0, 1.0, 3.0};
    EXPECT_LE(directional_albedo(*m, p, 89.0 * kDegree, 1.0), 1.0 + 1e-5) << dist;
  }
}

TEST(KelemenSzirmayKalos, FiniteReciprocalNonNegative) {
  const std::vector<Geometry> geometries = {
      geometry_from_degrees(0, 0, 0, 0),     geometry_from_degrees(89.9, 0, 89.9, 180),
      geometry_from_degrees(90, 0, 90, 180), geometry_from_degrees(90, 0, 30, 180),
      geometry_from_degrees(90, 0, 90, 0),   geometry_from_degrees(45, 0, 45, 180),
      geometry_from_degrees(45, 0, 45, 0),   geometry_from_degrees(20, 0, 75, 100),
  };
  for (const auto& dist : kDistributions) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    for (double alpha : {ksk::kAlphaMin, 0.3, ksk::kAlphaMax}) {
      const double p[] = {0.8, alpha, 1.5};
      for (const auto& g : geometries) {
        const double f = m->evaluate(p, g);
        EXPECT_TRUE(std::isfinite(f)) << dist << ' ' << alpha;
        EXPECT_GE(f, 0.0);
        EXPECT_NEAR(f, m->evaluate(p, g.swapped()), 1e-12 * (1 + f));
      }
    }
  }
}

TEST(KelemenSzirmayKalos, GradientMatchesFiniteDifferences) {
  const std::vector<Geometry> geometries = {geometry_from_degrees(30, 0, 50, 170), geometry_from_degrees(70, 0, 60, 20),
                                            geometry_from_degrees(0, 0, 80, 0)};
  for (const auto& dist : kDistributions) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    for (double alpha : {0.05, 0.33, 0.8}) {
      std::vector<double> p = {0.6, alpha, 1.7};
      for (const auto& g : geometries) {
        std::vector<double> grad(3);
        m->evaluate_with_gradient(p.data(), g, grad.data());
        for (std::size_t k = 0; k < 3; ++k) {
          const double h = 1e-6;
          std::vector<double> hi = p, lo = p;
          hi[k] += h;
          lo[k] -= h;
          const double fd = (m->evaluate(hi.data(), g) - m->evaluate(lo.data(), g)) / (2 * h);
          EXPECT_NEAR(grad[k], fd, 1e-5 * (1.0 + std::fabs(fd))) << dist << " alpha " << alpha << " param " << k;
        }
      }
    }
  }
}

}  // namespace
}  // namespace roadbrdf
