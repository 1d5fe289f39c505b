// Hapke's macroscopic roughness correction (option roughness = hapke1984, models/hapke_roughness.h)
// against Hapke, Icarus 59:41-59 (1984) eqs. 46-51, written again here in angle form (zenith angles
// i, e and the azimuth psi between the planes of incidence and emergence, as in the paper), not by
// calling the model's code:
//   - theta_bar = 0 is the smooth model bit for bit, for every phase and H function;
//   - the published limits: theta_bar -> 0 (mu0e -> mu0, mue -> mu, S -> 1, O(theta_bar^2)); i = e = 0:
//     mu0e = mue = chi(theta_bar) and S = 1; e = 0: mu0e = eta(i); i <= e and e <= i forms agree at i = e;
//   - reciprocity: (mu0e/mu0) S is symmetric in i and e, and so is the BRDF;
//   - values of mu0e, mue and S, and of the rough BRDF with H1 (Hapke 1981) written out, at a set of
//     geometries and slopes;
//   - the integrated parameter gradient of the black-sky albedo (albedo/gradient_integrals.h, which
//     uses the model's gradient path) against central differences of the albedo itself, for the rough
//     model and a 4-term Legendre phase function.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

constexpr double kDeg = kPi / 180.0;

struct Paper {
  double mu0e, mue, s;
};

// Hapke (1984) in the paper's variables; angles in radians, 0 < theta_bar, 0 <= psi <= pi.
Paper hapke_1984(double i, double e, double psi, double theta_bar) {
  const double t = std::tan(theta_bar);
  const double chi = 1.0 / std::sqrt(1.0 + kPi * t * t);
  auto e1 = [&](double x) { return x == 0.0 ? 0.0 : std::exp(-2.0 / (kPi * t * std::tan(x))); };
  auto e2 = [&](double x) { return x == 0.0 ? 0.0 : std::exp(-1.0 / (kPi * t * t * std::tan(x) * std::tan(x))); };
  auto eta = [&](double x) { return chi * (std::cos(x) + std::sin(x) * t * e2(x) / (2.0 - e1(x))); };
  const double f = psi >= kPi ? 0.0 : std::exp(-2.0 * std::tan(psi / 2.0));
  const double s2 = std::sin(psi / 2.0) * std::sin(psi / 2.0);
  Paper r;
  if (i <= e) {
    const double d = 2.0 - e1(e) - (psi / kPi) * e1(i);
    r.mu0e = chi * (std::cos(i) + std::sin(i) * t * (std::cos(psi) * e2(e) + s2 * e2(i)) / d);
    r.mue = chi * (std::cos(e) + std::sin(e) * t * (e2(e) - s2 * e2(i)) / d);
    r.s = (r.mue / eta(e)) * (std::cos(i) / eta(i)) * chi / (1.0 - f + f * chi * std::cos(i) / eta(i));
  } else {
    const double d = 2.0 - e1(i) - (psi / kPi) * e1(e);
    r.mu0e = chi * (std::cos(i) + std::sin(i) * t * (e2(i) - s2 * e2(e)) / d);
    r.mue = chi * (std::cos(e) + std::sin(e) * t * (std::cos(psi) * e2(i) + s2 * e2(e)) / d);
    r.s = (r.mue / eta(e)) * (std::cos(i) / eta(i)) * chi / (1.0 - f + f * chi * std::cos(e) / eta(e));
  }
  return r;
}

// eta(x) = chi [cos x + sin x tan theta_bar E2(x)/(2 - E1(x))], x > 0.
double eta_1984(double x, double theta_bar) {
  const double t = std::tan(theta_bar);
  const double chi = 1.0 / std::sqrt(1.0 + kPi * t * t);
  const double e1 = std::exp(-2.0 / (kPi * t * std::tan(x)));
  const double e2 = std::exp(-1.0 / (kPi * t * t * std::tan(x) * std::tan(x)));
  return chi * (std::cos(x) + std::sin(x) * t * e2 / (2.0 - e1));
}

OptionSet rough_options(const char* phase = "hg", const char* h_function = "hapke1981") {
  return {{"phase", phase}, {"h_function", h_function}, {"roughness", "hapke1984"}};
}

struct Angles {
  double i, e, psi;  // degrees
};

std::vector<Angles> angle_set() {
  std::vector<Angles> a;
  for (double i : {0.0, 20.0, 45.0, 70.0, 85.0}) {
    for (double e : {0.0, 10.0, 45.0, 60.0, 88.0}) {
      for (double psi : {0.0, 30.0, 90.0, 150.0, 180.0}) a.push_back({i, e, psi});
    }
  }
  return a;
}

TEST(HapkeRoughness, ZeroSlopeIsTheSmoothModelBitForBit) {
  for (const char* phase : {"hg", "legendre", "hg2"}) {
    for (const char* h_function : {"hapke1981", "hapke2002", "exact"}) {
      const auto smooth = make_model("hapke", {{"phase", phase}, {"h_function", h_function}});
      const auto rough = make_model("hapke", rough_options(phase, h_function));
      ASSERT_EQ(rough->parameter_count(), smooth->parameter_count() + 1);
      EXPECT_EQ(rough->description().parameters.back().name, "theta_bar");
      EXPECT_EQ(rough->description().parameters.back().unit, "rad");
      EXPECT_DOUBLE_EQ(rough->description().parameters.back().upper, 60.0 * kDeg);
      std::vector<double> p = smooth->description().default_parameters();
      p[0] = 0.73;
      p[1] = 0.6;
      std::vector<double> q = p;
      q.push_back(0.0);
      for (const Angles& a : angle_set()) {
        const Geometry g = geometry_from_degrees(a.i, 0.0, a.e, a.psi);
        EXPECT_EQ(rough->evaluate(q.data(), g), smooth->evaluate(p.data(), g)) << phase << " " << h_function;
      }
      // The gradient too (theta_bar's derivative is 0 there: O(theta_bar^2) terms only).
      const Geometry g = geometry_from_degrees(35.0, 0.0, 50.0, 120.0);
      std::vector<double> gs(p.size()), gr(q.size());
      const double fs = smooth->evaluate_with_gradient(p.data(), g, gs.data());
      const double fr = rough->evaluate_with_gradient(q.data(), g, gr.data());
      EXPECT_EQ(fr, fs);
      for (std::size_t k = 0; k < p.size(); ++k) EXPECT_NEAR(gr[k], gs[k], 1e-15 * std::fabs(gs[k]) + 1e-300);
      EXPECT_EQ(gr.back(), 0.0);
    }
  }
}

TEST(HapkeRoughness, EffectiveCosinesAndShadowingEqualThePaper) {
  for (double theta_bar : {1.0, 10.0, 25.0, 45.0, 60.0}) {
    for (const Angles& a : angle_set()) {
      const Geometry g = geometry_from_degrees(a.i, 0.0, a.e, a.psi);
      const hapke::RoughCosines<double> c =
          hapke::rough_cosines(theta_bar * kDeg, hapke::roughness_geometry(g.wi, g.wr));
      const Paper expected = hapke_1984(a.i * kDeg, a.e * kDeg, a.psi * kDeg, theta_bar * kDeg);
      EXPECT_NEAR(c.mu0e, expected.mu0e, 1e-14) << theta_bar << " " << a.i << " " << a.e << " " << a.psi;
      EXPECT_NEAR(c.mue, expected.mue, 1e-14) << theta_bar << " " << a.i << " " << a.e << " " << a.psi;
      EXPECT_NEAR(c.shadow_over_mu0 * std::cos(a.i * kDeg), expected.s, 1e-13);
    }
  }
}

TEST(HapkeRoughness, PublishedLimits) {
  for (double theta_bar : {5.0, 20.0, 40.0, 60.0}) {
    const double t = std::tan(theta_bar * kDeg);
    const double chi = 1.0 / std::sqrt(1.0 + kPi * t * t);
    // i = e = 0: mu0e = mue = chi, S = 1 (any psi).
    for (double psi : {0.0, 90.0, 180.0}) {
      const Paper nadir = hapke_1984(0.0, 0.0, psi * kDeg, theta_bar * kDeg);
      EXPECT_NEAR(nadir.mu0e, chi, 1e-15);
      EXPECT_NEAR(nadir.mue, chi, 1e-15);
      EXPECT_NEAR(nadir.s, 1.0, 1e-15);
      const Geometry g = geometry_from_degrees(0.0, 0.0, 0.0, psi);
      const auto c = hapke::rough_cosines(theta_bar * kDeg, hapke::roughness_geometry(g.wi, g.wr));
      EXPECT_NEAR(c.mu0e, chi, 1e-15);
      EXPECT_NEAR(c.mue, chi, 1e-15);
      EXPECT_NEAR(c.shadow_over_mu0, 1.0, 1e-15);
    }
    for (double x : {10.0, 50.0, 80.0}) {
      // Viewing along the normal: the effective cosine of incidence is eta(i), for any psi.
      const Geometry g = geometry_from_degrees(x, 0.0, 0.0, 0.0);
      const auto c = hapke::rough_cosines(theta_bar * kDeg, hapke::roughness_geometry(g.wi, g.wr));
      EXPECT_NEAR(c.mu0e, eta_1984(x * kDeg, theta_bar * kDeg), 1e-15);
      // The two forms of the paper agree at i = e.
      for (double psi : {0.0, 70.0, 180.0}) {
        const Geometry same = geometry_from_degrees(x, 0.0, x, psi);
        const Geometry nudged = geometry_from_degrees(x, 0.0, x * (1.0 + 1e-12), psi);
        const auto c1 = hapke::rough_cosines(theta_bar * kDeg, hapke::roughness_geometry(same.wi, same.wr));
        const auto c2 = hapke::rough_cosines(theta_bar * kDeg, hapke::roughness_geometry(nudged.wi, nudged.wr));
        EXPECT_NEAR(c1.mu0e, c2.mu0e, 1e-10);
        EXPECT_NEAR(c1.mue, c2.mue, 1e-10);
        EXPECT_NEAR(c1.shadow_over_mu0, c2.shadow_over_mu0, 1e-10);
      }
    }
  }
  // theta_bar -> 0: the smooth values, with differences O(theta_bar^2) (chi = 1 - pi theta_bar^2/2).
  for (const Angles& a : angle_set()) {
    if (a.i > 80.0 || a.e > 80.0) continue;  // E1, E2 are not yet negligible within theta_bar of grazing
    for (double theta_bar : {1e-2, 1e-3}) {
      const Paper r = hapke_1984(a.i * kDeg, a.e * kDeg, a.psi * kDeg, theta_bar * kDeg);
      const double bound = 2.0 * theta_bar * kDeg * theta_bar * kDeg;
      EXPECT_NEAR(r.mu0e, std::cos(a.i * kDeg), bound);
      EXPECT_NEAR(r.mue, std::cos(a.e * kDeg), bound);
      EXPECT_NEAR(r.s, 1.0, 2.0 * bound);
    }
  }
}

TEST(HapkeRoughness, ReciprocalShadowingAndBrdf) {
  const auto model = make_model("hapke", rough_options("hg2", "exact"));
  const std::vector<double> p = {0.8, 0.7, 0.05, 0.4, 0.5, 30.0 * kDeg};
  for (const Angles& a : angle_set()) {
    const Paper forward = hapke_1984(a.i * kDeg, a.e * kDeg, a.psi * kDeg, 30.0 * kDeg);
    const Paper backward = hapke_1984(a.e * kDeg, a.i * kDeg, a.psi * kDeg, 30.0 * kDeg);
    EXPECT_NEAR(forward.mu0e, backward.mue, 1e-15);
    EXPECT_NEAR(forward.mue, backward.mu0e, 1e-15);
    if (a.i > 0.0 && a.e > 0.0) {
      EXPECT_NEAR(forward.mu0e / std::cos(a.i * kDeg) * forward.s, backward.mu0e / std::cos(a.e * kDeg) * backward.s,
                  1e-13);
    }
    const Geometry g = geometry_from_degrees(a.i, 0.0, a.e, a.psi);
    const double f = model->evaluate(p.data(), g), f_swapped = model->evaluate(p.data(), g.swapped());
    EXPECT_NEAR(f, f_swapped, 1e-13 * f);
  }
}

// The rough BRDF f = r_R/mu0 with H1 and Henyey-Greenstein written out.
TEST(HapkeRoughness, BrdfEqualsThePaperWithHapke1981H) {
  const auto model = make_model("hapke", rough_options("hg", "hapke1981"));
  const double w = 0.55, b0 = 0.9, h = 0.07, xi = -0.3;
  auto h1 = [&](double x) { return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * std::sqrt(1.0 - w)); };
  for (double theta_bar : {8.0, 20.0, 35.0}) {
    const std::vector<double> p = {w, b0, h, xi, theta_bar * kDeg};
    for (const Angles& a : angle_set()) {
      const double i = a.i * kDeg, e = a.e * kDeg, psi = a.psi * kDeg;
      const double cos_g = std::cos(i) * std::cos(e) + std::sin(i) * std::sin(e) * std::cos(psi);
      const double g = std::acos(std::fmax(-1.0, std::fmin(1.0, cos_g)));
      const double b = b0 / (1.0 + std::tan(g / 2.0) / h);
      const double phase = (1.0 - xi * xi) / std::pow(1.0 + 2.0 * xi * cos_g + xi * xi, 1.5);
      const Paper r = hapke_1984(i, e, psi, theta_bar * kDeg);
      if (a.i == 0.0 && a.e == 0.0) continue;  // below: divided by cos i, fine; nadir checked elsewhere
      const double reflectance =
          w / (4.0 * kPi) * r.mu0e / (r.mu0e + r.mue) * ((1.0 + b) * phase + h1(r.mu0e) * h1(r.mue) - 1.0) * r.s;
      const double expected = reflectance / std::cos(i);
      const double f = model->evaluate(p.data(), geometry_from_degrees(a.i, 0.0, a.e, a.psi));
      EXPECT_NEAR(f, expected, 1e-12 * expected) << theta_bar << " " << a.i << " " << a.e << " " << a.psi;
    }
  }
}

// Gradient of theta_bar (and of w through H at the effective cosines) against central differences,
// for the three H functions; the fixed-set evaluator agrees with the single evaluation.
TEST(HapkeRoughness, GradientMatchesCentralDifferences) {
  for (const char* h_function : {"hapke1981", "hapke2002", "exact"}) {
    const auto model = make_model("hapke", rough_options("legendre", h_function));
    const std::vector<double> p = {0.85, 0.4, 0.1, 0.3, 0.2, 25.0 * kDeg};
    for (const Angles& a : angle_set()) {
      const Geometry g = geometry_from_degrees(a.i, 0.0, a.e, a.psi);
      std::vector<double> gradient(p.size());
      const double f = model->evaluate_with_gradient(p.data(), g, gradient.data());
      EXPECT_NEAR(f, model->evaluate(p.data(), g), 1e-15 * f);
      for (std::size_t k : {std::size_t{0}, p.size() - 1}) {
        const double step = 1e-6;
        std::vector<double> up = p, down = p;
        up[k] += step;
        down[k] -= step;
        const double difference = (model->evaluate(up.data(), g) - model->evaluate(down.data(), g)) / (2.0 * step);
        EXPECT_NEAR(gradient[k], difference, 1e-6 * (std::fabs(difference) + f)) << h_function << " parameter " << k;
      }
    }
    std::vector<double> sets = p;
    sets.insert(sets.end(), {0.3, 0.0, 0.1, -0.2, 0.1, 50.0 * kDeg});
    const auto fixed = model->fixed_sets(sets.data(), 2);
    for (const Angles& a : angle_set()) {
      const Geometry g = geometry_from_degrees(a.i, 0.0, a.e, a.psi);
      double out[2];
      fixed->evaluate(g, out);
      for (int s = 0; s < 2; ++s) EXPECT_EQ(out[s], model->evaluate(sets.data() + s * p.size(), g));
    }
  }
}

TEST(HapkeRoughness, AlbedoGradientIntegralEqualsCentralDifferences) {
  const auto model = make_model("hapke", {{"phase", "legendre"}, {"legendre_terms", "4"}, {"roughness", "hapke1984"}});
  const ModelDescription& d = model->description();
  const std::size_t P = d.parameters.size();
  ASSERT_EQ(P, 8u);
  const std::vector<double> params = {0.7, 0.5, 0.1, 0.2, -0.1, 0.15, -0.05, 30.0 * kDeg};
  std::vector<double> scale(P);
  for (std::size_t k = 0; k < P; ++k) scale[k] = 0.02 * (d.parameters[k].upper - d.parameters[k].lower);
  albedo::QuadratureSettings settings;
  settings.tolerance = 1e-6;
  albedo::QuadratureSettings reference;
  reference.tolerance = 1e-8;
  const double theta_s = 40.0 * kDeg;
  const albedo::GradientIntegral g =
      albedo::black_sky_gradient(*model, params.data(), 1, scale, theta_s, 0.0, false, settings);
  ASSERT_EQ(g.gradient.size(), P);
  for (std::size_t k = 0; k < P; ++k) {
    const double h = 1e-3 * (d.parameters[k].upper - d.parameters[k].lower);
    std::vector<double> up = params, down = params;
    up[k] += h;
    down[k] -= h;
    const double difference = (albedo::black_sky(*model, up.data(), 1, theta_s, 0.0, reference).value[0] -
                               albedo::black_sky(*model, down.data(), 1, theta_s, 0.0, reference).value[0]) /
                              (2.0 * h);
    // Scaled by the parameter's uncertainty, as the uncertainty propagation uses it (to 1e-4 of the albedo).
    EXPECT_NEAR(scale[k] * g.gradient[k], scale[k] * difference, 1e-5) << d.parameters[k].name;
  }
}

// The batch paths (a fit's prepared geometries: values, and values with the gradient) compute the
// terms of theta_bar once and those of each zenith once per distinct zenith (Hapke::evaluate_rough):
// on a grid of repeated zeniths at several incidence azimuths (whose sines may differ in the last bit),
// grazing rows included, the values are operator()'s bit for bit and the gradient is the automatic
// derivative of operator() geometry by geometry, bit for bit.
TEST(HapkeRoughness, BatchSharingZenithTermsEqualsOneGeometryAtATime) {
  using Jet = ceres::Jet<double, 8>;
  for (const char* phase : {"hg", "legendre"}) {
    const OptionSet options = {{"roughness", "hapke1984"}, {"phase", phase}};
    const Hapke model(resolve_options(Hapke::kName, Hapke::options(), options));
    const auto adapter = make_model("hapke", options);
    std::vector<Geometry> geometries;
    for (double phi_i : {0.0, 37.0, 200.0}) {
      for (double ti : {0.0, 20.0, 55.0, 80.0, 90.0}) {
        for (double tr : {10.0, 55.0, 89.0}) {
          for (double dphi : {0.0, 90.0, 180.0})
            geometries.push_back(geometry_from_degrees(ti, phi_i, tr, phi_i + dphi));
        }
      }
    }
    std::vector<double> p = adapter->description().default_parameters();
    p.back() = 0.35;  // theta_bar [rad]
    const std::size_t P = p.size(), n = geometries.size();
    const auto prepared = adapter->prepare(geometries.data(), n);
    std::vector<double> values(n), with_gradient(n), jacobian(n * P);
    adapter->evaluate_prepared(*prepared, p.data(), values.data());
    adapter->evaluate_prepared_with_gradient(*prepared, p.data(), with_gradient.data(), jacobian.data());
    std::vector<Jet> pj(P);
    for (std::size_t k = 0; k < P; ++k) pj[k] = Jet(p[k], static_cast<int>(k));
    for (std::size_t g = 0; g < n; ++g) {
      const Hapke::Prepared q = model.prepare(geometries[g]);
      EXPECT_EQ(values[g], model(p.data(), q)) << phase << " " << g;
      const Jet f = model(pj.data(), q);
      EXPECT_EQ(with_gradient[g], f.a) << phase << " " << g;
      for (std::size_t k = 0; k < P; ++k) EXPECT_EQ(jacobian[g * P + k], f.v[static_cast<int>(k)]) << g << " " << k;
    }
  }
}

}  // namespace
}  // namespace roadbrdf
