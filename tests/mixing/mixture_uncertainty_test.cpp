// Uncertainties of a mixture from its end-members' fits (mixing/mixture_covariance.h). References,
// independent of the code under test:
//  - the closed form of an areal mixture of Lambertian end-members: its white-sky albedo is
//    sum_k a_k rho_k, so u^2 = sum_k a_k^2 u^2(rho_k), with u^2(rho) = (u^2(rho_1) + u^2(rho_2)) / 4
//    halfway between two fit wavelengths (linear interpolation of independent values);
//  - brute-force sampling: the end-members' parameters drawn from their fits' normal distributions
//    (independently per end-member and wavelength, Cholesky factors), the whole mixing run again on
//    every draw (for hapke: the inversion of each drawn end-member's white-sky albedo too), and the
//    standard deviations of the albedos and r-table figures of the drawn mixtures.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mixing_test_util.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/mixing/mixture_covariance.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_uncertainty.h"
#include "support/scratch.h"
#include "support/statistics.h"

namespace {

using namespace mixtest;
using roadbrdf::test::sample_standard_deviation;

// A binder and one aggregate class, each with its own fit "path".
Formulation binder_and_aggregate() {
  Formulation f;
  f.name = "two";
  f.components.push_back(component("binder", ComponentKind::kBinder, 6.0, 1.03, 0, 0, "binder"));
  f.components.push_back(component("aggregate", ComponentKind::kAggregate, 94.0, 2.65, 0.0, 2.0, "aggregate"));
  return f;
}

MixResult mixed(const Formulation& f, const FitLoader& loader, Method method, MixInputs& inputs) {
  inputs = load_mix_inputs(f, loader);
  MixResult r = mix(inputs, method, {});
  attach_parameter_covariance(inputs, r);
  return r;
}

TEST(MixtureUncertainty, ArealLambertIsTheWeightedSumOfTheEndMembersVariances) {
  // The aggregate is fitted at 400 and 600 nm only: at 500 nm its albedo is interpolated.
  SpectralModel binder(make_model("lambert"), {400.0, 500.0, 600.0}, {0.05, 0.06, 0.07});
  binder.set_parameter_covariance({1e-4, 4e-4, 9e-4});  // u = 0.01, 0.02, 0.03
  SpectralModel aggregate(make_model("lambert"), {400.0, 600.0}, {0.4, 0.5});
  aggregate.set_parameter_covariance({16e-4, 25e-4});  // u = 0.04, 0.05
  MixInputs inputs;
  const MixResult r = mixed(binder_and_aggregate(), memory_loader({{"binder", binder}, {"aggregate", aggregate}}),
                            Method::kAreal, inputs);
  ASSERT_EQ(r.model->wavelengths(), (std::vector<double>{400.0, 500.0, 600.0}));
  const double a = r.weights[0], b = r.weights[1];
  const double expected[3] = {std::hypot(a * 0.01, b * 0.04), std::hypot(a * 0.02, b * std::sqrt(16e-4 + 25e-4) / 2.0),
                              std::hypot(a * 0.03, b * 0.05)};
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {0.0, 50.0};
  const nlohmann::json j = albedo::compute_albedo(*r.model, request);
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_NEAR(j["uncertainty"]["white_sky"][l].get<double>(), expected[l], 1e-9) << l;
    EXPECT_NEAR(j["uncertainty"]["black_sky"][1][l].get<double>(), expected[l], 1e-9) << l;
  }
  // Q0 of a Lambertian surface is A / pi.
  photometry::SpectralWeighting w;
  w.kind = photometry::SpectralWeighting::Kind::wavelength;
  w.wavelength_nm = 400.0;
  const auto u = photometry::summary_uncertainty(*r.model, w, photometry::compute_rtable(*r.model, w));
  ASSERT_TRUE(u.has_value());
  EXPECT_NEAR(u->independent.q0, expected[0] / kPi, 1e-9);
  EXPECT_NEAR(u->independent.s1, 0.0, 1e-12);
  // The interpolated end-member is said.
  bool said = false;
  for (const std::string& note : r.notes) said = said || note.find("'aggregate' is interpolated") != std::string::npos;
  EXPECT_TRUE(said);

  // MIX.json carries the covariance, and reading it back gives the same uncertainties.
  const roadbrdf::test::ScratchDirectory scratch;
  const std::string path = (scratch.path() / "m.mix.json").string();
  MixFileContent content;
  content.inputs = &inputs;
  content.results = {r};
  write_mix_file(path, content);
  const SpectralModel back = read_mix_file(path, "areal");
  ASSERT_EQ(back.parameter_covariance().size(), r.model->parameter_covariance().size());
  for (std::size_t i = 0; i < back.parameter_covariance().size(); ++i) {
    EXPECT_NEAR(back.parameter_covariance()[i], r.model->parameter_covariance()[i], 1e-15) << i;
  }
}

TEST(MixtureUncertainty, NoneWithoutTheEndMembersCovarianceOrForFittedWeights) {
  SpectralModel binder(make_model("lambert"), {400.0, 600.0}, {0.05, 0.07});
  binder.set_parameter_covariance({1e-4, 1e-4});
  const SpectralModel aggregate(make_model("lambert"), {400.0, 600.0}, {0.4, 0.5});  // no covariance
  MixInputs inputs;
  const MixResult r = mixed(binder_and_aggregate(), memory_loader({{"binder", binder}, {"aggregate", aggregate}}),
                            Method::kAreal, inputs);
  EXPECT_TRUE(r.model->parameter_covariance().empty());
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.back().find("end-member 'aggregate' has none"), std::string::npos) << r.notes.back();
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {30.0};
  EXPECT_TRUE(albedo::compute_albedo(*r.model, request)["uncertainty"].is_null());
  MixResult fitted = r;
  fitted.method = Method::kFitted;
  fitted.notes.clear();
  attach_parameter_covariance(inputs, fitted);
  EXPECT_TRUE(fitted.model->parameter_covariance().empty());
  ASSERT_EQ(fitted.notes.size(), 1u);
  EXPECT_NE(fitted.notes[0].find("fitted to the measured mixture"), std::string::npos);
}

// An Oren-Nayar fit at 500 and 600 nm: albedo and sigma with their standard errors and correlation.
struct OrenNayarFit {
  double albedo[2], sigma[2], u_albedo[2], u_sigma[2], correlation[2];

  SpectralModel model(roadbrdf::NormalStream* normal) const {
    std::vector<double> table;
    for (int j = 0; j < 2; ++j) {
      const double z1 = normal ? normal->next() : 0.0, z2 = normal ? normal->next() : 0.0;
      const double r = correlation[j];
      table.push_back(albedo[j] + u_albedo[j] * z1);
      table.push_back(sigma[j] + u_sigma[j] * (r * z1 + std::sqrt(1.0 - r * r) * z2));
    }
    SpectralModel sm(make_model("oren-nayar"), {500.0, 600.0}, table);
    std::vector<double> covariance;
    for (int j = 0; j < 2; ++j) {
      const double c = correlation[j] * u_albedo[j] * u_sigma[j];
      covariance.insert(covariance.end(), {u_albedo[j] * u_albedo[j], c, c, u_sigma[j] * u_sigma[j]});
    }
    sm.set_parameter_covariance(covariance);
    return sm;
  }
};

// The linearised uncertainties of a mixing method against the standard deviations over mixtures of
// drawn end-members: white-sky and black-sky (30 deg) albedo at both wavelengths, and Q0, S1, Qd of
// the r-table at 530 nm (parameters 0.7 p(500) + 0.3 p(600): both wavelengths contribute). 2000 draws:
// the sampling error of a standard deviation is 1/sqrt(2N) = 1.6 %; the tolerance 6 % also covers the
// curvature in sigma.
void expect_linearised_agrees_with_sampling(Method method) {
  const OrenNayarFit binder{{0.10, 0.12}, {0.25, 0.30}, {0.006, 0.008}, {0.05, 0.04}, {0.5, -0.3}};
  const OrenNayarFit aggregate{{0.45, 0.50}, {0.50, 0.45}, {0.02, 0.025}, {0.06, 0.05}, {-0.4, 0.2}};
  const Formulation f = binder_and_aggregate();
  MixInputs inputs;
  const MixResult r = mixed(
      f, memory_loader({{"binder", binder.model(nullptr)}, {"aggregate", aggregate.model(nullptr)}}), method, inputs);
  ASSERT_FALSE(r.model->parameter_covariance().empty());
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {30.0};
  const nlohmann::json j = albedo::compute_albedo(*r.model, request);
  photometry::SpectralWeighting w;
  w.kind = photometry::SpectralWeighting::Kind::wavelength;
  w.wavelength_nm = 530.0;
  const auto u = photometry::summary_uncertainty(*r.model, w, photometry::compute_rtable(*r.model, w));
  ASSERT_TRUE(u.has_value());

  constexpr std::size_t kSamples = 2000;
  roadbrdf::NormalStream normal(method == Method::kHapke ? 17 : 4);
  std::vector<double> params, q0s, s1s, qds;
  for (std::size_t n = 0; n < kSamples; ++n) {
    MixInputs drawn_inputs =
        load_mix_inputs(f, memory_loader({{"binder", binder.model(&normal)}, {"aggregate", aggregate.model(&normal)}}));
    const MixResult drawn = mix(drawn_inputs, method, {});
    const std::vector<double>& table = drawn.model->parameter_table();
    params.insert(params.end(), table.begin(), table.end());
    const photometry::RTable t = photometry::compute_rtable(*drawn.model, w);
    q0s.push_back(photometry::q0(t));
    s1s.push_back(photometry::s1(t));
    qds.push_back(photometry::qd(t));
  }
  const Model& mixture = r.model->model();
  const std::size_t P = mixture.parameter_count();
  for (std::size_t l = 0; l < 2; ++l) {
    std::vector<double> at_l;
    for (std::size_t n = 0; n < kSamples; ++n) {
      at_l.insert(at_l.end(), params.begin() + static_cast<std::ptrdiff_t>((2 * n + l) * P),
                  params.begin() + static_cast<std::ptrdiff_t>((2 * n + l + 1) * P));
    }
    const double white = sample_standard_deviation(albedo::white_sky(mixture, at_l.data(), kSamples).value);
    const double black =
        sample_standard_deviation(albedo::black_sky(mixture, at_l.data(), kSamples, 30.0 * kDegree).value);
    EXPECT_NEAR(j["uncertainty"]["white_sky"][l].get<double>(), white, 0.06 * white) << l;
    EXPECT_NEAR(j["uncertainty"]["black_sky"][0][l].get<double>(), black, 0.06 * black) << l;
  }
  EXPECT_NEAR(u->independent.q0, sample_standard_deviation(q0s), 0.06 * sample_standard_deviation(q0s));
  EXPECT_NEAR(u->independent.s1, sample_standard_deviation(s1s), 0.06 * sample_standard_deviation(s1s));
  EXPECT_NEAR(u->independent.qd, sample_standard_deviation(qds), 0.06 * sample_standard_deviation(qds));
  EXPECT_GT(u->independent.s1, 1e-3);  // the sigmas move S1: not a comparison of two zeros
}

TEST(MixtureUncertainty, ArealLinearisedAgreesWithSamplingTheEndMembersFits) {
  expect_linearised_agrees_with_sampling(Method::kAreal);
}

TEST(MixtureUncertainty, HapkeLinearisedAgreesWithSamplingTheEndMembersFits) {
  // The single-scattering albedos move with the drawn end-members (their inversion is run again on
  // every draw), so this checks their variance and covariances with the end-members' parameters too.
  expect_linearised_agrees_with_sampling(Method::kHapke);
}

}  // namespace
