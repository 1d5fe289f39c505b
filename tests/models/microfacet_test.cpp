// Microfacet distributions and masking functions (models/microfacet.h) against independent
// numerical integrals over the hemisphere and closed forms from the papers.
#include "roadbrdf/models/microfacet.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "roadbrdf/core/math.h"

namespace roadbrdf {
namespace {

using microfacet::beckmann_cos_lambda;
using microfacet::beckmann_cos_lambda_rational;
using microfacet::ggx_cos_lambda;

// Composite Simpson rule on [a, b] with n (even) intervals: the test's own integrator.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

// 2 pi int_0^{pi/2} D(theta) cos(theta) sin(theta) dtheta: the projected-area normalisation.
double cos_weighted_integral(const std::function<double(double)>& d_of_cos) {
  return 2.0 * kPi *
         simpson([&](double t) { return d_of_cos(std::cos(t)) * std::cos(t) * std::sin(t); }, 0.0, kPi / 2, 40000);
}
// 2 pi int D sin dtheta: the solid-angle normalisation.
double solid_angle_integral(const std::function<double(double)>& d_of_cos) {
  return 2.0 * kPi * simpson([&](double t) { return d_of_cos(std::cos(t)) * std::sin(t); }, 0.0, kPi / 2, 40000);
}

TEST(Microfacet, BeckmannIsNormalised) {
  for (double a : {0.05, 0.2, 0.5, 1.0, 2.0}) {
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::beckmann_d(c, a); }), 1.0, 1e-6) << a;
  }
}

TEST(Microfacet, GgxIsNormalisedAndMatchesReportForm) {
  for (double a : {0.05, 0.2, 0.5, 1.0, 2.0}) {
    // GGX has a heavy tail; the integral converges, Simpson handles it.
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::ggx_d(c, a); }), 1.0, 1e-6) << a;
    // Report eq. 3.14 / Walter 2007 eq. 33 written with tan: 1 / (pi a^2 cos^4 (1 + tan^2/a^2)^2).
    for (double deg : {0.0, 10.0, 30.0, 60.0, 85.0}) {
      const double t = deg * kDegree;
      const double c = std::cos(t);
      const double tan2 = std::pow(std::tan(t), 2);
      const double ref = 1.0 / (kPi * a * a * std::pow(c, 4) * std::pow(1.0 + tan2 / (a * a), 2));
      EXPECT_NEAR(microfacet::ggx_d(c, a), ref, 1e-12 * ref) << a << ' ' << deg;
    }
  }
}

TEST(Microfacet, GaussianIsNormalised) {
  for (double s : {0.01, 0.05, 0.17, 0.2, 0.5, 1.0, 1.2}) {
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::gaussian_d(c, s); }), 1.0, 1e-6) << s;
  }
  // Small sigma: the Gaussian tends to a 2-D Gaussian of the slope angle, c -> 1/(2 pi sigma^2).
  EXPECT_NEAR(microfacet::gaussian_normalisation(1e-3) * 2.0 * kPi * 1e-6, 1.0, 1e-5);
}

TEST(Microfacet, GtrAndBerryAreNormalised) {
  for (double a : {0.05, 0.3, 0.999999, 1.0, 1.3}) {
    for (double g : {0.6, 1.0, 1.000001, 1.5, 2.0, 3.0}) {
      EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::gtr_d(c, a, g); }), 1.0, 2e-6)
          << a << ' ' << g;
    }
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::berry_d(c, a); }), 1.0, 2e-6) << a;
  }
  // gamma = 2 is GGX (Burley 2012 appendix B).
  for (double c : {1.0, 0.9, 0.5, 0.1}) {
    EXPECT_NEAR(microfacet::gtr_d(c, 0.3, 2.0), microfacet::ggx_d(c, 0.3), 1e-12 * microfacet::ggx_d(c, 0.3));
  }
  // alpha = 1: uniform projected area, D = 1/pi for every gamma.
  EXPECT_NEAR(microfacet::gtr_d(0.4, 1.0, 1.7), kInvPi, 1e-14);
}

TEST(Microfacet, WardAndPhongNormalisations) {
  for (double a : {0.05, 0.1, 0.3, 0.6, 1.0}) {
    // Report eq. 3.22 as printed is a density over the half-vector solid angle...
    EXPECT_NEAR(solid_angle_integral([&](double c) { return microfacet::ward_halfway_pdf(c, a); }), 1.0, 1e-6) << a;
    // ...and ward_d is rescaled to the projected-area normalisation.
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::ward_d(c, a); }), 1.0, 1e-6) << a;
  }
  for (double m : {0.0, 1.0, 10.0, 100.0, 1000.0}) {
    EXPECT_NEAR(cos_weighted_integral([&](double c) { return microfacet::phong_d(c, m); }), 1.0, 1e-6) << m;
    EXPECT_NEAR(solid_angle_integral([&](double c) { return microfacet::phong_halfway_pdf(c, m); }), 1.0, 1e-6) << m;
  }
}

TEST(Microfacet, ErfcxBothBranches) {
  // erfcx(x) = exp(x^2) erfc(x) is representable in double up to x ~ 26: check the asymptotic branch.
  for (double x : {0.0, 0.5, 3.0, 9.999, 11.999, 12.0, 12.001, 14.0, 20.0, 25.0}) {
    const double ref = std::exp(x * x) * std::erfc(x);
    EXPECT_NEAR(microfacet::erfcx(x), ref, 1e-12 * ref) << x;  // ref: erfc(x) keeps ~1e-15 relative accuracy
  }
}

// Smith's projected-area identity (Heitz 2014 eq. 44; Walter 2007 section 5.1):
//   int max(0, o.m) D(m) dm = cos theta_o (1 + Lambda(o)),
// i.e. int G1(o, m) D(m) <o, m> dm = cos theta_o. The left side is integrated here over the microfacet
// hemisphere in (theta_m, phi_m), with the phi range cut analytically where o.m = 0.
double projected_area(const std::function<double(double)>& d_of_cos, double theta_o) {
  const double so = std::sin(theta_o), co = std::cos(theta_o);
  const double t_split = kPi / 2 - theta_o;  // below it every facet faces o
  auto inner = [&](double tm) {
    const double cm = std::cos(tm), sm = std::sin(tm);
    double phi_max = kPi;
    if (so * sm > 0.0) {
      const double x = -co * cm / (so * sm);
      phi_max = x <= -1.0 ? kPi : (x >= 1.0 ? 0.0 : std::acos(x));
    }
    if (phi_max <= 0.0) return 0.0;
    const double integral_phi =
        2.0 * simpson([&](double p) { return so * sm * std::cos(p) + co * cm; }, 0.0, phi_max, 64);
    return d_of_cos(cm) * integral_phi * sm;
  };
  double total = 0.0;
  if (t_split > 0.0) total += simpson(inner, 0.0, t_split, 4000);
  total += simpson(inner, std::fmax(t_split, 0.0), kPi / 2, 4000);
  return total;
}

TEST(Microfacet, SmithIdentityBeckmannAndGgx) {
  for (double a : {0.1, 0.4, 1.0}) {
    for (double deg : {0.0, 30.0, 60.0, 80.0, 89.0}) {
      const double t = deg * kDegree;
      const double c = std::cos(t);
      const double lhs_b = projected_area([&](double cm) { return microfacet::beckmann_d(cm, a); }, t);
      EXPECT_NEAR(lhs_b, c + beckmann_cos_lambda(c, a), 2e-5) << "beckmann " << a << ' ' << deg;
      const double lhs_g = projected_area([&](double cm) { return microfacet::ggx_d(cm, a); }, t);
      EXPECT_NEAR(lhs_g, c + ggx_cos_lambda(c, a), 2e-5) << "ggx " << a << ' ' << deg;
    }
  }
}

TEST(Microfacet, LambdaClosedForms) {
  // Report eq. 3.12 / 3.15 evaluated directly (a = 1/(alpha tan theta)).
  for (double alpha : {0.1, 0.5, 1.2}) {
    for (double deg : {5.0, 40.0, 75.0, 89.0}) {
      const double t = deg * kDegree;
      const double a = 1.0 / (alpha * std::tan(t));
      const double lb = (std::erf(a) - 1.0) / 2.0 + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
      const double lg = (-1.0 + std::sqrt(1.0 + 1.0 / (a * a))) / 2.0;
      EXPECT_NEAR(beckmann_cos_lambda(std::cos(t), alpha) / std::cos(t), lb, 1e-12 * (1.0 + lb));
      EXPECT_NEAR(ggx_cos_lambda(std::cos(t), alpha) / std::cos(t), lg, 1e-12 * (1.0 + lg));
    }
  }
  // Normal direction: no masking. Grazing: cos*Lambda -> alpha/(2 sqrt(pi)) (Beckmann), alpha/2 (GGX).
  EXPECT_EQ(beckmann_cos_lambda(1.0, 0.3), 0.0);
  EXPECT_EQ(ggx_cos_lambda(1.0, 0.3), 0.0);
  EXPECT_NEAR(beckmann_cos_lambda(0.0, 0.3), 0.3 / (2.0 * std::sqrt(kPi)), 1e-15);
  EXPECT_NEAR(ggx_cos_lambda(0.0, 0.3), 0.15, 1e-15);
}

TEST(Microfacet, RationalBeckmannWithinPublishedAccuracy) {
  // Walter et al. 2007, eq. 27 and text: the rational approximation of G1 is within about 0.35 %
  // relative error of the exact Smith-Beckmann G1 (exact from the erf form, computed here).
  double worst = 0.0;
  for (double deg = 1.0; deg < 90.0; deg += 0.5) {
    const double t = deg * kDegree;
    for (double alpha : {0.05, 0.2, 0.5, 1.0, 2.0}) {
      const double c = std::cos(t);
      const double a = 1.0 / (alpha * std::tan(t));
      const double lambda = (std::erf(a) - 1.0) / 2.0 + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
      const double g_exact = 1.0 / (1.0 + lambda);
      const double g_rational = c / (c + beckmann_cos_lambda_rational(c, alpha));
      worst = std::fmax(worst, std::fabs(g_rational - g_exact) / g_exact);
    }
  }
  EXPECT_LT(worst, 0.0035);
}

TEST(Microfacet, VCavityLimits) {
  // Normal incidence and viewing: no masking.
  EXPECT_EQ(microfacet::vcavity_g(1.0, 1.0, 1.0, 1.0), 1.0);
  // G <= 1 and symmetric in (i, r); G/(cos_i cos_r) finite when one direction is grazing.
  EXPECT_DOUBLE_EQ(microfacet::vcavity_g(0.3, 0.8, 0.9, 0.7), microfacet::vcavity_g(0.8, 0.3, 0.9, 0.7));
  EXPECT_LE(microfacet::vcavity_g(0.3, 0.8, 0.9, 0.7), 1.0);
  EXPECT_TRUE(std::isfinite(microfacet::vcavity_g_over_cos(0.0, 0.5, 0.8, 0.6)));
  EXPECT_NEAR(microfacet::vcavity_g_over_cos(0.0, 0.5, 0.8, 0.6), 2.0 * 0.8 / 0.6 / 0.5, 1e-15);
  EXPECT_NEAR(microfacet::vcavity_g_over_cos(0.3, 0.8, 0.9, 0.7) * 0.3 * 0.8, microfacet::vcavity_g(0.3, 0.8, 0.9, 0.7),
              1e-15);
}

TEST(Microfacet, RoughnessDerivativesMatchFiniteDifferences) {
  using J = ceres::Jet<double, 2>;
  const double h = 1e-6;
  auto check = [&](const std::function<J(J)>& fj, const std::function<double(double)>& fd, double x, const char* what) {
    const J v = fj(J(x, 0));
    const double ref = (fd(x + h) - fd(x - h)) / (2 * h);
    EXPECT_NEAR(v.v[0], ref, 1e-6 * (1.0 + std::fabs(ref))) << what << " at " << x;
    EXPECT_NEAR(v.a, fd(x), 1e-14 * (1.0 + std::fabs(v.a))) << what;
  };
  const double c = std::cos(20.0 * kDegree);
  for (double x : {0.05, 0.16, 0.3, 0.9}) {
    check([&](J s) { return microfacet::gaussian_d(c, s); }, [&](double s) { return microfacet::gaussian_d(c, s); }, x,
          "gaussian");
    check([&](J s) { return microfacet::beckmann_d(c, s); }, [&](double s) { return microfacet::beckmann_d(c, s); }, x,
          "beckmann");
    check([&](J s) { return microfacet::ggx_d(c, s); }, [&](double s) { return microfacet::ggx_d(c, s); }, x, "ggx");
    check([&](J s) { return microfacet::ward_d(c, s); }, [&](double s) { return microfacet::ward_d(c, s); }, x, "ward");
    check([&](J s) { return microfacet::beckmann_cos_lambda(0.2, s); },
          [&](double s) { return microfacet::beckmann_cos_lambda(0.2, s); }, x, "beckmann lambda");
    check([&](J s) { return microfacet::ggx_cos_lambda(0.2, s); },
          [&](double s) { return microfacet::ggx_cos_lambda(0.2, s); }, x, "ggx lambda");
  }
  // GTR derivative in gamma through the series branch near gamma = 1 and in alpha near alpha = 1.
  for (double g : {1.0, 1.3, 2.0}) {
    check([&](J gg) { return microfacet::gtr_d(c, J(0.4), gg); },
          [&](double gg) { return microfacet::gtr_d(c, 0.4, gg); }, g, "gtr gamma");
  }
  check([&](J a) { return microfacet::gtr_d(c, a, J(1.5)); }, [&](double a) { return microfacet::gtr_d(c, a, 1.5); },
        1.0, "gtr alpha at 1");
  check([&](J m) { return microfacet::phong_d(c, m); }, [&](double m) { return microfacet::phong_d(c, m); }, 20.0,
        "phong");
}

}  // namespace
}  // namespace roadbrdf
