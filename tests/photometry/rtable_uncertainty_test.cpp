// Uncertainties of the r-table figures Q0, S1, S2, Qd and the class probabilities
// (photometry/rtable_uncertainty.h). References, independent of the code under test:
//  - brute-force sampling of a correlated Oren-Nayar parameter distribution at two wavelengths
//    (standard deviations of the figures of the sampled tables, compute_rtable);
//  - closed forms of a Lambertian surface of albedo rho: r = (rho/pi) cos^3(gamma), so Q0 = Qd = rho/pi
//    are linear in rho (u(Q0) = Q0 u(rho)/rho) and S1 = 5^-1.5, S2 = 1 do not depend on it (u = 0);
//    qualitative Oren-Nayar is linear in its albedo too, so with sigma fixed the same holds;
//  - for the photometric weighting, the coefficients dQ0/drho_j of a Lambertian fit taken from
//    compute_rtable itself (Q0 is linear in rho_j, so one difference is exact);
//  - the standard normal distribution function at tabulated points (Phi(1) = 0.8413447460685429).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_request.h"
#include "roadbrdf/photometry/rtable_uncertainty.h"
#include "support/cli.h"
#include "support/scratch.h"
#include "support/statistics.h"

namespace roadbrdf::photometry {
namespace {

SpectralWeighting at_wavelength(double nm) {
  SpectralWeighting w;
  w.kind = SpectralWeighting::Kind::wavelength;
  w.wavelength_nm = nm;
  return w;
}

// Both propagations; uncertainty_of() the value (wavelengths independent).
RTableUncertainty both_of(const SpectralModel& sm, const SpectralWeighting& w) {
  const std::optional<RTableUncertainty> u = summary_uncertainty(sm, w, compute_rtable(sm, w));
  EXPECT_TRUE(u.has_value());
  return u.value_or(RTableUncertainty{});
}
SummaryUncertainty uncertainty_of(const SpectralModel& sm, const SpectralWeighting& w) {
  return both_of(sm, w).independent;
}

using test::sample_standard_deviation;

TEST(RTableUncertainty, LinearisedAgreesWithSamplingTheParameterDistribution) {
  // Oren-Nayar fitted at 500 and 600 nm (albedo 0.5 +- 0.01, sigma 0.3 +- 0.05, correlation 0.6;
  // albedo 0.4 +- 0.02, sigma 0.35 +- 0.04, correlation -0.3), the table at 530 nm (parameters
  // 0.7 p(500) + 0.3 p(600)): both wavelengths contribute. 4000 draws of the two independent normal
  // distributions (Cholesky factors); the sampling error of a standard deviation is 1/sqrt(2N) =
  // 1.1 %, the tolerance 5 % also covers the curvature in sigma.
  const std::shared_ptr<const Model> model = make_model("oren-nayar");
  const std::vector<double> wavelengths = {500.0, 600.0};
  const std::vector<double> mean = {0.5, 0.3, 0.4, 0.35};
  const double u_a[2] = {0.01, 0.02}, u_s[2] = {0.05, 0.04}, rho[2] = {0.6, -0.3};
  SpectralModel sm(model, wavelengths, mean);
  std::vector<double> covariance;
  for (int j = 0; j < 2; ++j) {
    const double c = rho[j] * u_a[j] * u_s[j];
    covariance.insert(covariance.end(), {u_a[j] * u_a[j], c, c, u_s[j] * u_s[j]});
  }
  sm.set_parameter_covariance(covariance);
  const SpectralWeighting w = at_wavelength(530.0);
  const SummaryUncertainty u = uncertainty_of(sm, w);

  constexpr std::size_t kSamples = 4000;
  NormalStream normal(2026);
  std::vector<double> q0s, s1s, s2s, qds;
  for (std::size_t n = 0; n < kSamples; ++n) {
    std::vector<double> p;
    for (int j = 0; j < 2; ++j) {
      const double z1 = normal.next(), z2 = normal.next();
      p.push_back(mean[2 * j] + u_a[j] * z1);
      p.push_back(mean[2 * j + 1] + u_s[j] * (rho[j] * z1 + std::sqrt(1.0 - rho[j] * rho[j]) * z2));
    }
    const RTable t = compute_rtable(SpectralModel(model, wavelengths, p), w);
    q0s.push_back(q0(t));
    s1s.push_back(s1(t));
    s2s.push_back(s2(t));
    qds.push_back(qd(t));
  }
  EXPECT_NEAR(u.q0, sample_standard_deviation(q0s), 0.05 * sample_standard_deviation(q0s));
  EXPECT_NEAR(u.s1, sample_standard_deviation(s1s), 0.05 * sample_standard_deviation(s1s));
  EXPECT_NEAR(u.s2, sample_standard_deviation(s2s), 0.05 * sample_standard_deviation(s2s));
  EXPECT_NEAR(u.qd, sample_standard_deviation(qds), 0.05 * sample_standard_deviation(qds));
  EXPECT_GT(u.s1, 1e-3);  // sigma moves S1: the comparison is not between two zeros
}

// The propagation's gradient is the model's own; the reference here is central differences of the
// figures of whole tables (compute_rtable) at p_jk +- h, written in the test. Hapke (HG, SHOE, all four
// parameters free) fitted at 500 and 600 nm with correlated errors, the table at 530 nm.
TEST(RTableUncertainty, GradientPropagationEqualsCentralDifferencesOfTheTables) {
  const std::shared_ptr<const Model> model = make_model("hapke", {{"h_function", "hapke2002"}, {"phase", "hg"}});
  const std::size_t P = model->parameter_count();
  ASSERT_EQ(P, 4u);  // w, b0, h, xi
  const std::vector<double> wavelengths = {500.0, 600.0};
  const std::vector<double> params = {0.6, 0.4, 0.1, -0.2, 0.5, 0.5, 0.08, -0.3};
  const std::vector<double> u = {0.01, 0.05, 0.01, 0.03, 0.02, 0.04, 0.02, 0.02};
  std::vector<double> covariance(2 * P * P, 0.0);
  for (std::size_t j = 0; j < 2; ++j) {
    for (std::size_t a = 0; a < P; ++a) {
      for (std::size_t b = 0; b < P; ++b) {
        const double correlation = a == b ? 1.0 : (a + b == 3 ? 0.4 : -0.2);
        covariance[(j * P + a) * P + b] = correlation * u[j * P + a] * u[j * P + b];
      }
    }
  }
  SpectralModel sm(model, wavelengths, params);
  sm.set_parameter_covariance(covariance);
  const SpectralWeighting w = at_wavelength(530.0);
  const SummaryUncertainty propagated = uncertainty_of(sm, w);

  auto figures = [&](const std::vector<double>& p) {
    const RTable t = compute_rtable(SpectralModel(model, wavelengths, p), w);
    return std::array<double, 4>{q0(t), s1(t), s2(t), qd(t)};
  };
  std::array<double, 4> variance{};
  for (std::size_t j = 0; j < 2; ++j) {
    std::array<std::vector<double>, 4> g;
    for (std::size_t k = 0; k < P; ++k) {
      const double h = 1e-5;
      std::vector<double> up = params, down = params;
      up[j * P + k] += h;
      down[j * P + k] -= h;
      const std::array<double, 4> fu = figures(up), fd = figures(down);
      for (std::size_t f = 0; f < 4; ++f) g[f].push_back((fu[f] - fd[f]) / (2.0 * h));
    }
    for (std::size_t f = 0; f < 4; ++f) {
      for (std::size_t a = 0; a < P; ++a) {
        for (std::size_t b = 0; b < P; ++b) variance[f] += g[f][a] * covariance[(j * P + a) * P + b] * g[f][b];
      }
    }
  }
  EXPECT_NEAR(propagated.q0, std::sqrt(variance[0]), 0.01 * std::sqrt(variance[0]));
  EXPECT_NEAR(propagated.s1, std::sqrt(variance[1]), 0.01 * std::sqrt(variance[1]));
  EXPECT_NEAR(propagated.s2, std::sqrt(variance[2]), 0.01 * std::sqrt(variance[2]));
  EXPECT_NEAR(propagated.qd, std::sqrt(variance[3]), 0.01 * std::sqrt(variance[3]));
  EXPECT_GT(propagated.s1, 1e-4);  // not a comparison of zeros
}

TEST(RTableUncertainty, LambertQ0IsLinearInTheAlbedoAndS1DoesNotDependOnIt) {
  const std::shared_ptr<const Model> lambert = make_model("lambert");
  // Q0 = rho / pi, linear in rho.
  const double q = q0(compute_rtable(*lambert, {0.4}));
  EXPECT_NEAR(q, 0.4 / kPi, 1e-12);
  EXPECT_NEAR(q0(compute_rtable(*lambert, {0.8})), 2.0 * q, 1e-12);
  // At 550 nm, halfway between 500 and 600: rho = (0.3 + 0.5) / 2, u^2(rho) = (1e-4 + 4e-4) / 4.
  SpectralModel sm(lambert, {500.0, 600.0}, {0.3, 0.5});
  sm.set_parameter_covariance({1e-4, 4e-4});
  const SummaryUncertainty u = uncertainty_of(sm, at_wavelength(550.0));
  const double rho = 0.4, u_rho = std::sqrt(5e-4) / 2.0;
  const double q0_value = rho / kPi;
  EXPECT_NEAR(u.q0, q0_value * u_rho / rho, 1e-12);
  EXPECT_NEAR(u.qd, q0_value * u_rho / rho, 1e-12);  // Qd = rho / pi as well
  EXPECT_NEAR(u.s1, 0.0, 1e-12);
  EXPECT_NEAR(u.s2, 0.0, 1e-12);
}

TEST(RTableUncertainty, PhotometricWeightingOfLambertIsTheSumOverTheFitWavelengths) {
  // Five bands covering the luminous integral; Q0 = sum_j c_j rho_j with c_j = dQ0/drho_j taken from
  // compute_rtable (exact: linear), so u^2(Q0) = sum_j c_j^2 u_j^2 for independent bands and
  // u(Q0) = sum_j c_j u_j (c_j > 0) for errors fully correlated across them.
  const std::shared_ptr<const Model> lambert = make_model("lambert");
  const std::vector<double> wavelengths = {360.0, 450.0, 550.0, 650.0, 830.0};
  const std::vector<double> rho = {0.2, 0.25, 0.3, 0.35, 0.4};
  const std::vector<double> u_rho = {0.01, 0.02, 0.015, 0.03, 0.05};
  const SpectralWeighting photometric;  // CIE A
  const double base = q0(compute_rtable(SpectralModel(lambert, wavelengths, rho), photometric));
  double sum = 0.0, bound = 0.0;
  for (std::size_t j = 0; j < rho.size(); ++j) {
    std::vector<double> moved = rho;
    moved[j] += 0.1;
    const double c = (q0(compute_rtable(SpectralModel(lambert, wavelengths, moved), photometric)) - base) / 0.1;
    EXPECT_GT(c, 0.0) << j;
    sum += c * c * u_rho[j] * u_rho[j];
    bound += c * u_rho[j];
  }
  SpectralModel sm(lambert, wavelengths, rho);
  std::vector<double> covariance;
  for (double x : u_rho) covariance.push_back(x * x);
  sm.set_parameter_covariance(covariance);
  const RTableUncertainty u = both_of(sm, photometric);
  EXPECT_NEAR(u.independent.q0, std::sqrt(sum), 1e-9 * std::sqrt(sum));
  EXPECT_NEAR(u.correlated.q0, bound, 1e-9 * bound);
  EXPECT_GT(u.correlated.q0, 1.5 * u.independent.q0);  // the two cases differ here
  EXPECT_NEAR(u.independent.s1, 0.0, 1e-12);
  EXPECT_NEAR(u.correlated.s1, 0.0, 1e-12);
}

TEST(RTableUncertainty, FixedParametersAndWavelengthsOutsideTheWeightingContributeNothing) {
  // Qualitative Oren-Nayar (eq. 32, no interreflection term in rho^2) is linear in its albedo: with
  // sigma fixed (variance 0, its rows and columns 0), u(Q0) = Q0 u(rho) / rho and S1, S2 do not move.
  // 700 nm lies outside the table's 550 nm (between 500 and 600): its variance, however large,
  // changes nothing.
  const std::shared_ptr<const Model> model = make_model("oren-nayar", {{"form", "qualitative"}});
  SpectralModel sm(model, {500.0, 600.0, 700.0}, {0.4, 0.3, 0.4, 0.3, 0.9, 0.6});
  sm.set_parameter_covariance({4e-4, 0, 0, 0, 4e-4, 0, 0, 0, 0.04, 0.01, 0.01, 0.04});
  const SpectralWeighting w = at_wavelength(550.0);
  const double q = q0(compute_rtable(sm, w));
  const SummaryUncertainty u = uncertainty_of(sm, w);
  const double u_rho = std::sqrt(2.0 * 4e-4) / 2.0;  // (rho_500 + rho_600) / 2
  EXPECT_NEAR(u.q0, q * u_rho / 0.4, 1e-12);
  EXPECT_NEAR(u.s1, 0.0, 1e-12);
  EXPECT_NEAR(u.s2, 0.0, 1e-12);
  // An undefined covariance where the table depends on it: undefined, never a number.
  sm.set_parameter_covariance({std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, 4e-4, 0, 0, 0, 0.04, 0, 0, 0.04});
  EXPECT_TRUE(std::isnan(uncertainty_of(sm, w).q0));
  // A model given by its parameters has no covariance: no uncertainty.
  const SpectralModel plain(model, {0.4, 0.3});
  EXPECT_FALSE(summary_uncertainty(plain, SpectralWeighting{}, compute_rtable(plain, SpectralWeighting{})));
}

TEST(RTableUncertainty, ClassProbabilitiesAreNormalProbabilitiesBetweenTheS1Limits) {
  // S1 = 0.80 +- 0.05 in the R system: R2 [0.42, 0.85), R3 [0.85, 1.35) one standard deviation away.
  const double phi1 = 0.8413447460685429;  // Phi(1)
  const std::vector<ClassProbability> p = class_probabilities(0.80, 0.05, ClassSystem::R);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].name, "R1");
  EXPECT_EQ(p[2].name, "R3");
  EXPECT_NEAR(p[0].probability, 0.0, 1e-12);  // Phi(-7.6)
  EXPECT_NEAR(p[1].probability, phi1, 1e-12);
  EXPECT_NEAR(p[2].probability, 1.0 - phi1, 1e-12);
  EXPECT_NEAR(p[3].probability, 0.0, 1e-12);  // beyond 11 standard deviations
  // Two classes of the C system around their limit 0.40: Phi(-0.5) = 0.3085375387259869.
  const std::vector<ClassProbability> c = class_probabilities(0.45, 0.1, ClassSystem::C);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].probability, 0.3085375387259869, 1e-12);
  EXPECT_NEAR(c[1].probability, 1.0 - 0.3085375387259869, 1e-12);
  for (ClassSystem system : {ClassSystem::R, ClassSystem::N, ClassSystem::C}) {
    for (double s : {0.05, 0.3, 0.6, 1.3, 2.0}) {
      double sum = 0.0;
      for (const ClassProbability& x : class_probabilities(s, 0.2, system)) sum += x.probability;
      EXPECT_NEAR(sum, 1.0, 1e-12) << s;
    }
  }
  // No uncertainty: certainty for the class classify() gives, also exactly at a limit.
  const std::vector<ClassProbability> exact = class_probabilities(0.85, 0.0);
  EXPECT_EQ(exact[2].probability, 1.0);
  EXPECT_EQ(exact[1].probability, 0.0);
  EXPECT_THROW(class_probabilities(0.5, -0.1), InputError);
  EXPECT_THROW(class_probabilities(0.5, std::numeric_limits<double>::quiet_NaN()), InputError);
  EXPECT_THROW(class_probabilities(std::numeric_limits<double>::infinity(), 0.1), InputError);
}

TEST(RTableUncertainty, ReportListsTheClassesOfAtLeastOnePercent) {
  RTableReport report;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  report.uncertainty = RTableUncertainty{{0.001, 0.05, 0.02, nan}, {0.002, 0.1, 0.04, nan}};
  report.class_system = "R";
  report.class_probabilities = class_probabilities(0.80, 0.05);
  const nlohmann::json j = report.uncertainty_json();
  EXPECT_EQ(j["S1"].get<double>(), 0.05);
  EXPECT_TRUE(j["Qd"].is_null());
  EXPECT_EQ(j["correlated"]["S1"].get<double>(), 0.1);
  ASSERT_EQ(j["class_probabilities"].size(), 2u);  // R1 and R4 are below 1 %
  EXPECT_EQ(j["class_probabilities"][0]["class"], "R2");
  EXPECT_EQ(j["class_probabilities"][1]["class"], "R3");
  EXPECT_NEAR(j["class_probabilities"][1]["probability"].get<double>(), 0.15865525393145707, 1e-12);
  EXPECT_TRUE(RTableReport{}.uncertainty_json().is_null());
}

TEST(RTableUncertainty, NoClassProbabilityWhenEveryStandardCellIsExtrapolated) {
  // Every r-table cell is seen at theta_r = 90 - alpha = 89 deg; a fit measured up to theta_r = 80 deg
  // (beyond the 5 deg tolerance) covers none of them, so its covariance says nothing about the class.
  SpectralModel sm(make_model("oren-nayar"), {550.0}, {0.4, 0.3});
  sm.set_parameter_covariance({1e-4, 0.0, 0.0, 2.5e-3});
  RTableRequest request;
  request.wavelength = 550.0;
  const RTableReport unknown_coverage = rtable_report(sm, request);
  EXPECT_FALSE(unknown_coverage.class_probabilities.empty());
  EXPECT_FALSE(unknown_coverage.to_json()["extrapolated"].get<bool>());
  AngularCoverage measured;
  measured.theta_i_min_deg = 0.0;
  measured.theta_i_max_deg = 80.0;
  measured.theta_r_min_deg = 0.0;
  measured.theta_r_max_deg = 80.0;
  measured.azimuth_planes_deg = {0.0, 45.0, 90.0, 135.0, 180.0};
  measured.geometries = 89;
  sm.set_coverage(measured);
  const RTableReport report = rtable_report(sm, request);
  ASSERT_TRUE(report.uncertainty);
  EXPECT_TRUE(report.class_probabilities.empty());
  const nlohmann::json j = report.to_json();
  EXPECT_TRUE(j["extrapolated"].get<bool>());
  EXPECT_TRUE(j["uncertainty"]["class_probabilities"].is_null());
  EXPECT_NE(report.summary_text().find("class probability: none (extrapolated"), std::string::npos);
}

std::string oren_nayar_fit(const test::ScratchDirectory& scratch) {
  const std::string path = (scratch.path() / "on.fit.json").string();
  std::ofstream(path) << R"({"format": "roadbrdf-fit", "version": 1, "best": "oren-nayar", "fits": [{
    "model": "oren-nayar", "options": {}, "wavelengths": [550],
    "parameters": {"albedo": [0.4], "sigma": [0.3]},
    "stderr": {"albedo": [0.01], "sigma": [0.05]},
    "parameter_order": ["albedo", "sigma"], "fixed": [],
    "correlation": [[[1, 0.6], [0.6, 1]]]}]})";
  return path;
}

TEST(RTableUncertaintyCli, JsonAndTextCarryTheUncertainties) {
  const test::ScratchDirectory scratch;
  const std::string fit = oren_nayar_fit(scratch);
  // The library's values for the fit file, against which the command's output is checked.
  RTableRequest request;
  const RTableReport expected = rtable_report(read_fit_file(fit), request);
  ASSERT_TRUE(expected.uncertainty);
  const test::CliResult json = test::run_shell(test::cli_program() + " rtable " + fit + " --json 2>/dev/null");
  ASSERT_EQ(json.status, 0) << json.output;
  const nlohmann::json j = nlohmann::json::parse(json.output);
  const nlohmann::json& u = j.at("uncertainty");
  const SummaryUncertainty& e = expected.uncertainty->independent;
  EXPECT_DOUBLE_EQ(u["Q0"].get<double>(), e.q0);
  EXPECT_DOUBLE_EQ(u["S1"].get<double>(), e.s1);
  // One wavelength: the correlated bound is the same number.
  EXPECT_DOUBLE_EQ(u["correlated"]["S1"].get<double>(), e.s1);
  EXPECT_GT(u["S1"].get<double>(), 0.0);
  EXPECT_EQ(u["class_probabilities"][0]["class"], j["class"]);
  EXPECT_NE(u["method"].get<std::string>().find("GUM"), std::string::npos);
  EXPECT_TRUE(j["units"].contains("uncertainty"));
  const test::CliResult text = test::run_cli("rtable " + fit + " -o " + (scratch.path() / "t.csv").string());
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find(fmt::format("u(Q0) = {:.3g} sr^-1, u(S1) = {:.3g}", e.q0, e.s1)), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("class probability (R, S1 normal with u(S1)): R1 1.000"), std::string::npos)
      << text.output;
  // A model given by its parameters: null, and no uncertainty line.
  const test::CliResult plain =
      test::run_shell(test::cli_program() + " rtable oren-nayar -p albedo=0.4 -p sigma=0.3 --json 2>/dev/null");
  ASSERT_EQ(plain.status, 0) << plain.output;
  EXPECT_TRUE(nlohmann::json::parse(plain.output)["uncertainty"].is_null());
  const test::CliResult plain_text = test::run_cli("rtable oren-nayar -p albedo=0.4 -p sigma=0.3");
  EXPECT_EQ(plain_text.output.find("u(Q0)"), std::string::npos) << plain_text.output;
}

}  // namespace
}  // namespace roadbrdf::photometry
