// Tabulated BRDF sampler of the path tracer (surface/brdf_sampler.h): the density is normalised,
// sample() draws from exactly pdf(), and the table follows the BRDF.
#include <gtest/gtest.h>

#include <cmath>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/surface/brdf_sampler.h"

namespace rs = roadbrdf::surface;
using roadbrdf::kPi;
using roadbrdf::Vec3;

namespace {

Vec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// A glossy material: Oren-Nayar diffuse + Torrance-Sparrow lobe of small roughness (0.05 rad).
struct Glossy {
  std::shared_ptr<const roadbrdf::Model> model = roadbrdf::make_model("oren-nayar+torrance-sparrow");
  std::vector<double> p;
  Glossy() {
    p = model->description().default_parameters();
    p[model->description().parameter_index("torrance-sparrow.roughness").value()] = 0.05;
  }
};

// Independent quadrature of pdf over the hemisphere in (theta, phi) with sin(theta) (midpoint
// rule on a grid unrelated to the table's cells).
double integral_of_pdf(const rs::BrdfSampler& s, const Vec3& w_o, int n_theta, int n_phi) {
  double sum = 0.0;
  const double dt = 0.5 * kPi / n_theta, dp = 2 * kPi / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double th = (i + 0.5) * dt;
    for (int j = 0; j < n_phi; ++j) sum += s.pdf(w_o, direction(th, (j + 0.5) * dp)) * std::sin(th) * dt * dp;
  }
  return sum;
}

}  // namespace

TEST(BrdfSampler, DensityIntegratesToOne) {
  const Glossy g;
  const rs::BrdfSampler s(*g.model, g.p, 1);
  for (double theta_o_deg : {0.0, 30.0, 62.0, 85.0}) {
    const Vec3 w_o = direction(roadbrdf::deg_to_rad(theta_o_deg), 0.7);
    EXPECT_NEAR(integral_of_pdf(s, w_o, 3000, 3000), 1.0, 2e-3) << theta_o_deg;
  }
  const auto lambert = roadbrdf::make_model("lambert");
  const rs::BrdfSampler black(*lambert, {0.0}, 1);  // all-zero table -> uniform
  EXPECT_NEAR(integral_of_pdf(black, direction(0.5, 0.0), 300, 600), 1.0, 3e-3);
  // The CDFs are stored as floats: an interval of width 1/96 is exact to 2^-24 / (1/96) ~ 6e-6 relative.
  EXPECT_NEAR(black.pdf(direction(0.5, 0.0), direction(1.0, 2.0)), 1.0 / (2 * kPi), 1e-5 / (2 * kPi));
}

// For a Lambertian material the table is cos(theta) at the cell centres: pdf = cos/pi up to half a
// cell in cos(theta).
TEST(BrdfSampler, LambertianTableIsTheCosineDensity) {
  const auto lambert = roadbrdf::make_model("lambert");
  const rs::BrdfSampler s(*lambert, {0.5}, 1);
  const double half_cell = 0.5 / s.settings().cos_theta_bins;
  for (double th : {0.1, 0.6, 1.0, 1.4}) {
    for (double ph : {0.0, 1.0, 3.0, 5.0}) {
      const Vec3 w = direction(th, ph);
      EXPECT_NEAR(s.pdf(direction(0.8, 0.3), w), std::cos(th) / kPi, half_cell / kPi + 1e-12);
    }
  }
}

// Histogram of sample() over bins unrelated to the table's cells, against the integral of pdf()
// over each bin; each count within 5 binomial standard deviations (+ the quadrature error). The
// pdf returned by sample() equals pdf() at the drawn direction.
TEST(BrdfSampler, SampledHistogramMatchesTheDensity) {
  const Glossy g;
  const rs::BrdfSampler s(*g.model, g.p, 1);
  const Vec3 w_o = direction(roadbrdf::deg_to_rad(60.0), 1.1);
  const int nb_t = 9, nb_p = 12;  // bins in theta (uniform angle) and phi
  const int n = 400000;
  std::vector<double> counts(nb_t * nb_p, 0.0);
  roadbrdf::Rng rng(7);
  double max_pdf_mismatch = 0.0;
  for (int k = 0; k < n; ++k) {
    double p = 0.0;
    const Vec3 w = s.sample(w_o, rng.uniform(), rng.uniform(), rng.uniform(), p);
    ASSERT_NEAR(w.x * w.x + w.y * w.y + w.z * w.z, 1.0, 1e-12);
    ASSERT_GE(w.z, 0.0);
    max_pdf_mismatch = std::max(max_pdf_mismatch, std::fabs(p - s.pdf(w_o, w)) / p);
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    const int bt = std::min(nb_t - 1, static_cast<int>(std::acos(w.z) / (0.5 * kPi) * nb_t));
    const int bp = std::min(nb_p - 1, static_cast<int>(phi / (2 * kPi) * nb_p));
    counts[bt * nb_p + bp] += 1.0;
  }
  // Boundary cases (a direction exactly on a cell edge) may differ; nearly all must match.
  EXPECT_LT(max_pdf_mismatch, 1e-9);
  const int sub = 40;
  for (int bt = 0; bt < nb_t; ++bt) {
    for (int bp = 0; bp < nb_p; ++bp) {
      double prob = 0.0;
      const double t0 = bt * 0.5 * kPi / nb_t, p0 = bp * 2 * kPi / nb_p;
      const double dt = 0.5 * kPi / nb_t / sub, dp = 2 * kPi / nb_p / sub;
      for (int i = 0; i < sub; ++i) {
        const double th = t0 + (i + 0.5) * dt;
        for (int j = 0; j < sub; ++j) prob += s.pdf(w_o, direction(th, p0 + (j + 0.5) * dp)) * std::sin(th) * dt * dp;
      }
      const double expected = n * prob, sd = std::sqrt(n * prob * (1 - prob));
      EXPECT_NEAR(counts[bt * nb_p + bp], expected, 5 * sd + 0.02 * expected + 3) << bt << " " << bp;
    }
  }
}

// The table of a glossy material puts most of the probability near the mirror direction of w_o:
// the density there is far above the cosine density.
TEST(BrdfSampler, GlossyTablePeaksAtTheMirrorDirection) {
  const Glossy g;
  const rs::BrdfSampler s(*g.model, g.p, 1);
  const double th = roadbrdf::deg_to_rad(50.0);
  const Vec3 w_o = direction(th, 0.4);
  const Vec3 mirror = direction(th, 0.4 + kPi);
  EXPECT_GT(s.pdf(w_o, mirror), 5.0 * std::cos(th) / kPi);
  EXPECT_LT(s.pdf(w_o, direction(th, 0.4)), s.pdf(w_o, mirror));
}
