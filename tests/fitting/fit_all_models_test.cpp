// Every registered model: synthetic data from known parameters (inside the bounds, away from the
// defaults) plus 1 % Gaussian noise, fitted from the model's default parameters with a multi-start.
// The fit must reach the noise level (reduced chi2 near 1, i.e. the global minimum basin), and every
// parameter with a defined standard error must lie within 5 standard errors of the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/registry.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

class EveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryModel, RecoversParametersFromNoisySyntheticData) {
  auto model = make_model(GetParam());
  const ModelDescription& d = model->description();
  // Truth: the default moved 25 % of the way towards the upper bound (capped for wide bounds).
  std::vector<double> truth = d.default_parameters();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double hi = std::min(d.parameters[k].upper, truth[k] + std::max(1.0, std::fabs(truth[k])));
    truth[k] += 0.25 * (hi - truth[k]);
  }
  const auto grid = test::test_grid(6, 7, 7);
  const double rel = 0.01;
  const SpectralDataset data = test::synthetic_dataset(
      *model, grid, {550.0}, [&](std::size_t) { return truth; }, rel, 1e-5, 77, true);
  FitOptions o;
  o.multistart = 8;
  const FitResult r = fit_model(*model, data, o);
  const WavelengthFit& f = r.wavelengths[0];
  const double reduced_chi2 = f.chi2 / double(f.points - f.free_parameters);
  std::printf("%-22s reduced chi2 %.3f  converged %d  cov %d  at bounds %zu\n", GetParam().c_str(), reduced_chi2,
              int(f.converged), int(f.covariance_ok), f.at_bounds.size());
  for (std::size_t k = 0; k < truth.size(); ++k) {
    std::printf("    %-14s true %-10.5g fit %-10.5g se %.3g\n", d.parameters[k].name.c_str(), truth[k], f.parameters[k],
                f.standard_errors[k]);
  }
  // sigma is known (stored in the dataset): chi2/(n-k) ~ 1 +- sqrt(2/(n-k)) (n ~ 290).
  EXPECT_LT(reduced_chi2, 1.5) << GetParam() << " did not reach the noise level";
  if (f.covariance_ok) {
    for (std::size_t k = 0; k < truth.size(); ++k) {
      if (std::isfinite(f.standard_errors[k]) && f.standard_errors[k] > 0.0) {
        EXPECT_LT(std::fabs(f.parameters[k] - truth[k]), 5.0 * f.standard_errors[k])
            << GetParam() << " " << d.parameters[k].name;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryModel, ::testing::ValuesIn(model_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string s = info.param;
                           for (char& c : s) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return s;
                         });

}  // namespace
}  // namespace roadbrdf
