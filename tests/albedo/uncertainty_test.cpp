// Albedo uncertainties from the fit's parameter covariance (albedo/uncertainty.h): the Lambertian
// closed form (A = albedo exactly, so u(A) = u(albedo)), brute-force sampling of a correlated
// Oren-Nayar parameter distribution, and the covariance read from a fit file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "support/scratch.h"
#include "support/statistics.h"

namespace roadbrdf {
namespace {

TEST(AlbedoUncertainty, LambertIsTheAlbedoUncertaintyForEverySky) {
  SpectralModel sm(make_model("lambert"), {500.0, 600.0}, {0.3, 0.5});
  sm.set_parameter_covariance({1e-4, 4e-4});  // u = 0.01 and 0.02
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {0.0, 60.0};
  request.diffuse_fraction = "0.3";
  const nlohmann::json j = albedo::compute_albedo(sm, request);
  const auto& u = j.at("uncertainty");
  for (std::size_t z = 0; z < 2; ++z) {
    EXPECT_NEAR(u["black_sky"][z][0].get<double>(), 0.01, 1e-9);
    EXPECT_NEAR(u["black_sky"][z][1].get<double>(), 0.02, 1e-9);
    EXPECT_NEAR(u["blue_sky"][z][1].get<double>(), 0.02, 1e-9);  // both integrals move with the albedo
  }
  EXPECT_NEAR(u["white_sky"][0].get<double>(), 0.01, 1e-9);
  EXPECT_NEAR(u["white_sky"][1].get<double>(), 0.02, 1e-9);
  // Undefined covariance: null, never a number.
  sm.set_parameter_covariance({std::numeric_limits<double>::quiet_NaN(), 4e-4});
  const nlohmann::json k = albedo::compute_albedo(sm, request);
  EXPECT_TRUE(k["uncertainty"]["white_sky"][0].is_null());
  EXPECT_NEAR(k["uncertainty"]["white_sky"][1].get<double>(), 0.02, 1e-9);
  // A model given by its parameters has none.
  EXPECT_TRUE(albedo::compute_albedo(SpectralModel(make_model("lambert"), {0.4}), request)["uncertainty"].is_null());
  EXPECT_THROW(sm.set_parameter_covariance({1.0}), InputError);
}

TEST(AlbedoUncertainty, LinearisedAgreesWithSamplingTheParameterDistribution) {
  // Oren-Nayar, albedo 0.5 +- 0.01 and sigma 0.3 +- 0.05, correlation 0.6: the standard deviation of
  // the black-sky albedo (30 deg) and white-sky albedo over 4000 parameter sets drawn from that
  // normal distribution (Cholesky factor), against the linearised value. The sampling error of a
  // standard deviation is 1/sqrt(2N) = 1.1 %; the tolerance 5 % also covers the curvature in sigma.
  const std::shared_ptr<const Model> model = make_model("oren-nayar");
  const double s_a = 0.01, s_s = 0.05, r = 0.6;
  SpectralModel sm(model, {550.0}, {0.5, 0.3});
  sm.set_parameter_covariance({s_a * s_a, r * s_a * s_s, r * s_a * s_s, s_s * s_s});
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {30.0};
  const nlohmann::json j = albedo::compute_albedo(sm, request);
  const double u_black = j["uncertainty"]["black_sky"][0][0].get<double>();
  const double u_white = j["uncertainty"]["white_sky"][0].get<double>();

  constexpr std::size_t kSamples = 4000;
  NormalStream normal(2024);
  std::vector<double> sets;
  for (std::size_t k = 0; k < kSamples; ++k) {
    const double z1 = normal.next(), z2 = normal.next();
    sets.push_back(0.5 + s_a * z1);
    sets.push_back(0.3 + s_s * (r * z1 + std::sqrt(1.0 - r * r) * z2));
  }
  const double sampled_black =
      test::sample_standard_deviation(albedo::black_sky(*model, sets.data(), kSamples, 30.0 * kDegree).value);
  const double sampled_white = test::sample_standard_deviation(albedo::white_sky(*model, sets.data(), kSamples).value);
  EXPECT_NEAR(u_black, sampled_black, 0.05 * sampled_black);
  EXPECT_NEAR(u_white, sampled_white, 0.05 * sampled_white);
  EXPECT_GT(u_black, 0.5 * s_a);  // the albedo term alone would give about s_a x (black-sky at albedo 1)
}

TEST(AlbedoUncertainty, BroadbandOfLambertUnderAFlatSpectrumIsTheTrapezoidRuleOfTheBandUncertainties) {
  // A flat spectrum over 400-600 nm with bands at 400, 500, 600 nm: the broadband value is the
  // trapezoid mean (A400 + 2 A500 + A600) / 4, so u^2 = (u400^2 + 4 u500^2 + u600^2) / 16 for
  // independent bands and u = (u400 + 2 u500 + u600) / 4 fully correlated (Lambert: A = albedo).
  const test::ScratchDirectory scratch;
  const std::string flat = (scratch.path() / "flat.csv").string();
  std::ofstream(flat) << "wavelength_nm,irradiance\n300,1\n700,1\n";
  SpectralModel sm(make_model("lambert"), {400.0, 500.0, 600.0}, {0.3, 0.4, 0.5});
  sm.set_parameter_covariance({1e-4, 4e-4, 9e-4});  // u = 0.01, 0.02, 0.03
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {20.0};
  request.diffuse_fraction = "0.3";
  request.spectrum = flat;
  const nlohmann::json j = albedo::compute_albedo(sm, request);
  EXPECT_NEAR(j["broadband"]["white_sky"].get<double>(), (0.3 + 0.8 + 0.5) / 4, 1e-12);
  const auto& bb = j.at("uncertainty").at("broadband");
  const double independent = std::sqrt(1e-4 + 4.0 * 4e-4 + 9e-4) / 4.0, correlated = (0.01 + 0.04 + 0.03) / 4.0;
  for (const nlohmann::json& u : {bb["white_sky"], bb["black_sky"][0], bb["blue_sky"][0]}) {
    EXPECT_NEAR(u["independent"].get<double>(), independent, 1e-9);
    EXPECT_NEAR(u["correlated"].get<double>(), correlated, 1e-9);
  }
  EXPECT_NE(albedo::albedo_table(j).find("u 1.27e-02 (correlated 2.00e-02)"), std::string::npos)
      << albedo::albedo_table(j);
}

TEST(AlbedoUncertainty, BroadbandBlueSkyOfSpectrl2IsTheDerivativeOfTheBroadbandValue) {
  // SPECTRL2 blue-sky weighs black-sky by the direct and white-sky by the diffuse spectrum. For
  // Lambert the broadband value is linear in the band albedos; its derivatives are taken here from
  // the broadband values themselves (finite differences of compute_albedo), independently of the
  // coefficients, and u^2 = sum_k (dB/dA_k)^2 u_k^2.
  const std::vector<double> wavelengths = {400.0, 550.0, 700.0, 900.0};
  const std::vector<double> albedos = {0.2, 0.3, 0.35, 0.4};
  const std::vector<double> u = {0.01, 0.02, 0.015, 0.03};
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {40.0};
  request.atmosphere = "spectrl2";
  auto broadband_blue = [&](const std::vector<double>& a) {
    return albedo::compute_albedo(SpectralModel(make_model("lambert"), wavelengths, a),
                                  request)["broadband"]["blue_sky"][0]
        .get<double>();
  };
  double sum = 0.0, bound = 0.0;
  for (std::size_t k = 0; k < albedos.size(); ++k) {
    std::vector<double> up = albedos, down = albedos;
    up[k] += 0.01;
    down[k] -= 0.01;
    const double derivative = (broadband_blue(up) - broadband_blue(down)) / 0.02;
    sum += derivative * derivative * u[k] * u[k];
    bound += std::abs(derivative) * u[k];
  }
  SpectralModel sm(make_model("lambert"), wavelengths, albedos);
  sm.set_parameter_covariance({u[0] * u[0], u[1] * u[1], u[2] * u[2], u[3] * u[3]});
  const nlohmann::json j = albedo::compute_albedo(sm, request);
  const auto& bb = j.at("uncertainty").at("broadband").at("blue_sky")[0];
  EXPECT_NEAR(bb["independent"].get<double>(), std::sqrt(sum), 1e-9);
  EXPECT_NEAR(bb["correlated"].get<double>(), bound, 1e-9);
}

TEST(AlbedoUncertainty, CovarianceIsReadFromTheFitFile) {
  const test::ScratchDirectory scratch;
  const std::string path = (scratch.path() / "f.fit.json").string();
  std::ofstream(path) << R"({"format": "roadbrdf-fit", "version": 1, "best": "oren-nayar", "fits": [{
    "model": "oren-nayar", "options": {}, "wavelengths": [500, 600],
    "parameters": {"albedo": [0.4, 0.5], "sigma": [0.2, 0.3]},
    "stderr": {"albedo": [0.01, 0.02], "sigma": [null, 0.1]},
    "parameter_order": ["albedo", "sigma"], "fixed": [],
    "correlation": [null, [[1, -0.5], [-0.5, 1]]]}]})";
  const SpectralModel sm = read_fit_file(path);
  const std::vector<double>& c = sm.parameter_covariance();
  ASSERT_EQ(c.size(), 8u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(std::isnan(c[k])) << k;  // 500 nm: undefined
  EXPECT_DOUBLE_EQ(c[4], 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(c[5], -0.5 * 0.02 * 0.1);
  EXPECT_DOUBLE_EQ(c[6], -0.5 * 0.02 * 0.1);
  EXPECT_DOUBLE_EQ(c[7], 0.1 * 0.1);
  // A fixed parameter has no uncertainty: its rows and columns are 0.
  const std::string fixed = (scratch.path() / "fixed.fit.json").string();
  std::ofstream(fixed) << R"({"format": "roadbrdf-fit", "version": 1, "best": "oren-nayar", "fits": [{
    "model": "oren-nayar", "options": {}, "wavelengths": [500],
    "parameters": {"albedo": [0.4], "sigma": [0.2]}, "stderr": {"albedo": [0.01], "sigma": [null]},
    "fixed": ["sigma"], "correlation": [[[1, null], [null, null]]]}]})";
  const std::vector<double> f = read_fit_file(fixed).parameter_covariance();
  ASSERT_EQ(f.size(), 4u);
  EXPECT_DOUBLE_EQ(f[0], 0.01 * 0.01);
  EXPECT_EQ(f[1], 0.0);
  EXPECT_EQ(f[2], 0.0);
  EXPECT_EQ(f[3], 0.0);
}

TEST(AlbedoReport, ResultsDoNotDependOnTheNumberOfThreads) {
  // The integrals run in parallel (one task per sun zenith and the white-sky one, the white-sky outer
  // nodes, then the gradients likewise), each deterministic and summed in a fixed order: one thread
  // and all of them give the same document, bit for bit, values and uncertainties (a Hapke fit of
  // three wavelengths with a covariance; 80 deg takes the grazing cross-check).
  const std::shared_ptr<const Model> model = make_model("hapke");
  const std::size_t P = model->parameter_count();
  std::vector<double> params;
  for (double w : {0.3, 0.5, 0.7}) {
    std::vector<double> p = model->description().default_parameters();
    p[0] = w;
    params.insert(params.end(), p.begin(), p.end());
  }
  SpectralModel sm(model, {500.0, 600.0, 700.0}, params);
  std::vector<double> covariance(3 * P * P, 0.0);
  for (std::size_t s = 0; s < 3; ++s) {
    for (std::size_t k = 0; k < P; ++k) covariance[s * P * P + k * P + k] = 1e-4;
  }
  sm.set_parameter_covariance(covariance);
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {0.0, 30.0, 60.0, 80.0};
  request.diffuse_fraction = "0.2";
  request.tolerance = 1e-4;
  request.threads = 1;
  const nlohmann::json one = albedo::compute_albedo(sm, request);
  request.threads = 0;
  const nlohmann::json all = albedo::compute_albedo(sm, request);
  ASSERT_FALSE(one.at("uncertainty").is_null());
  EXPECT_EQ(one.dump(), all.dump());
  request.threads = -1;
  EXPECT_THROW(albedo::compute_albedo(sm, request), FieldError);
}

TEST(AlbedoReport, ProgressCountsTheIntegralsOfEachPass) {
  // A model with a mirror lobe (Torrance-Sparrow) has its black-sky value at 80 deg cross-checked with
  // the mirror-polar rule, so that integral's gradient is integrated in a second pass, counted when it
  // becomes known; the other two (30 deg, white-sky) are integrated with their gradients in one pass.
  const std::shared_ptr<const Model> model = make_model("lambert+torrance-sparrow");
  ASSERT_TRUE(model->description().mirror_lobe);
  const std::vector<double> p = parameters_from_assignments(
      model->description(),
      {{"lambert.albedo", 0.3}, {"torrance-sparrow.ks", 0.2}, {"torrance-sparrow.roughness", 0.3}});
  SpectralModel sm(model, {550.0}, p);
  const std::size_t P = model->parameter_count();
  std::vector<double> covariance(P * P, 0.0);
  for (std::size_t k = 0; k < P; ++k) covariance[k * P + k] = 1e-6;
  sm.set_parameter_covariance(covariance);
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {30.0, 80.0};
  request.tolerance = 1e-4;
  request.threads = 1;  // every report made (core/progress.h)
  std::vector<std::pair<std::size_t, std::size_t>> progress;
  request.progress = [&](std::size_t done, std::size_t total) { progress.emplace_back(done, total); };
  const nlohmann::json j = albedo::compute_albedo(sm, request);
  EXPECT_EQ(progress, (std::vector<std::pair<std::size_t, std::size_t>>{{1, 3}, {2, 3}, {3, 3}, {4, 4}, {4, 4}}));
  EXPECT_TRUE(j.at("uncertainty").at("black_sky")[1][0].is_number());
}

}  // namespace
}  // namespace roadbrdf
