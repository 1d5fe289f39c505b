// Fresnel reflectance (models/fresnel.h) against closed forms, physical laws and an independent
// complex-arithmetic evaluation of the Fresnel equations.
#include "roadbrdf/models/fresnel.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "roadbrdf/core/math.h"

namespace roadbrdf {
namespace {

// Independent reference: Fresnel amplitude coefficients for a complex relative index N = n + ik,
// r_s = (cos i - N cos t)/(cos i + N cos t), r_p = (N cos i - cos t)/(N cos i + cos t) with
// N cos t = sqrt(N^2 - sin^2 i) (Born & Wolf, Principles of Optics, 7th ed., section 1.5.2 and 14.2).
double reference_reflectance(double cos_i, double n, double k) {
  using C = std::complex<double>;
  const C N(n, k);
  const double sin2 = 1.0 - cos_i * cos_i;
  C n_cos_t = std::sqrt(N * N - sin2);
  if (n_cos_t.imag() < 0.0) n_cos_t = -n_cos_t;  // decaying transmitted wave
  const C rs = (cos_i - n_cos_t) / (cos_i + n_cos_t);
  const C cos_t = n_cos_t / N;
  const C rp = (N * cos_i - cos_t) / (N * cos_i + cos_t);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(Fresnel, NormalIncidenceDielectric) {
  for (double n : {1.0, 1.33, 1.5, 1.7, 2.42, 3.0}) {
    const double expected = std::pow((n - 1.0) / (n + 1.0), 2);
    EXPECT_NEAR(fresnel_dielectric(1.0, n), expected, 1e-15) << n;
    EXPECT_NEAR(fresnel_f0(n), expected, 1e-15) << n;
  }
  // Glass n = 1.5: 4 % (classic textbook value, e.g. Hecht, Optics, section 4.6).
  EXPECT_NEAR(fresnel_dielectric(1.0, 1.5), 0.04, 1e-15);
}

TEST(Fresnel, BrewsterAngleHasNoPReflection) {
  for (double n : {1.33, 1.5, 2.0}) {
    const double theta_b = std::atan(n);
    const auto r = fresnel_dielectric_polarised(std::cos(theta_b), n);
    EXPECT_NEAR(r.rp, 0.0, 1e-15) << n;
    EXPECT_GT(r.rs, 0.01);
    // Away from Brewster rp > 0.
    EXPECT_GT(fresnel_dielectric_polarised(std::cos(theta_b + 0.1), n).rp, 1e-5);
  }
}

TEST(Fresnel, TotalInternalReflection) {
  const double eta = 1.0 / 1.5;  // from glass to air
  const double theta_c = std::asin(eta);
  EXPECT_EQ(fresnel_dielectric(std::cos(theta_c + 1e-6), eta), 1.0);
  EXPECT_EQ(fresnel_dielectric(std::cos(1.2), eta), 1.0);
  EXPECT_LT(fresnel_dielectric(std::cos(theta_c - 1e-3), eta), 1.0);
  // Normal incidence from the dense side: same 4 % as from outside.
  EXPECT_NEAR(fresnel_dielectric(1.0, eta), 0.04, 1e-15);
}

TEST(Fresnel, StokesReciprocity) {
  // The reflectance of an interface is the same from both sides at corresponding angles
  // (Stokes relations; Born & Wolf 1.5.3): F(theta_i, n) = F(theta_t, 1/n), sin theta_t = sin theta_i / n.
  const double n = 1.6;
  for (double deg : {5.0, 20.0, 40.0, 60.0, 80.0, 89.0}) {
    const double ti = deg * kDegree;
    const double tt = std::asin(std::sin(ti) / n);
    EXPECT_NEAR(fresnel_dielectric(std::cos(ti), n), fresnel_dielectric(std::cos(tt), 1.0 / n), 1e-12) << deg;
  }
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  EXPECT_NEAR(fresnel_dielectric(0.0, 1.5), 1.0, 1e-15);
  EXPECT_NEAR(fresnel_conductor(0.0, 0.5, 3.0), 1.0, 1e-15);
}

TEST(Fresnel, ConductorWithoutExtinctionIsDielectric) {
  for (double n : {1.0, 1.2, 1.5, 2.5}) {
    for (double deg : {0.0, 15.0, 30.0, 45.0, 56.3, 70.0, 85.0, 89.9}) {
      const double c = std::cos(deg * kDegree);
      EXPECT_NEAR(fresnel_conductor(c, n, 0.0), fresnel_dielectric(c, n), 1e-13) << n << ' ' << deg;
    }
  }
}

TEST(Fresnel, DielectricMatchesComplexFresnelEquations) {
  for (double n : {1.2, 1.5, 2.4}) {
    for (double deg = 0.0; deg < 90.0; deg += 7.5) {
      const double c = std::cos(deg * kDegree);
      EXPECT_NEAR(fresnel_dielectric(c, n), reference_reflectance(c, n, 0.0), 1e-13) << n << ' ' << deg;
    }
  }
}

TEST(Fresnel, AluminiumAt632nm) {
  // Aluminium at 632.8 nm: n = 1.37289, k = 7.617691 (Rakic et al., Appl. Opt. 37, 5271 (1998),
  // as tabulated by refractiveindex.info). Normal-incidence reflectance from the closed form
  // R = ((n-1)^2 + k^2)/((n+1)^2 + k^2) (Born & Wolf eq. 14.2(24)) is 0.9137, i.e. the ~91 %
  // visible reflectance of aluminium.
  const double n = 1.37289, k = 7.617691;
  const double r0 = (std::pow(n - 1.0, 2) + k * k) / (std::pow(n + 1.0, 2) + k * k);
  EXPECT_NEAR(r0, 0.9137, 5e-4);
  EXPECT_NEAR(fresnel_conductor(1.0, n, k), r0, 1e-14);
  // Oblique incidence against the independent complex evaluation.
  for (double deg = 0.0; deg <= 89.0; deg += 8.0) {
    const double c = std::cos(deg * kDegree);
    EXPECT_NEAR(fresnel_conductor(c, n, k), reference_reflectance(c, n, k), 1e-12) << deg;
  }
  // Gold at 632.8 nm style constants (n < 1): still matches the complex form.
  for (double deg = 0.0; deg <= 89.0; deg += 11.0) {
    const double c = std::cos(deg * kDegree);
    EXPECT_NEAR(fresnel_conductor(c, 0.18, 3.4), reference_reflectance(c, 0.18, 3.4), 1e-12) << deg;
  }
}

TEST(Fresnel, SchlickMatchesExactAtNormalAndGrazing) {
  for (double n : {1.2, 1.5, 2.0}) {
    const double f0 = fresnel_f0(n);
    EXPECT_NEAR(fresnel_schlick(1.0, f0), fresnel_dielectric(1.0, n), 1e-15);
    EXPECT_NEAR(fresnel_schlick(0.0, f0), fresnel_dielectric(0.0, n), 1e-15);
    // In between it is an approximation: for n = 1.5 its largest absolute error, near 80-85 deg,
    // is about 0.036 (evaluated against the exact form; no claim of the code under test).
    if (n == 1.5) {
      for (double deg = 0.0; deg < 90.0; deg += 5.0) {
        const double c = std::cos(deg * kDegree);
        EXPECT_NEAR(fresnel_schlick(c, f0), fresnel_dielectric(c, n), 0.04) << deg;
      }
    }
  }
  // Conductor Schlick-type form: exact at normal incidence, 1 at grazing.
  const double n = 1.37289, k = 7.617691;
  EXPECT_NEAR(fresnel_schlick_conductor(1.0, n, k), fresnel_conductor(1.0, n, k), 1e-14);
  EXPECT_NEAR(fresnel_schlick_conductor(0.0, n, k), 1.0, 1e-14);
}

TEST(Fresnel, JetDerivativesMatchFiniteDifferences) {
  using J = ceres::Jet<double, 2>;
  const double c = std::cos(50.0 * kDegree);
  const double n = 1.45, k = 2.0, h = 1e-6;
  {
    const J f = fresnel_dielectric(J(c), J(n, 0));
    const double fd = (fresnel_dielectric(c, n + h) - fresnel_dielectric(c, n - h)) / (2 * h);
    EXPECT_NEAR(f.v[0], fd, 1e-7);
  }
  {
    const J f = fresnel_conductor(J(c), J(n, 0), J(k, 1));
    const double fdn = (fresnel_conductor(c, n + h, k) - fresnel_conductor(c, n - h, k)) / (2 * h);
    const double fdk = (fresnel_conductor(c, n, k + h) - fresnel_conductor(c, n, k - h)) / (2 * h);
    EXPECT_NEAR(f.v[0], fdn, 1e-7);
    EXPECT_NEAR(f.v[1], fdk, 1e-7);
  }
}

}  // namespace
}  // namespace roadbrdf
