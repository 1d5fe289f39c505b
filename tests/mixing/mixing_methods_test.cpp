// Mixing methods: recovery of known weights, identities, Hapke intimate mixing, albedo linearity.
// References: closed forms written here (IMSA with H1, Hapke 1981; area weights M/(rho D)), an
// independent midpoint quadrature of the white-sky albedo, and the known synthetic truth.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "mixing_test_util.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/hapke_imsa.h"
#include "roadbrdf/models/model.h"

namespace {

using namespace mixtest;

// ---- synthetic linear mixture: fitted weights recover the truth -------------------------------

struct LinearCase {
  MixInputs inputs;
  std::vector<double> truth = {0.15, 0.35, 0.5};  // binder, fines, coarse
};

LinearCase linear_case() {
  LinearCase c;
  const FitLoader loader = memory_loader({{"binder", glossy_spectral(0.04, 0.06, 40.0)},
                                          {"fines", oren_nayar_spectral(0.30, 0.10, 0.30)},
                                          {"coarse", oren_nayar_spectral(0.55, -0.10, 0.60)},
                                          {"mastic", oren_nayar_spectral(0.12, 0.02, 0.2)}});
  c.inputs = load_mix_inputs(three_component_formulation("binder", "fines", "coarse", "mastic"), loader);
  return c;
}

TEST(FittedMixing, RecoversKnownWeightsWithinNoise) {
  LinearCase c = linear_case();
  const auto& em = c.inputs.end_members;
  ASSERT_EQ(em.size(), 4u);  // binder, fines, coarse, mastic
  roadbrdf::NormalStream gauss(42);
  const double noise = 0.01;  // 1 % relative Gaussian noise
  const SpectralDataset data = make_dataset([&](const Geometry& g, double w) {
    double f = 0.0;
    for (std::size_t k = 0; k < 3; ++k) f += c.truth[k] * value_at(*em[k].model, g, w);
    return f * (1.0 + noise * gauss.next());
  });
  // Expected standard errors of the (ordinary) least-squares weights under the heteroscedastic noise
  // sigma_n = 1 % of the value: sandwich covariance (A^T A)^-1 A^T diag(sigma^2) A (A^T A)^-1, for the
  // global fit (all wavelengths) and for one wavelength.
  auto standard_errors = [&](std::size_t m0, std::size_t m1) {
    Eigen::MatrixXd A((m1 - m0) * data.geometry_count(), 3);
    Eigen::VectorXd variance(A.rows());
    std::size_t row = 0;
    for (std::size_t n = 0; n < data.geometry_count(); ++n) {
      for (std::size_t m = m0; m < m1; ++m, ++row) {
        double y = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
          A(row, k) = value_at(*em[k].model, data.geometries[n], data.wavelengths[m]);
          y += c.truth[k] * A(row, k);
        }
        variance(row) = std::pow(noise * y, 2);
      }
    }
    const Eigen::MatrixXd inverse = (A.transpose() * A).inverse();
    const Eigen::MatrixXd cov = inverse * (A.transpose() * variance.asDiagonal() * A) * inverse;
    return Eigen::Vector3d(std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1)), std::sqrt(cov(2, 2)));
  };
  Eigen::Vector3d per_wavelength_error(0, 0, 0);
  for (std::size_t m = 0; m < 4; ++m) per_wavelength_error = per_wavelength_error.cwiseMax(standard_errors(m, m + 1));
  const Eigen::Vector3d global_error = standard_errors(0, 4);
  for (bool per_wavelength : {false, true}) {
    MixSettings s;
    s.per_wavelength = per_wavelength;
    const MixResult r = mix(c.inputs, Method::kFitted, s, &data);
    ASSERT_EQ(r.weights.size(), 3u);
    const Eigen::Vector3d& err = per_wavelength ? per_wavelength_error : global_error;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_LT(err[k], 0.05);  // the design resolves the weights at this noise level
      EXPECT_NEAR(r.weights[k], c.truth[k], 4.0 * err[k]) << "k=" << k << " per_wavelength=" << per_wavelength;
    }
    EXPECT_TRUE(std::isfinite(r.weight_distance));
  }
  MixSettings s;
  s.sum_to_one = true;
  const MixResult r = mix(c.inputs, Method::kFitted, s, &data);
  EXPECT_NEAR(r.weight_sum, 1.0, 1e-6);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.weights[k], c.truth[k], 4.0 * global_error[k]);
}

TEST(FittedMixing, ExactDataGivesExactWeights) {
  LinearCase c = linear_case();
  const auto& em = c.inputs.end_members;
  const SpectralDataset data = make_dataset([&](const Geometry& g, double w) {
    double f = 0.0;
    for (std::size_t k = 0; k < 3; ++k) f += c.truth[k] * value_at(*em[k].model, g, w);
    return f;
  });
  const MixResult r = mix(c.inputs, Method::kFitted, {}, &data);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.weights[k], c.truth[k], 1e-8);
  // Cross-validation of exact data: held-out error ~ 0.
  const Comparison cmp = compare_method(c.inputs, Method::kFitted, {}, data, 5);
  EXPECT_LT(cmp.relative_rmse, 1e-8);
  // Progress: one unit per mix, the in-sample one and one per fold (comparison_mixes).
  std::vector<std::size_t> done;
  const ProgressCallback callback = [&](std::size_t d, std::size_t total) {
    EXPECT_EQ(total, 6u);
    done.push_back(d);
  };
  ProgressCounter progress(callback, comparison_mixes(Method::kFitted, 5));
  compare_method(c.inputs, Method::kFitted, {}, data, 5, 1, nullptr, &progress);
  EXPECT_EQ(done, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(comparison_mixes(Method::kAreal, 5), 1u);  // nothing fitted: one mix predicts every fold
}

TEST(Nnls, MatchesKnownActiveSetSolution) {
  // min |A x - b|, A = I (2x2), b = (1, -1): x = (1, 0).
  const std::vector<double> x = nnls_normal({1, 0, 0, 1}, {1, -1}, 2);
  EXPECT_NEAR(x[0], 1.0, 1e-14);
  EXPECT_EQ(x[1], 0.0);
  // A = [[1, 1], [0, 1]], b = (2, -1): unconstrained (3, -1) -> constrained: x2 = 0, x1 = 2... with
  // x2 = 0, min (x1 - 2)^2 + 1 -> x1 = 2.
  const std::vector<double> y = nnls_normal({1, 1, 1, 2}, {2, 1}, 2);
  EXPECT_NEAR(y[0], 2.0, 1e-12);
  EXPECT_EQ(y[1], 0.0);
}

// ---- areal weights from the formulation ---------------------------------------------------------

TEST(ArealMixing, WeightsFollowProjectedAreaAndBinderVolume) {
  LinearCase c = linear_case();
  const MixResult r = mix(c.inputs, Method::kAreal, {});
  // Independent computation: binder coverage = binder volume fraction; granular area per mass
  // ~ M / (rho D) with D the logarithmic mean of the class (0 -> 0.063 mm).
  const double v_binder = 6.0 / 1.03, v_total = 6.0 / 1.03 + 34.0 / 2.65 + 60.0 / 2.70;
  const double coverage = v_binder / v_total;
  const double d_fines = (2.0 - 0.063) / std::log(2.0 / 0.063);
  const double d_coarse = 4.0 / std::log(10.0 / 6.0);
  const double p_fines = 34.0 / (2.65 * d_fines), p_coarse = 60.0 / (2.70 * d_coarse);
  EXPECT_NEAR(r.settings.at("binder_coverage"), coverage, 1e-12);
  EXPECT_NEAR(r.weights[0], coverage, 1e-12);
  EXPECT_NEAR(r.weights[1], (1 - coverage) * p_fines / (p_fines + p_coarse), 1e-12);
  EXPECT_NEAR(r.weights[2], (1 - coverage) * p_coarse / (p_fines + p_coarse), 1e-12);
  // Explicit coverage.
  MixSettings s;
  s.binder_coverage = 0.4;
  const MixResult q = mix(c.inputs, Method::kAreal, s);
  EXPECT_NEAR(q.weights[0], 0.4, 1e-14);
  EXPECT_NEAR(q.weights[1] + q.weights[2], 0.6, 1e-14);
}

TEST(ArealMixing, AlbedoIsTheSameMixtureOfComponentAlbedos) {
  LinearCase c = linear_case();
  const MixResult r = mix(c.inputs, Method::kAreal, {});
  for (double w : {400.0, 550.0, 700.0}) {
    const double mixed = midpoint_white_sky_albedo([&](const Geometry& g) { return value_at(*r.model, g, w); });
    double expected = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      expected += r.weights[k] * midpoint_white_sky_albedo(
                                     [&](const Geometry& g) { return value_at(*c.inputs.end_members[k].model, g, w); });
    }
    EXPECT_NEAR(mixed, expected, 1e-12 * std::max(1.0, expected)) << w;
    // The library's quadrature agrees with the independent midpoint rule.
    EXPECT_NEAR(spectral_white_sky_albedo(*r.model, {w})[0], mixed, 2e-3) << w;
  }
}

// ---- identities -------------------------------------------------------------------------------

TEST(Identities, OneComponentFormulationReturnsThatComponent) {
  const SpectralModel m = oren_nayar_spectral(0.3, 0.1, 0.3);
  Formulation f;
  f.name = "one";
  f.components.push_back(component("sand", ComponentKind::kAggregate, 100.0, 2.65, 0.0, 2.0, "sand"));
  MasticSpec spec;
  spec.fit = spec.fit_path = "sand";
  f.mastic = spec;  // the fines are the "mastic": the mastic method has no coarse class
  const MixInputs in = load_mix_inputs(f, memory_loader({{"sand", m}}));
  const SpectralDataset data = make_dataset([&](const Geometry& g, double w) { return value_at(m, g, w); });
  for (Method method : {Method::kAreal, Method::kFitted, Method::kMastic, Method::kHapke}) {
    const MixResult r = mix(in, method, {}, &data);
    for (const Geometry& g : test_geometries()) {
      for (double w : {400.0, 470.0, 700.0}) {
        EXPECT_NEAR(value_at(*r.model, g, w), value_at(m, g, w), 1e-9) << name_of(method);
      }
    }
  }
  // The shadowed method needs a coarse and a matrix end-member: a clear error.
  EXPECT_THROW(mix(in, Method::kShadowed, {}, &data), InputError);
}

TEST(Identities, MixingIdenticalComponentsChangesNothing) {
  const SpectralModel m = oren_nayar_spectral(0.25, 0.2, 0.25);
  const MixInputs in = load_mix_inputs(three_component_formulation("b", "f", "c", "m"),
                                       memory_loader({{"b", m}, {"f", m}, {"c", m}, {"m", m}}));
  const SpectralDataset data = make_dataset([&](const Geometry& g, double w) { return value_at(m, g, w); });
  for (Method method : values_of<Method>()) {
    MixSettings s;
    s.sum_to_one = method == Method::kFitted;  // identical end-members: only the sum is identifiable
    const MixResult r = mix(in, method, s, &data);
    for (const Geometry& g : test_geometries()) {
      for (double w : {400.0, 650.0}) {
        EXPECT_NEAR(value_at(*r.model, g, w), value_at(m, g, w), 1e-6 * value_at(m, g, w) + 1e-9) << name_of(method);
      }
    }
  }
}

// ---- Hapke intimate mixing ----------------------------------------------------------------------

// IMSA with H1 and isotropic scattering, written independently of the library (Hapke 1981):
// BRDF = w/(4 pi) H(mu0) H(mu) / (mu0 + mu), H(x) = (1 + 2x)/(1 + 2x sqrt(1 - w)).
struct TestImsa {
  static constexpr const char* kName = "test-imsa";
  static constexpr int kMaxParameters = 1;
  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary = "IMSA H1 isotropic (test)";
    d.parameters = {{"w", "1", "single-scattering albedo", 0.5, 0.0, 1.0, true, false}};
    return d;
  }
  explicit TestImsa(const OptionSet&) {}
  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    using std::sqrt;
    const double mu0 = g.cos_theta_i(), mu = g.cos_theta_r();
    const T gamma = sqrt(1.0 - p[0]);
    const T h0 = (1.0 + 2.0 * mu0) / (1.0 + 2.0 * mu0 * gamma);
    const T h1 = (1.0 + 2.0 * mu) / (1.0 + 2.0 * mu * gamma);
    return p[0] / (4.0 * kPi) * h0 * h1 / (mu0 + mu);
  }
};

double imsa(double w, const Geometry& g) {
  const double p = w;
  return TestImsa({})(&p, g);
}

SpectralModel imsa_spectral(double w0, double w1) {
  std::shared_ptr<const Model> model = std::make_shared<ModelAdapter<TestImsa>>(OptionSet{});
  std::vector<double> table;
  for (double w : test_wavelengths()) table.push_back(w0 + w1 * (w - 400.0) / 300.0);
  return SpectralModel(model, test_wavelengths(), table);
}

TEST(HapkeMixing, InversionRecoversTheSingleScatteringAlbedo) {
  for (double w : {0.0, 0.05, 0.3, 0.7, 0.95, 0.999}) {
    EXPECT_NEAR(invert_imsa_white_sky_albedo(imsa_white_sky_albedo(w)), w, 1e-9) << w;
  }
  EXPECT_THROW(invert_imsa_white_sky_albedo(1.5), InputError);
  EXPECT_THROW(invert_imsa_white_sky_albedo(-0.1), InputError);
  // The quadrature of the IMSA BRDF agrees with the independent midpoint rule.
  for (double w : {0.2, 0.6, 0.95}) {
    EXPECT_NEAR(imsa_white_sky_albedo(w),
                midpoint_white_sky_albedo([&](const Geometry& g) { return imsa(w, g); }, 96, 8), 2e-3);
  }
}

TEST(HapkeMixing, MixtureOfImsaComponentsIsImsaOfTheMixedAlbedo) {
  const double w_binder = 0.08, w_fines = 0.75, w_coarse = 0.5;
  const MixInputs in = load_mix_inputs(three_component_formulation("b", "f", "c", "m"),
                                       memory_loader({{"b", imsa_spectral(w_binder, 0.0)},
                                                      {"f", imsa_spectral(w_fines, 0.0)},
                                                      {"c", imsa_spectral(w_coarse, 0.0)},
                                                      {"m", imsa_spectral(0.3, 0.0)}}));
  const MixResult r = mix(in, Method::kHapke, {});
  // Cross-section weights M/(rho D): binder film 0.01 mm, fines log-mean of (0.063, 2), coarse of (6, 10).
  const double c_b = 6.0 / (1.03 * 0.01);
  const double c_f = 34.0 / (2.65 * (2.0 - 0.063) / std::log(2.0 / 0.063));
  const double c_c = 60.0 / (2.70 * 4.0 / std::log(10.0 / 6.0));
  const double total = c_b + c_f + c_c;
  EXPECT_NEAR(r.weights[0], c_b / total, 1e-12);
  EXPECT_NEAR(r.weights[1], c_f / total, 1e-12);
  EXPECT_NEAR(r.weights[2], c_c / total, 1e-12);
  const double w_mix = (c_b * w_binder + c_f * w_fines + c_c * w_coarse) / total;
  const std::size_t K = 3;
  const std::vector<double> p = r.model->parameters_at(500.0);
  EXPECT_NEAR(p[K + 0], w_binder, 1e-8);
  EXPECT_NEAR(p[K + 1], w_fines, 1e-8);
  EXPECT_NEAR(p[K + 2], w_coarse, 1e-8);
  for (const Geometry& g : test_geometries()) {
    EXPECT_NEAR(value_at(*r.model, g, 500.0), imsa(w_mix, g), 1e-8 * imsa(w_mix, g));
  }
  // Nonlinear: darker than the linear mixture of the components with the same weights.
  const Geometry g = geometry_from_degrees(30, 0, 30, 90);
  const double linear = (c_b * imsa(w_binder, g) + c_f * imsa(w_fines, g) + c_c * imsa(w_coarse, g)) / total;
  EXPECT_LT(value_at(*r.model, g, 500.0), linear);
}

TEST(HapkeMixing, EqualSingleScatteringAlbedosReturnThatAlbedo) {
  // Different angular shapes (Oren-Nayar roughness), equal white-sky albedo hence equal w.
  const SpectralModel rough = oren_nayar_spectral(0.4, 0.0, 0.3);
  const double albedo = spectral_white_sky_albedo(rough, {500.0})[0];
  const SpectralModel lambert = lambert_spectral(albedo, 0.0);
  const MixInputs in = load_mix_inputs(three_component_formulation("b", "f", "c", "m"),
                                       memory_loader({{"b", rough}, {"f", lambert}, {"c", rough}, {"m", lambert}}));
  const MixResult r = mix(in, Method::kHapke, {});
  const std::vector<double> p = r.model->parameters_at(500.0);
  const double w = invert_imsa_white_sky_albedo(albedo);
  double w_mix = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(p[3 + k], w, 1e-9);
    w_mix += p[k] * p[3 + k];
  }
  EXPECT_NEAR(w_mix, w, 1e-9);
  // ...and the mixture is then the linear mixture with the cross-section weights.
  for (const Geometry& g : test_geometries()) {
    const double expected = (p[0] + p[2]) * value_at(rough, g, 500.0) + p[1] * value_at(lambert, g, 500.0);
    EXPECT_NEAR(value_at(*r.model, g, 500.0), expected, 1e-9);
  }
}

// ---- mastic and shadowed -------------------------------------------------------------------------

TEST(MasticMixing, MasticPlusCoarseWithVolumeFraction) {
  LinearCase c = linear_case();
  const MixResult r = mix(c.inputs, Method::kMastic, {});
  ASSERT_EQ(r.end_members.size(), 2u);
  EXPECT_EQ(r.end_members[0], "mastic");
  EXPECT_EQ(r.end_members[1], "coarse");
  const double v_mastic = 6.0 / 1.03 + 34.0 / 2.65, v_total = v_mastic + 60.0 / 2.70;
  EXPECT_NEAR(r.weights[0], v_mastic / v_total, 1e-12);
  EXPECT_NEAR(r.weights[1], 1.0 - v_mastic / v_total, 1e-12);
  Formulation no_mastic = c.inputs.formulation;
  no_mastic.mastic.reset();
  const MixInputs in2 = load_mix_inputs(no_mastic, memory_loader({{"binder", lambert_spectral(0.04, 0.0)},
                                                                  {"fines", lambert_spectral(0.3, 0.0)},
                                                                  {"coarse", lambert_spectral(0.5, 0.0)}}));
  EXPECT_THROW(mix(in2, Method::kMastic, {}), InputError);
}

// Data made with the shadowed form itself (independent evaluation: tan, exp written here).
SpectralDataset shadowed_data(const std::vector<const SpectralModel*>& matrix, const SpectralModel& coarse,
                              const std::vector<double>& a_matrix, double a_coarse, double s) {
  return make_dataset([&](const Geometry& g, double w) {
    const double S = std::exp(-s * (std::tan(g.theta_i) + std::tan(g.theta_r)));
    double sum_matrix = 0.0, f = 0.0;
    for (std::size_t k = 0; k < matrix.size(); ++k) {
      sum_matrix += a_matrix[k];
      f += S * a_matrix[k] * value_at(*matrix[k], g, w);
    }
    return f + a_coarse * (1.0 + (1.0 - S) * sum_matrix / a_coarse) * value_at(coarse, g, w);
  });
}

TEST(ShadowedMixing, RecoversShadowingAndWeightsWithComponentMatrix) {
  LinearCase c = linear_case();
  Formulation f = c.inputs.formulation;
  f.mastic.reset();  // without a mastic, the matrix is the binder and the fines
  const MixInputs in = load_mix_inputs(f, memory_loader({{"binder", *c.inputs.end_members[0].model},
                                                         {"fines", *c.inputs.end_members[1].model},
                                                         {"coarse", *c.inputs.end_members[2].model}}));
  const auto& em = in.end_members;
  const SpectralDataset data =
      shadowed_data({em[0].model.get(), em[1].model.get()}, *em[2].model, {0.15, 0.35}, 0.5, 0.3);
  const MixResult r = mix(in, Method::kShadowed, {}, &data);
  ASSERT_EQ(r.end_members, (std::vector<std::string>{"binder", "fines", "coarse"}));
  EXPECT_NEAR(r.settings.at("shadowing"), 0.3, 1e-5);
  const double a[] = {0.15, 0.35, 0.5};
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.weights[k], a[k], 1e-5);
}

TEST(ShadowedMixing, RecoversShadowingAndWeightsWithMasticMatrix) {
  LinearCase c = linear_case();
  const auto& em = c.inputs.end_members;  // binder, fines, coarse, mastic
  const SpectralDataset data = shadowed_data({em[3].model.get()}, *em[2].model, {0.45}, 0.55, 0.8);
  const MixResult r = mix(c.inputs, Method::kShadowed, {}, &data);
  ASSERT_EQ(r.end_members, (std::vector<std::string>{"mastic", "coarse"}));
  EXPECT_NEAR(r.settings.at("shadowing"), 0.8, 1e-5);
  EXPECT_NEAR(r.weights[0], 0.45, 1e-5);
  EXPECT_NEAR(r.weights[1], 0.55, 1e-5);
  // Compared with the mastic method's formulation weights.
  EXPECT_EQ(r.formulation_weights.size(), 2u);
}

}  // namespace
