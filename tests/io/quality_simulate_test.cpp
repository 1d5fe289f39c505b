// Quality checks on simulated data with planted defects, and the virtual gonioreflectometer.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/io/simulate.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

// A Cerema-like grid in road angles: incidence 0-80, observation 10-90, azimuth planes 0-180.
std::vector<Geometry> grid() {
  std::vector<Geometry> g;
  for (double gamma : {0.0, 20.0, 40.0, 60.0, 80.0}) {
    for (double alpha : {10.0, 30.0, 50.0, 70.0, 90.0}) {
      for (double beta : {0.0, 45.0, 90.0, 135.0, 180.0}) {
        if ((gamma == 0.0 || alpha == 90.0) && beta != 0.0) continue;
        g.push_back(geometry_from_road_angles({gamma, alpha, beta, 0.0}));
      }
    }
  }
  return g;
}

SpectralDataset simulate(const std::string& model_name, std::map<std::string, double> p, const NoiseModel& noise,
                         std::uint64_t seed = 7) {
  auto model = std::shared_ptr<const Model>(make_model(model_name));
  const SpectralModel sm(model, parameters_from_assignments(model->description(), p));
  SimulationInput in;
  in.model = &sm;
  in.geometries = grid();
  in.convention = AngleConvention::kRoad;
  for (double wl = 400; wl <= 2400; wl += 20) in.wavelengths.push_back(wl);
  in.noise = noise;
  in.seed = seed;
  return simulate_dataset(in);
}

TEST(Simulate, LambertValuesAndReproducibleNoise) {
  const SpectralDataset clean = simulate("lambert", {{"albedo", 0.4}}, {});
  for (double v : clean.brdf) EXPECT_NEAR(v, 0.4 / std::numbers::pi, 1e-15);
  EXPECT_FALSE(clean.has_sigma());
  NoiseModel noise;
  noise.relative = 0.02;
  noise.absolute = 1e-3;
  const SpectralDataset a = simulate("lambert", {{"albedo", 0.4}}, noise, 11);
  const SpectralDataset b = simulate("lambert", {{"albedo", 0.4}}, noise, 11);
  const SpectralDataset c = simulate("lambert", {{"albedo", 0.4}}, noise, 12);
  EXPECT_EQ(a.brdf, b.brdf);
  EXPECT_NE(a.brdf, c.brdf);
  // Standardised residuals are standard normal: mean 0 and variance 1 within sampling error.
  double sum = 0.0, sum2 = 0.0;
  const double f = 0.4 / std::numbers::pi;
  const double sigma = std::sqrt(std::pow(0.02 * f, 2) + 1e-6);
  for (std::size_t k = 0; k < a.brdf.size(); ++k) {
    EXPECT_NEAR(a.sigma[k], sigma, 1e-15);
    const double z = (a.brdf[k] - f) / sigma;
    sum += z;
    sum2 += z * z;
  }
  const double n = static_cast<double>(a.brdf.size());
  EXPECT_NEAR(sum / n, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(sum2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));
}

TEST(Simulate, NoiseShapeLargerAtEdgesAndWaterBands) {
  NoiseModel n = parse_noise_model("relative=0.01,edge=5,water=4");
  EXPECT_NEAR(n.shape(350), 5.0, 1e-6);  // 1 + 4 (1 + exp(-2150/60))
  EXPECT_NEAR(n.shape(1400), 4.0, 1e-3);
  EXPECT_LT(n.shape(1000), 1.01);
  EXPECT_THROW(parse_noise_model("relative=-1"), InputError);
  EXPECT_THROW(parse_noise_model("colour=1"), InputError);
}

TEST(Quality, CleanDataHasNoDefects) {
  for (const auto& [name, params] : std::vector<std::pair<std::string, std::map<std::string, double>>>{
           {"lambert", {{"albedo", 0.3}}}, {"oren-nayar", {{"albedo", 0.3}, {"sigma", 0.3}}}}) {
    NoiseModel noise;
    noise.relative = 0.005;
    const SpectralDataset d = simulate(name, params, noise);
    const QualityReport r = check_dataset(d);
    EXPECT_TRUE(r.outliers.empty()) << name << ": " << r.outliers.size() << " outliers, first #" << r.outliers[0].index;
    EXPECT_GT(r.reciprocity.size(), 10u) << name;
    EXPECT_EQ(r.reciprocity_flagged, 0u) << name;
    EXPECT_TRUE(r.noisy_bands.empty()) << name;
    EXPECT_EQ(r.negative_values, 0u);
    EXPECT_EQ(r.incidence_angles_deg, (std::vector<double>{0, 20, 40, 60, 80}));
    EXPECT_EQ(r.azimuth_planes_deg, (std::vector<double>{0, 45, 90, 135, 180}));
  }
}

TEST(Quality, ReciprocityPairsAreSwappedGeometries) {
  const SpectralDataset d = simulate("lambert", {{"albedo", 0.3}}, {});
  const QualityReport r = check_dataset(d);
  for (const auto& p : r.reciprocity) {
    const Geometry& a = d.geometries[p.a];
    const Geometry& b = d.geometries[p.b];
    EXPECT_NEAR(a.theta_i, b.theta_r, 1e-9);
    EXPECT_NEAR(a.theta_r, b.theta_i, 1e-9);
    EXPECT_NE(p.a, p.b);
    EXPECT_EQ(p.disagreement, 0.0);
  }
}

TEST(Quality, FindsPlantedReciprocityViolationAndOutlier) {
  NoiseModel noise;
  noise.relative = 0.005;
  SpectralDataset d = simulate("oren-nayar", {{"albedo", 0.3}, {"sigma", 0.3}}, noise);
  const QualityReport clean = check_dataset(d);
  ASSERT_FALSE(clean.reciprocity.empty());
  // Plant 1: one member of a reciprocity pair 30 % too bright.
  const ReciprocityPair target = clean.reciprocity[clean.reciprocity.size() / 2];
  const std::size_t m = d.wavelength_count();
  for (std::size_t j = 0; j < m; ++j) d.brdf[target.b * m + j] *= 1.3;
  // Plant 2: stray light at one interior geometry (gamma 40, alpha 50, beta 90): 2.5 x.
  const Geometry stray = geometry_from_road_angles({40.0, 50.0, 90.0, 0.0});
  std::size_t planted = d.geometry_count();
  for (std::size_t g = 0; g < d.geometry_count(); ++g) {
    if (length(d.geometries[g].wi - stray.wi) < 1e-9 && length(d.geometries[g].wr - stray.wr) < 1e-9) planted = g;
  }
  ASSERT_LT(planted, d.geometry_count());
  ASSERT_NE(planted, target.b);
  for (std::size_t j = 0; j < m; ++j) d.brdf[planted * m + j] *= 2.5;
  const QualityReport r = check_dataset(d);
  std::size_t flagged = 0;
  for (const auto& p : r.reciprocity) {
    if (!p.flagged) continue;
    ++flagged;
    EXPECT_TRUE((p.a == target.a && p.b == target.b) || p.a == planted || p.b == planted);
  }
  EXPECT_GE(flagged, 1u);
  bool found_target = false;
  for (const auto& p : r.reciprocity) found_target |= p.flagged && p.a == target.a && p.b == target.b;
  EXPECT_TRUE(found_target);
  ASSERT_FALSE(r.outliers.empty());
  bool found = false;
  for (const auto& o : r.outliers) {
    if (o.index == planted) {
      found = true;
      EXPECT_GT(o.ratio, 1.6);
    } else {
      EXPECT_EQ(o.index, target.b);  // the 1.3 x geometry is the only other candidate
    }
  }
  EXPECT_TRUE(found);
}

TEST(Quality, FlagsNoisyWaterBandsOnly) {
  NoiseModel noise;
  noise.relative = 0.004;
  noise.water_factor = 25.0;  // 10 % noise at the band centres: SNR ~ 10
  const SpectralDataset d = simulate("lambert", {{"albedo", 0.3}}, noise);
  const QualityReport r = check_dataset(d);
  ASSERT_EQ(r.noisy_bands.size(), 2u);
  EXPECT_LE(r.noisy_bands[0].lower_nm, 1400.0);
  EXPECT_GE(r.noisy_bands[0].upper_nm, 1400.0);
  EXPECT_LE(r.noisy_bands[1].lower_nm, 1900.0);
  EXPECT_GE(r.noisy_bands[1].upper_nm, 1900.0);
  EXPECT_GT(r.noisy_bands[0].lower_nm, 1200.0);
  EXPECT_LT(r.noisy_bands[1].upper_nm, 2100.0);
}

TEST(Quality, PanelValidationAgainstRhoOverPi) {
  SpectralDataset d = simulate("lambert", {{"albedo", 0.9}}, {});
  const spectra::Spectrum rho("rho", {300, 2500}, {0.9, 0.9});
  QualityOptions o;
  o.panel_reflectance = rho;
  const QualityReport clean = check_dataset(d, o);
  ASSERT_TRUE(clean.panel);
  EXPECT_NEAR(clean.panel->overall_max_abs, 0.0, 1e-12);
  d.brdf[5] *= 1.1;
  const QualityReport r = check_dataset(d, o);
  EXPECT_NEAR(r.panel->overall_max_abs, 0.1, 1e-12);
  EXPECT_NEAR(r.panel->max_abs_relative_deviation[0], 0.1, 1e-12);
}

}  // namespace
}  // namespace roadbrdf
