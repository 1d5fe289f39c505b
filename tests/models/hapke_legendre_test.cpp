// The N-term Legendre phase function of the hapke model (option legendre_terms, models/hapke_phase.h)
// against independent references written here:
//   - the Legendre polynomials P1..P8 in their explicit closed forms (Abramowitz & Stegun, table 22.9);
//   - N = 1: p = 1 + a1 cos g, and the whole BRDF by report eq. 3.28 with H1 (Hapke 1981) written out;
//   - the normalisation (1/4pi) int p dOmega = 1 by a composite Simpson rule in cos g;
//   - N = 2 is the two-term model; N terms with the extra coefficients at 0 are the shorter series;
//   - the default bounds keep p >= 0 (corners of the box on a fine grid of g), and the physical range
//     |a_n| <= 2n + 1 contains the Legendre moments of a sharply peaked non-negative p;
//   - the analytic Jacobian column of a_n is w (1 + B) P_n(cos g)/(4 pi (mu0 + mu));
//   - Hapke's (2002) anisotropic multiple scattering: A_n = int_{-1}^{0} P_n dx by Simpson; P(mu0) as the
//     mean of p(g) over the directions of the lower hemisphere and P-bar as the mean of p over two
//     directions of one hemisphere, both by quadrature written here; isotropic p gives IMSA; the BRDF
//     with H1 written out; the analytic gradient against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

// P_n(x), n = 0..8, explicit (A&S table 22.9).
double legendre_closed_form(int n, double x) {
  const double x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x, x6 = x3 * x3, x7 = x6 * x, x8 = x4 * x4;
  switch (n) {
    case 0:
      return 1.0;
    case 1:
      return x;
    case 2:
      return (3.0 * x2 - 1.0) / 2.0;
    case 3:
      return (5.0 * x3 - 3.0 * x) / 2.0;
    case 4:
      return (35.0 * x4 - 30.0 * x2 + 3.0) / 8.0;
    case 5:
      return (63.0 * x5 - 70.0 * x3 + 15.0 * x) / 8.0;
    case 6:
      return (231.0 * x6 - 315.0 * x4 + 105.0 * x2 - 5.0) / 16.0;
    case 7:
      return (429.0 * x7 - 693.0 * x5 + 315.0 * x3 - 35.0 * x) / 16.0;
    default:
      return (6435.0 * x8 - 12012.0 * x6 + 6930.0 * x4 - 1260.0 * x2 + 35.0) / 128.0;
  }
}

double phase_closed_form(const std::vector<double>& a, double x) {
  double p = 1.0;
  for (std::size_t n = 1; n <= a.size(); ++n) p += a[n - 1] * legendre_closed_form(static_cast<int>(n), x);
  return p;
}

// (1/4pi) int p dOmega = (1/2) int_{-1}^{1} p(x) dx by composite Simpson (error h^4 f^{(4)}/180 < 1e-14 for the
// polynomials of degree <= 8 and coefficients below, at this step).
double sphere_mean(const std::vector<double>& a) {
  const int intervals = 20000;
  const double h = 2.0 / intervals;
  double sum = 0.0;
  for (int k = 0; k <= intervals; ++k) {
    const double weight = k == 0 || k == intervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += weight * phase_closed_form(a, -1.0 + k * h);
  }
  return 0.5 * sum * h / 3.0;
}

OptionSet legendre_options(int terms, const char* h_function = "hapke1981") {
  return {{"phase", "legendre"}, {"legendre_terms", std::to_string(terms)}, {"h_function", h_function}};
}

std::vector<Geometry> geometries() {
  std::vector<Geometry> g;
  for (double ti : {0.0, 25.0, 60.0, 80.0}) {
    for (double tr : {0.0, 30.0, 70.0}) {
      for (double dphi : {0.0, 45.0, 135.0, 180.0}) g.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    }
  }
  return g;
}

TEST(HapkeLegendre, PolynomialsEqualTheirClosedForms) {
  double p[hapke::kMaxLegendreTerms + 1];
  for (double x : {-1.0, -0.73, -0.2, 0.0, 0.31, 0.5, 0.999, 1.0}) {
    hapke::legendre_polynomials(x, hapke::kMaxLegendreTerms, p);
    for (int n = 0; n <= hapke::kMaxLegendreTerms; ++n)
      EXPECT_NEAR(p[n], legendre_closed_form(n, x), 1e-13) << n;  // the closed forms cancel near |x| = 1
  }
}

TEST(HapkeLegendre, ParametersBoundsAndOptionChecks) {
  for (int terms = 1; terms <= 8; ++terms) {
    const auto model = make_model("hapke", legendre_options(terms));
    const ModelDescription& d = model->description();
    ASSERT_EQ(d.parameters.size(), 3u + terms);
    EXPECT_EQ(d.parameters[3].name, "legendre_b");
    if (terms >= 2) {
      EXPECT_EQ(d.parameters[4].name, "legendre_c");
    }
    if (terms >= 3) {
      EXPECT_EQ(d.parameters[5].name, "legendre_a3");
    }
    EXPECT_EQ(d.parameters.back().name,
              terms >= 3 ? "legendre_a" + std::to_string(terms) : (terms == 2 ? "legendre_c" : "legendre_b"));
    if (terms == 2) continue;  // the two-term box, pinned in hapke_test
    for (int n = 1; n <= terms; ++n) {
      const std::size_t k = 2 + static_cast<std::size_t>(n);
      EXPECT_DOUBLE_EQ(d.parameters[k].lower, -1.0 / terms);
      EXPECT_DOUBLE_EQ(d.parameters[k].upper, 1.0 / terms);
      EXPECT_DOUBLE_EQ(d.parameters[k].default_value, 0.0);
      const double physical = terms == 1 ? 1.0 : 2.0 * n + 1.0;
      EXPECT_EQ(d.physical_range(k), (std::pair<double, double>{-physical, physical}));
    }
  }
  // A number of terms with another phase function would be silently ignored: refused.
  EXPECT_THROW(make_model("hapke", {{"legendre_terms", "4"}}), InputError);
  EXPECT_THROW(make_model("hapke", {{"phase", "hg2"}, {"legendre_terms", "1"}}), InputError);
  EXPECT_THROW(make_model("hapke", {{"phase", "legendre"}, {"legendre_terms", "9"}}), InputError);
  EXPECT_NO_THROW(make_model("hapke", {{"phase", "hg"}, {"legendre_terms", "2"}}));  // the default
}

TEST(HapkeLegendre, SeriesIsNormalisedForAnyCoefficients) {
  const std::vector<std::vector<double>> sets = {
      {0.7}, {0.4, -0.3, 0.25}, {-0.1, 0.2, -0.3, 0.4, -0.5, 0.6, -0.7, 0.8}, {1.5, 2.0, -3.0, 4.0, 5.0}};
  for (const auto& a : sets) {
    EXPECT_NEAR(sphere_mean(a), 1.0, 1e-13);
    for (double x : {-1.0, -0.4, 0.0, 0.66, 1.0}) {
      EXPECT_NEAR(hapke::legendre_series(a.data(), static_cast<int>(a.size()), x), phase_closed_form(a, x), 1e-14);
    }
  }
}

// N = 1 against report eq. 3.28 with p = 1 + a1 cos g and H1(x) = (1 + 2x)/(1 + 2x sqrt(1 - w)).
TEST(HapkeLegendre, OneTermModelIsEquation328WithALinearPhaseFunction) {
  const auto model = make_model("hapke", legendre_options(1));
  const double w = 0.62, b0 = 0.4, h = 0.08, a1 = 0.55;
  const std::vector<double> p = {w, b0, h, a1};
  auto h1 = [&](double x) { return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * std::sqrt(1.0 - w)); };
  for (const Geometry& g : geometries()) {
    const double mu0 = std::cos(g.theta_i), mu = std::cos(g.theta_r);
    const double cos_g = mu0 * mu + std::sin(g.theta_i) * std::sin(g.theta_r) * std::cos(g.phi_r - g.phi_i);
    const double phase_angle = std::acos(std::fmax(-1.0, std::fmin(1.0, cos_g)));
    const double b = b0 / (1.0 + std::tan(0.5 * phase_angle) / h);
    const double expected = w / (4.0 * kPi) / (mu0 + mu) * ((1.0 + b) * (1.0 + a1 * cos_g) + h1(mu0) * h1(mu) - 1.0);
    EXPECT_NEAR(model->evaluate(p.data(), g), expected, 1e-12 * expected);
  }
}

TEST(HapkeLegendre, TwoTermsAreTheTwoTermModelAndZeroTermsDropOut) {
  const double w = 0.8, b0 = 0.3, h = 0.1, b = 0.45, c = 0.35;
  const auto two = make_model("hapke", {{"phase", "legendre"}});
  const auto two_explicit = make_model("hapke", legendre_options(2, "exact"));
  const auto one = make_model("hapke", legendre_options(1, "exact"));
  const auto five = make_model("hapke", legendre_options(5, "exact"));
  const std::vector<double> p2 = {w, b0, h, b, c}, p2c0 = {w, b0, h, b, 0.0};
  const std::vector<double> p1 = {w, b0, h, b}, p5 = {w, b0, h, b, c, 0.0, 0.0, 0.0};
  for (const Geometry& g : geometries()) {
    const double f2 = two->evaluate(p2.data(), g);
    EXPECT_EQ(two_explicit->evaluate(p2.data(), g), f2);
    EXPECT_NEAR(five->evaluate(p5.data(), g), f2, 1e-15 * f2);
    EXPECT_NEAR(one->evaluate(p1.data(), g), two->evaluate(p2c0.data(), g), 1e-15 * f2);
    // The phase function itself: 1 + b cos g + c P2 by the closed form.
    const double x = dot(g.wi, g.wr);
    EXPECT_NEAR(hapke::legendre_series(p2.data() + 3, 2, x), Hapke::legendre(b, c, x), 1e-15);
  }
}

TEST(HapkeLegendre, DefaultBoundsKeepThePhaseFunctionNonNegative) {
  for (int terms = 3; terms <= 8; ++terms) {
    // Every corner of the box |a_n| <= 1/N (2^N sign patterns) on a fine grid of cos g.
    for (int signs = 0; signs < (1 << terms); ++signs) {
      std::vector<double> a(terms);
      for (int n = 0; n < terms; ++n) a[n] = ((signs >> n) & 1 ? 1.0 : -1.0) / terms;
      for (int k = 0; k <= 400; ++k) EXPECT_GE(phase_closed_form(a, -1.0 + k / 200.0), -1e-15);
    }
  }
}

// A non-negative, normalised phase function peaked at g = 0: its moments a_n = (2n + 1)/2 int p P_n dx
// lie within the physical range |a_n| <= 2n + 1 and approach it as the peak narrows.
TEST(HapkeLegendre, PhysicalRangeHoldsTheMomentsOfAPeakedPhaseFunction) {
  const double xi = -0.98;  // Henyey-Greenstein in the phase angle: backward peak at g = 0
  auto hg = [&](double x) { return (1.0 - xi * xi) / std::pow(1.0 + 2.0 * xi * x + xi * xi, 1.5); };
  const int intervals = 200000;
  const double step = 2.0 / intervals;
  for (int n = 1; n <= 8; ++n) {
    double sum = 0.0;
    for (int k = 0; k < intervals; ++k) {
      const double x = -1.0 + (k + 0.5) * step;
      sum += hg(x) * legendre_closed_form(n, x) * step;
    }
    const double moment = 0.5 * (2.0 * n + 1.0) * sum;
    EXPECT_LE(std::fabs(moment), 2.0 * n + 1.0);
    EXPECT_GT(std::fabs(moment), 0.8 * (2.0 * n + 1.0));  // HG: a_n = (2n + 1)(-xi)^n
  }
}

TEST(HapkeLegendre, JacobianColumnsAreTheLegendrePolynomials) {
  const auto model = make_model("hapke", legendre_options(6, "exact"));
  const std::vector<double> p = {0.7, 0.5, 0.06, 0.1, 0.05, -0.08, 0.12, 0.03, -0.1};
  const std::vector<Geometry> g = geometries();
  std::vector<double> values(g.size()), jacobian(g.size() * p.size());
  model->evaluate_batch_with_gradient(g.data(), g.size(), p.data(), values.data(), jacobian.data());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double mu0 = g[k].wi.z, mu = g[k].wr.z;
    const double x = dot(g[k].wi, g[k].wr);
    const double sum = length(g[k].wi + g[k].wr), difference = length(g[k].wi - g[k].wr);
    const double b = sum > 0.0 ? p[1] * p[2] / (p[2] + difference / sum) : 0.0;
    for (int n = 1; n <= 6; ++n) {
      const double expected = p[0] * (1.0 + b) * legendre_closed_form(n, x) / (4.0 * kPi * (mu0 + mu));
      EXPECT_NEAR(jacobian[k * p.size() + 2 + n], expected, 1e-13) << n;
    }
    EXPECT_NEAR(values[k], model->evaluate(p.data(), g[k]), 1e-15 * values[k]);
  }
  // The fixed-set evaluator (the path tracer's) agrees with the single evaluation.
  std::vector<double> sets = p;
  sets.insert(sets.end(), {0.3, 0.2, 0.1, -0.1, 0.0, 0.1, 0.0, 0.1, 0.0});
  const auto fixed = model->fixed_sets(sets.data(), 2);
  for (const Geometry& geometry : g) {
    double out[2];
    fixed->evaluate(geometry, out);
    for (int s = 0; s < 2; ++s) {
      const double single = model->evaluate(sets.data() + s * p.size(), geometry);
      EXPECT_NEAR(out[s], single, 1e-13 * single);
    }
  }
}

// Mean over the hemisphere of directions v (z = sign * t, t in [0, 1] uniform: uniform in solid angle)
// of p(u . v), u = (sqrt(1 - mu^2), 0, mu): midpoint rule in the azimuth (exact for the trigonometric
// polynomials that p(u . v) is in it), Simpson in t (then a polynomial, by the addition theorem).
double hemisphere_mean(const std::vector<double>& a, double mu, double sign) {
  const int azimuths = 24, intervals = 400;
  const double su = std::sqrt(1.0 - mu * mu);
  double sum = 0.0;
  for (int k = 0; k <= intervals; ++k) {
    const double t = static_cast<double>(k) / intervals;
    const double st = std::sqrt(std::fmax(0.0, 1.0 - t * t));
    double ring = 0.0;
    for (int j = 0; j < azimuths; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / azimuths;
      ring += phase_closed_form(a, su * st * std::cos(phi) + mu * sign * t);
    }
    const double weight = k == 0 || k == intervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += weight * ring / azimuths;
  }
  return sum / (3.0 * intervals);
}

TEST(HapkeAnisotropicScattering, HemisphereMomentsAndAverages) {
  for (int n = 1; n <= 8; ++n) {
    const int intervals = 20000;
    double sum = 0.0;
    for (int k = 0; k <= intervals; ++k) {
      const double weight = k == 0 || k == intervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      sum += weight * legendre_closed_form(n, -1.0 + static_cast<double>(k) / intervals);
    }
    EXPECT_NEAR(hapke::hemisphere_moment(n), sum / (3.0 * intervals), 1e-13) << n;
  }
  const std::vector<double> a = {0.4, -0.2, 0.3, 0.1, -0.25, 0.05, 0.12, -0.1};
  for (int terms : {1, 3, 8}) {
    const std::vector<double> head(a.begin(), a.begin() + terms);
    for (double mu : {0.0, 0.3, 0.77, 1.0}) {
      // P(mu): the incident direction at cosine mu above, the scattered ones below the surface.
      EXPECT_NEAR(hapke::hemisphere_average(head.data(), terms, mu), hemisphere_mean(head, mu, -1.0), 1e-9);
    }
    // P-bar: both directions in one hemisphere, the outer mean over mu by Simpson.
    const int intervals = 400;
    double sum = 0.0;
    for (int k = 0; k <= intervals; ++k) {
      const double weight = k == 0 || k == intervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      sum += weight * hemisphere_mean(head, static_cast<double>(k) / intervals, 1.0);
    }
    EXPECT_NEAR(hapke::double_hemisphere_average(head.data(), terms), sum / (3.0 * intervals), 1e-8) << terms;
  }
}

OptionSet anisotropic_options(int terms, const char* h_function) {
  OptionSet o = legendre_options(terms, h_function);
  o["multiple_scattering"] = "anisotropic";
  return o;
}

TEST(HapkeAnisotropicScattering, OptionChecksAndTheIsotropicLimit) {
  EXPECT_THROW(make_model("hapke", {{"multiple_scattering", "anisotropic"}}), InputError);
  EXPECT_THROW(make_model("hapke", {{"phase", "hg2"}, {"multiple_scattering", "anisotropic"}}), InputError);
  const auto amsa = make_model("hapke", anisotropic_options(4, "exact"));
  const auto imsa = make_model("hapke", legendre_options(4, "exact"));
  EXPECT_NE(amsa->description().summary.find("AMSA"), std::string::npos);
  const std::vector<double> p = {0.9, 0.3, 0.05, 0.0, 0.0, 0.0, 0.0};
  for (const Geometry& g : geometries()) {
    const double f = imsa->evaluate(p.data(), g);
    EXPECT_NEAR(amsa->evaluate(p.data(), g), f, 1e-14 * f);  // P = P-bar = 1: M = H0 H1 - 1
  }
}

TEST(HapkeAnisotropicScattering, BrdfEqualsHapke2002WithH1) {
  const auto model = make_model("hapke", anisotropic_options(3, "hapke1981"));
  const double w = 0.75, b0 = 0.2, h = 0.1;
  const std::vector<double> a = {0.3, 0.2, -0.1};
  const std::vector<double> p = {w, b0, h, a[0], a[1], a[2]};
  auto h1 = [&](double x) { return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * std::sqrt(1.0 - w)); };
  // A_1 = -1/2, A_3 = 1/8 (the integrals above), A_2 = 0.
  auto average = [&](double x) { return 1.0 - 0.5 * a[0] * x + 0.125 * a[2] * legendre_closed_form(3, x); };
  const double p_bar = 1.0 + 0.25 * a[0] + a[2] / 64.0;
  for (const Geometry& g : geometries()) {
    const double mu0 = std::cos(g.theta_i), mu = std::cos(g.theta_r);
    const double cos_g = dot(g.wi, g.wr);
    const double phase_angle = std::acos(std::fmax(-1.0, std::fmin(1.0, cos_g)));
    const double b = b0 / (1.0 + std::tan(0.5 * phase_angle) / h);
    const double m =
        average(mu0) * (h1(mu) - 1.0) + average(mu) * (h1(mu0) - 1.0) + p_bar * (h1(mu0) - 1.0) * (h1(mu) - 1.0);
    const double expected = w / (4.0 * kPi) / (mu0 + mu) * ((1.0 + b) * phase_closed_form(a, cos_g) + m);
    EXPECT_NEAR(model->evaluate(p.data(), g), expected, 1e-12 * expected);
  }
}

TEST(HapkeAnisotropicScattering, GradientMatchesCentralDifferences) {
  for (const char* h_function : {"hapke2002", "exact"}) {
    for (int terms : {2, 5}) {
      const auto model = make_model("hapke", anisotropic_options(terms, h_function));
      std::vector<double> p = {0.8, 0.4, 0.07, 0.3, 0.2, 0.1, -0.1, 0.05};
      p.resize(3 + terms);
      for (const Geometry& g : geometries()) {
        std::vector<double> gradient(p.size());
        const double f = model->evaluate_with_gradient(p.data(), g, gradient.data());
        EXPECT_NEAR(f, model->evaluate(p.data(), g), 1e-15 * f);
        for (std::size_t k = 0; k < p.size(); ++k) {
          const double step = 1e-6;
          std::vector<double> up = p, down = p;
          up[k] += step;
          down[k] -= step;
          const double difference = (model->evaluate(up.data(), g) - model->evaluate(down.data(), g)) / (2.0 * step);
          EXPECT_NEAR(gradient[k], difference, 1e-6 * (std::fabs(difference) + f)) << h_function << " " << k;
        }
      }
    }
  }
}

}  // namespace
}  // namespace roadbrdf
