// Comparison of a mixing method with a measured mixture: k-fold cross-validation over geometries,
// held-out reduced chi^2, albedo summary (mixing.h compare_method).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing {

std::size_t comparison_mixes(Method method, int folds) {
  return method_needs_data(method) ? 1 + static_cast<std::size_t>(std::max(folds, 0)) : 1;
}

Comparison compare_method(const MixInputs& inputs, Method method, const MixSettings& settings,
                          const SpectralDataset& data, int folds, unsigned seed, const SpectralModel* reference,
                          ProgressCounter* progress) {
  const std::size_t N = data.geometry_count();
  const std::size_t M = data.wavelength_count();
  if (folds < 2) throw FieldError("folds", "must be at least 2");
  if (N < static_cast<std::size_t>(folds)) {
    throw FieldError(
        "folds", std::to_string(folds) + " is more than the measured mixture's " + std::to_string(N) + " geometries");
  }
  Comparison c;
  c.method = method;
  c.folds = folds;
  c.result = mix(inputs, method, settings, &data);
  if (progress) progress->add();
  // Errors of predictions (N_rows x M, rows = geometry indices) against the data.
  // Missing values (NaN) are measurements not made: left out of every error and count.
  const double measured = static_cast<double>(N * M - missing_value_count(data));
  if (!(measured > 0.0)) throw InputError("the measured mixture has no measured value (every value is missing)");
  auto errors = [&](const std::vector<double>& predicted, const std::vector<std::size_t>& rows, double& sse,
                    double& sum_abs) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (std::size_t m = 0; m < M; ++m) {
        const double y = data.value(rows[r], m);
        if (std::isnan(y)) continue;
        const double d = predicted[r * M + m] - y;
        sse += d * d;
        sum_abs += std::fabs(y);
      }
    }
  };
  std::vector<std::size_t> all(N);
  std::iota(all.begin(), all.end(), 0);
  const std::vector<double> in_sample = evaluate_spectral(*c.result.model, data.geometries, data.wavelengths);
  {
    double sse = 0.0, sum_abs = 0.0;
    errors(in_sample, all, sse, sum_abs);
    c.rmse_in_sample = std::sqrt(sse / measured);
    c.relative_rmse_in_sample = c.rmse_in_sample / (sum_abs / measured);
  }
  c.fold_of_geometry.assign(N, 0);
  if (!method_needs_data(method)) {
    c.predicted = in_sample;
  } else {
    c.predicted.assign(N * M, std::numeric_limits<double>::quiet_NaN());
    std::vector<std::size_t> order = all;
    Rng rng(seed);
    shuffle(order, rng);
    for (int fold = 0; fold < folds; ++fold) {
      std::vector<std::size_t> train, test;
      for (std::size_t i = 0; i < N; ++i) (static_cast<int>(i % folds) == fold ? test : train).push_back(order[i]);
      const MixResult part = mix(inputs, method, settings, &data, &train);
      if (progress) progress->add();
      std::vector<Geometry> geometries;
      geometries.reserve(test.size());
      for (std::size_t n : test) geometries.push_back(data.geometries[n]);
      const std::vector<double> predicted = evaluate_spectral(*part.model, geometries, data.wavelengths);
      for (std::size_t t = 0; t < test.size(); ++t) {
        std::copy(predicted.begin() + t * M, predicted.begin() + (t + 1) * M, c.predicted.begin() + test[t] * M);
        c.fold_of_geometry[test[t]] = fold + 1;
      }
    }
  }
  {
    double sse = 0.0, sum_abs = 0.0;
    errors(c.predicted, all, sse, sum_abs);
    c.rmse = std::sqrt(sse / measured);
    c.relative_rmse = c.rmse / (sum_abs / measured);
  }
  if (data.has_sigma()) {
    if (data.sigma.size() != N * M) throw InputError("the measured mixture's sigma table has the wrong size");
    double chi2 = 0.0;
    bool valid = true;
    for (std::size_t i = 0; i < N * M && valid; ++i) {
      if (std::isnan(data.brdf[i])) continue;
      const double sigma = data.sigma[i];
      if (!(sigma > 0.0) || !std::isfinite(sigma)) {
        // Keep the comparison, say why chi^2 is missing.
        std::ostringstream msg;
        msg << "held-out chi^2 not computed: the measured mixture's uncertainty at geometry " << i / M + 1
            << ", wavelength " << data.wavelengths[i % M] << " nm is " << sigma << " (must be > 0)";
        c.result.notes.push_back(msg.str());
        valid = false;
        break;
      }
      const double z = (c.predicted[i] - data.brdf[i]) / sigma;
      chi2 += z * z;
    }
    if (valid) c.chi2_reduced = chi2 / measured;
  }
  // Albedo summary on at most kAlbedoWavelengths wavelengths evenly spaced in index (the quadrature
  // costs ~14k model evaluations per wavelength).
  std::vector<double> albedo_wavelengths;
  const std::size_t n_albedo = std::min<std::size_t>(M, kAlbedoWavelengths);
  for (std::size_t i = 0; i < n_albedo; ++i) {
    const std::size_t index = n_albedo == 1 ? 0 : (i * (M - 1) + (n_albedo - 1) / 2) / (n_albedo - 1);
    if (albedo_wavelengths.empty() || albedo_wavelengths.back() != data.wavelengths[index]) {
      albedo_wavelengths.push_back(data.wavelengths[index]);
    }
  }
  const std::vector<double> albedo = mixture_white_sky_albedo(inputs, c.result, albedo_wavelengths);
  c.albedo = std::accumulate(albedo.begin(), albedo.end(), 0.0) / albedo.size();
  if (reference) {
    const std::vector<double> ref = spectral_white_sky_albedo(*reference, albedo_wavelengths);
    c.albedo_reference = std::accumulate(ref.begin(), ref.end(), 0.0) / ref.size();
    c.albedo_difference = c.albedo - c.albedo_reference;
  }
  return c;
}

}  // namespace roadbrdf::mixing
