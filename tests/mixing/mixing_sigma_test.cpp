// Uncertainty weighting of the fitted mixing methods (1/sigma^2) and the held-out chi^2.
// References: the closed-form weighted least-squares solution (A^T W A)^-1 A^T W y computed here with
// Eigen, the known synthetic truth, and the chi^2 distribution (E[chi^2/n] = 1 for Gaussian noise of
// the stated sigma).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <limits>

#include "mixing_test_util.h"
#include "roadbrdf/core/random.h"

namespace {

using namespace mixtest;

const std::vector<double> kTruth = {0.15, 0.35, 0.5};  // binder, fines, coarse

MixInputs linear_inputs() {
  const FitLoader loader = memory_loader({{"binder", glossy_spectral(0.04, 0.06, 40.0)},
                                          {"fines", oren_nayar_spectral(0.30, 0.10, 0.30)},
                                          {"coarse", oren_nayar_spectral(0.55, -0.10, 0.60)},
                                          {"mastic", oren_nayar_spectral(0.12, 0.02, 0.2)}});
  return load_mix_inputs(three_component_formulation("binder", "fines", "coarse", "mastic"), loader);
}

double true_mixture(const MixInputs& in, const Geometry& g, double w) {
  double f = 0.0;
  for (std::size_t k = 0; k < 3; ++k) f += kTruth[k] * value_at(*in.end_members[k].model, g, w);
  return f;
}

// Gaussian noise of standard deviation sigma(n, m) added to the true mixture; sigma stored.
template <class Sigma>
SpectralDataset noisy_dataset(const MixInputs& in, unsigned seed, Sigma&& sigma_of) {
  roadbrdf::NormalStream gauss(seed);
  SpectralDataset d = make_dataset([&](const Geometry& g, double w) { return true_mixture(in, g, w); });
  d.sigma.resize(d.brdf.size());
  for (std::size_t n = 0; n < d.geometry_count(); ++n) {
    for (std::size_t m = 0; m < d.wavelength_count(); ++m) {
      const double s = sigma_of(n, d.value(n, m));
      d.sigma[n * d.wavelength_count() + m] = s;
      d.value(n, m) += s * gauss.next();
    }
  }
  return d;
}

double weight_error(const std::vector<double>& w) {
  double e = 0.0;
  for (std::size_t k = 0; k < 3; ++k) e += (w[k] - kTruth[k]) * (w[k] - kTruth[k]);
  return std::sqrt(e);
}

TEST(SigmaWeighting, WeightedNnlsRecoversWeightsBetterWithHeteroscedasticNoise) {
  const MixInputs in = linear_inputs();
  // Half of the geometries (odd indices) are 10x noisier: 2 % vs 20 % of the value.
  auto sigma_of = [](std::size_t n, double y) { return (n % 2 ? 0.20 : 0.02) * y; };
  double weighted = 0.0, unweighted = 0.0;
  const int seeds = 5;
  for (int seed = 1; seed <= seeds; ++seed) {
    const SpectralDataset d = noisy_dataset(in, 100 + seed, sigma_of);
    MixSettings on, off;
    off.use_sigma = false;
    const MixResult a = mix(in, Method::kFitted, on, &d);
    const MixResult b = mix(in, Method::kFitted, off, &d);
    EXPECT_EQ(a.settings.at("sigma_weighted"), 1.0);
    EXPECT_EQ(b.settings.at("sigma_weighted"), 0.0);
    weighted += weight_error(a.weights) / seeds;
    unweighted += weight_error(b.weights) / seeds;
  }
  // Relative variance of the estimates (same design in both halves): unweighted ~ mean sigma^2 =
  // (0.02^2 + 0.2^2)/2, weighted ~ 1 / mean(1/sigma^2) = 2 / (0.02^-2 + 0.2^-2): ratio 25.5, so the
  // error ratio is ~5; require a clear margin (2x), not the exact ratio.
  EXPECT_LT(weighted, 0.5 * unweighted) << "weighted " << weighted << " unweighted " << unweighted;
  EXPECT_LT(weighted, 0.1);
}

// Closed-form weighted least squares over the wavelengths [m0, m1): (A^T W A)^-1 A^T W y.
Eigen::Vector3d closed_form(const MixInputs& in, const SpectralDataset& d, std::size_t m0, std::size_t m1,
                            bool weighted) {
  const std::size_t rows = d.geometry_count() * (m1 - m0);
  Eigen::MatrixXd A(rows, 3);
  Eigen::VectorXd y(rows), w(rows);
  std::size_t row = 0;
  for (std::size_t n = 0; n < d.geometry_count(); ++n) {
    for (std::size_t m = m0; m < m1; ++m, ++row) {
      for (std::size_t k = 0; k < 3; ++k)
        A(row, k) = value_at(*in.end_members[k].model, d.geometries[n], d.wavelengths[m]);
      const bool missing = std::isnan(d.value(n, m));  // a measurement not made: no row
      y(row) = missing ? 0.0 : d.value(n, m);
      const double s = d.sigma[n * d.wavelength_count() + m];
      w(row) = missing ? 0.0 : weighted ? 1.0 / (s * s) : 1.0;
    }
  }
  const Eigen::MatrixXd AtW = A.transpose() * w.asDiagonal();
  return (AtW * A).ldlt().solve(AtW * y);
}

TEST(SigmaWeighting, WeightedNnlsEqualsClosedFormWhenNoBoundIsActive) {
  const MixInputs in = linear_inputs();
  // Small, strongly heteroscedastic case: sigma varies by 30x over the values.
  roadbrdf::Rng rng(7);
  auto factor = [&rng] { return 0.002 + 0.058 * rng.uniform(); };
  const SpectralDataset d = noisy_dataset(in, 11, [&](std::size_t, double y) { return factor() * y; });
  for (bool weighted : {true, false}) {
    MixSettings s;
    s.use_sigma = weighted;
    const Eigen::Vector3d expected = closed_form(in, d, 0, d.wavelength_count(), weighted);
    ASSERT_GT(expected.minCoeff(), 0.0);  // no bound active: NNLS must equal the closed form
    const MixResult r = mix(in, Method::kFitted, s, &d);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.weights[k], expected[k], 1e-10 * expected[k]) << k;
    // Per wavelength: one closed form per wavelength, found in the parameter table.
    s.per_wavelength = true;
    const MixResult p = mix(in, Method::kFitted, s, &d);
    for (std::size_t m = 0; m < d.wavelength_count(); ++m) {
      const Eigen::Vector3d e = closed_form(in, d, m, m + 1, weighted);
      ASSERT_GT(e.minCoeff(), 0.0);
      const std::vector<double> row = p.model->parameters_at(d.wavelengths[m]);
      for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(row[k], e[k], 1e-9 * e[k]) << "m=" << m << " k=" << k;
    }
  }
}

TEST(MissingValues, FittedWeightsLeaveTheMissingCellOut) {
  const MixInputs in = linear_inputs();
  roadbrdf::Rng rng(7);
  auto factor = [&rng] { return 0.002 + 0.058 * rng.uniform(); };
  SpectralDataset d = noisy_dataset(in, 11, [&](std::size_t, double y) { return factor() * y; });
  const Eigen::Vector3d complete = closed_form(in, d, 0, d.wavelength_count(), true);
  d.value(3, 1) = std::numeric_limits<double>::quiet_NaN();
  d.sigma[3 * d.wavelength_count() + 1] = std::numeric_limits<double>::quiet_NaN();
  for (bool weighted : {true, false}) {
    MixSettings s;
    s.use_sigma = weighted;
    const Eigen::Vector3d expected = closed_form(in, d, 0, d.wavelength_count(), weighted);
    ASSERT_GT(expected.minCoeff(), 0.0);
    const MixResult r = mix(in, Method::kFitted, s, &d);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(r.weights[k], expected[k], 1e-10 * expected[k]) << k;
    if (weighted) {
      EXPECT_GT((expected - complete).cwiseAbs().maxCoeff(), 1e-8);  // the cell mattered
    }
    s.per_wavelength = true;
    const MixResult p = mix(in, Method::kFitted, s, &d);
    const Eigen::Vector3d e = closed_form(in, d, 1, 2, weighted);
    const std::vector<double> row = p.model->parameters_at(d.wavelengths[1]);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(row[k], e[k], 1e-9 * e[k]) << k;
  }
  // The comparison leaves it out of the errors: finite RMSE and chi^2 over the measured values.
  const Comparison c = compare_method(in, Method::kFitted, {}, d, 5);
  EXPECT_TRUE(std::isfinite(c.rmse));
  EXPECT_TRUE(std::isfinite(c.chi2_reduced));
  double chi2 = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < d.brdf.size(); ++i) {
    if (std::isnan(d.brdf[i])) continue;
    chi2 += std::pow((c.predicted[i] - d.brdf[i]) / d.sigma[i], 2);
    ++n;
  }
  EXPECT_EQ(n, d.brdf.size() - 1);
  EXPECT_NEAR(c.chi2_reduced, chi2 / static_cast<double>(n), 1e-12);
}

TEST(SigmaWeighting, NonPositiveSigmaIsAnErrorWhenWeighting) {
  const MixInputs in = linear_inputs();
  SpectralDataset d = noisy_dataset(in, 3, [](std::size_t, double y) { return 0.01 * y; });
  d.sigma[5] = 0.0;
  try {
    mix(in, Method::kFitted, {}, &d);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("geometry 2"), std::string::npos)
        << e.what();  // index 5 = geometry 2, 2nd wavelength
    EXPECT_NE(std::string(e.what()).find("500 nm"), std::string::npos) << e.what();
  }
  MixSettings off;
  off.use_sigma = false;
  EXPECT_NO_THROW(mix(in, Method::kFitted, off, &d));
}

TEST(SigmaWeighting, HeldOutChi2IsAboutOneWithinNoiseAndLargeOtherwise) {
  const MixInputs in = linear_inputs();
  // 1 % noise: 150 geometries x 4 wavelengths = 600 held-out values; chi^2/n has standard deviation
  // sqrt(2/600) = 0.058 for the true model, plus ~K/n from the fitted weights.
  const SpectralDataset d = noisy_dataset(in, 5, [](std::size_t, double y) { return 0.01 * y; });
  const Comparison fitted = compare_method(in, Method::kFitted, {}, d, 5);
  EXPECT_NEAR(fitted.chi2_reduced, 1.0, 0.25);
  // The same chi^2 recomputed from the held-out predictions.
  double chi2 = 0.0, sse = 0.0;
  for (std::size_t i = 0; i < d.brdf.size(); ++i) {
    chi2 += std::pow((fitted.predicted[i] - d.brdf[i]) / d.sigma[i], 2);
    sse += std::pow(fitted.predicted[i] - d.brdf[i], 2);
  }
  EXPECT_NEAR(fitted.chi2_reduced, chi2 / d.brdf.size(), 1e-12);
  EXPECT_NEAR(fitted.rmse, std::sqrt(sse / d.brdf.size()), 1e-15);
  for (int f : fitted.fold_of_geometry) {
    EXPECT_GE(f, 1);
    EXPECT_LE(f, 5);
  }
  // Areal weights from the formulation are not the truth: far outside the noise.
  const Comparison areal = compare_method(in, Method::kAreal, {}, d, 5);
  EXPECT_GT(areal.chi2_reduced, 10.0);
  // No sigma: no chi^2.
  SpectralDataset plain = d;
  plain.sigma.clear();
  EXPECT_TRUE(std::isnan(compare_method(in, Method::kFitted, {}, plain, 5).chi2_reduced));
}

}  // namespace
