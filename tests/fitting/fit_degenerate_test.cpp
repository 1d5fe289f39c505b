// Degenerate input to the fitter: each case a clear InputError or a documented outcome, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/registry.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

using test::test_grid;

SpectralDataset constant_data(std::size_t n_geometries, double value) {
  SpectralDataset d;
  d.geometries = test_grid(5, 6, 5);
  d.geometries.resize(n_geometries);
  d.wavelengths = {500.0, 510.0};
  d.brdf.assign(n_geometries * 2, value);
  return d;
}

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FitDegenerate, AllZeroDataConvergesToZeroAlbedoOnItsBound) {
  // Documented outcome: albedo = 0 (reported on its lower bound), sigma undetermined (the Jacobian
  // column of sigma vanishes with albedo): the covariance is reported rank-deficient.
  auto model = make_model("oren-nayar");
  const SpectralDataset d = constant_data(40, 0.0);
  const FitResult r = fit_model(*model, d, FitOptions{});
  for (const auto& f : r.wavelengths) {
    EXPECT_NEAR(f.parameters[0], 0.0, 1e-12);
    EXPECT_NE(std::find(f.at_bounds.begin(), f.at_bounds.end(), "albedo=lower"), f.at_bounds.end());
    EXPECT_FALSE(f.covariance_ok);
    EXPECT_FALSE(f.covariance_message.empty());
    EXPECT_TRUE(std::isnan(f.r_squared));  // constant data: R^2 undefined
    EXPECT_TRUE(std::isnan(f.standard_errors[1]));
  }
  EXPECT_EQ(r.at_bound_count, 2u);
  // The relative loss cannot divide by zero data: clear error.
  FitOptions o;
  o.loss = FitLoss::kRelative;
  EXPECT_NE(error_of([&] { fit_model(*model, d, o); }).find("relative loss"), std::string::npos);
}

TEST(FitDegenerate, SingleGeometry) {
  auto two = make_model("oren-nayar");
  const SpectralDataset d = constant_data(1, 0.1);
  EXPECT_NE(error_of([&] { fit_model(*two, d, FitOptions{}); }).find("1 geometries for 2 free parameters"),
            std::string::npos);
  // One parameter, one point: exact fit, no degrees of freedom for the standard error.
  auto one = make_model("lambert");
  const FitResult r = fit_model(*one, d, FitOptions{});
  EXPECT_NEAR(r.wavelengths[0].parameters[0], 0.1 * M_PI, 1e-9);
  EXPECT_FALSE(r.wavelengths[0].covariance_ok);
  EXPECT_NE(r.wavelengths[0].covariance_message.find("degrees of freedom"), std::string::npos);
  // Fixing sigma makes the 2-parameter model fittable.
  FitOptions o;
  o.fixed = {{"sigma", 0.2}};
  EXPECT_NO_THROW(fit_model(*two, d, o));
}

TEST(FitDegenerate, FewerGeometriesThanParameters) {
  auto model = make_model("lambert+oren-nayar");  // 5 parameters
  const SpectralDataset d = constant_data(3, 0.1);
  EXPECT_NE(error_of([&] { fit_model(*model, d, FitOptions{}); }).find("3 geometries for 5 free parameters"),
            std::string::npos);
}

TEST(FitDegenerate, NaNIsMaskedInfinityIsAnError) {
  auto model = make_model("lambert");
  SpectralDataset d = constant_data(10, 0.1);
  // NaN: a measurement not made, masked out at its wavelength (fit_missing_values_test.cpp).
  d.value(3, 1) = std::numeric_limits<double>::quiet_NaN();
  const FitResult f = fit_model(*model, d, FitOptions{});
  EXPECT_EQ(f.missing_values, 1u);
  EXPECT_EQ(f.wavelengths[1].points, 9u);
  EXPECT_EQ(f.wavelengths[0].points, 10u);
  d.value(3, 1) = std::numeric_limits<double>::infinity();
  const std::string e = error_of([&] { fit_model(*model, d, FitOptions{}); });
  EXPECT_NE(e.find("geometry 4, wavelength 510 nm"), std::string::npos) << e;
}

TEST(FitDegenerate, StartOrFixedValueOutsideBounds) {
  auto model = make_model("oren-nayar");
  const SpectralDataset d = constant_data(10, 0.1);
  FitOptions o;
  o.start = {{"sigma", 2.0}};
  EXPECT_NE(error_of([&] { fit_model(*model, d, o); }).find("starting value of 'sigma' = 2 is outside its bounds"),
            std::string::npos);
  FitOptions f;
  f.fixed = {{"albedo", -1.0}};
  EXPECT_NE(error_of([&] { fit_model(*model, d, f); }).find("fixed value of 'albedo'"), std::string::npos);
  FitOptions u;
  u.start = {{"roughness", 0.1}};
  EXPECT_NE(error_of([&] { fit_model(*model, d, u); }).find("no parameter 'roughness'"), std::string::npos);
  FitOptions both;
  both.fixed = {{"sigma", 0.1}};
  both.shared = {"sigma"};
  EXPECT_NE(error_of([&] { fit_model(*model, d, both); }).find("both fixed and shared"), std::string::npos);
}

TEST(FitDegenerate, BadUncertaintiesAndLogLoss) {
  auto model = make_model("lambert");
  SpectralDataset d = constant_data(10, 0.1);
  d.sigma.assign(d.brdf.size(), 0.01);
  d.sigma[5] = 0.0;
  EXPECT_NE(error_of([&] { fit_model(*model, d, FitOptions{}); }).find("uncertainty"), std::string::npos);
  FitOptions no_sigma;
  no_sigma.use_sigma = false;
  EXPECT_NO_THROW(fit_model(*model, d, no_sigma));
  d.sigma.clear();
  d.value(0, 0) = -5.0;  // 1 + y cos(theta_i) < 0
  FitOptions log;
  log.loss = FitLoss::kLog;
  EXPECT_NE(error_of([&] { fit_model(*model, d, log); }).find("log loss"), std::string::npos);
}

TEST(FitDegenerate, EmptyDataset) {
  auto model = make_model("lambert");
  SpectralDataset d;
  EXPECT_NE(error_of([&] { fit_model(*model, d, FitOptions{}); }).find("no geometries"), std::string::npos);
}

TEST(FitDegenerate, OptionParsing) {
  RobustLoss k;
  double s = 0;
  robust_loss_from_string("huber:0.5", k, s);
  EXPECT_EQ(k, RobustLoss::kHuber);
  EXPECT_EQ(s, 0.5);
  EXPECT_THROW(robust_loss_from_string("huber", k, s), InputError);
  EXPECT_THROW(robust_loss_from_string("cauchy:-1", k, s), InputError);
  // The scale is read as every number is (core/number.h): whole text, no hex, no leading space.
  EXPECT_THROW(robust_loss_from_string("huber:0x1", k, s), InputError);
  EXPECT_THROW(robust_loss_from_string("huber: 0.5", k, s), InputError);
  EXPECT_THROW(robust_loss_from_string("huber:nan", k, s), InputError);
  robust_loss_from_string("cauchy:+0.25", k, s);
  EXPECT_EQ(s, 0.25);
  EXPECT_THROW(robust_loss_from_string("tukey:1", k, s), InputError);
  EXPECT_THROW(fit_loss_from_string("l1"), InputError);
  const std::vector<double> wl = {400, 410, 420, 430};
  EXPECT_EQ(select_wavelengths(wl, {400, 410, 420}), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(select_wavelengths(wl, {430, 400}), (std::vector<std::size_t>{0, 3}));
  EXPECT_THROW(select_wavelengths(wl, {400, 405}), InputError);  // 405 nm is not in the dataset
  EXPECT_THROW(select_wavelengths(wl, {400, 400}), InputError);
}

}  // namespace
}  // namespace roadbrdf
