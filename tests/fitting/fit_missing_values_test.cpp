// Missing values (NaN cells: measurements not made) are masked out of the fit at their wavelength:
// the fit of a dataset with one NaN cell is the fit of the same dataset without that geometry at
// that wavelength. The reference is an independent fit of the reduced dataset,
// not a number printed by the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/models/registry.h"
#include "support/scratch.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

SpectralDataset without_geometry(const SpectralDataset& d, std::size_t drop) {
  SpectralDataset out = d;
  const std::size_t m = d.wavelength_count();
  out.geometries.erase(out.geometries.begin() + static_cast<long>(drop));
  out.brdf.erase(out.brdf.begin() + static_cast<long>(drop * m), out.brdf.begin() + static_cast<long>((drop + 1) * m));
  if (d.has_sigma()) {
    out.sigma.erase(out.sigma.begin() + static_cast<long>(drop * m),
                    out.sigma.begin() + static_cast<long>((drop + 1) * m));
  }
  return out;
}

void expect_same_fit(const WavelengthFit& a, const WavelengthFit& b) {
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t k = 0; k < a.parameters.size(); ++k) {
    EXPECT_NEAR(a.parameters[k], b.parameters[k], 1e-9 * std::max(1.0, std::fabs(b.parameters[k])))
        << "parameter " << k;
    if (std::isfinite(b.standard_errors[k])) {
      EXPECT_NEAR(a.standard_errors[k], b.standard_errors[k], 1e-7 * std::fabs(b.standard_errors[k])) << "stderr " << k;
    }
  }
  EXPECT_EQ(a.points, b.points);
  EXPECT_NEAR(a.rmse, b.rmse, 1e-10 * b.rmse);
  EXPECT_NEAR(a.chi2, b.chi2, 1e-9 * b.chi2);
  EXPECT_NEAR(a.r_squared, b.r_squared, 1e-9);
  EXPECT_NEAR(a.aic, b.aic, 1e-7 * std::fabs(b.aic));
  EXPECT_NEAR(a.bic, b.bic, 1e-7 * std::fabs(b.bic));
  EXPECT_NEAR(a.max_relative_error, b.max_relative_error, 1e-9);
  EXPECT_EQ(a.converged, b.converged);
}

class FitMissing : public ::testing::TestWithParam<const char*> {};

TEST_P(FitMissing, NanCellEqualsGeometryRemovedAtThatWavelength) {
  auto model = make_model("oren-nayar+torrance-sparrow");
  const std::vector<double> wl = {450.0, 550.0, 650.0};
  const auto grid = test::test_grid(4, 5, 4);
  const SpectralDataset full = test::synthetic_dataset(
      *model, grid, wl,
      [&](std::size_t w) {
        std::vector<double> p = model->description().default_parameters();
        p[*model->description().parameter_index("oren-nayar.albedo")] = 0.2 + 0.1 * static_cast<double>(w);
        p[*model->description().parameter_index("torrance-sparrow.roughness")] = 0.25;
        return p;
      },
      0.02, 1e-4, 7);
  const std::size_t g_missing = 17, w_missing = 1;
  SpectralDataset holed = full;
  holed.value(g_missing, w_missing) = kNaN;

  FitOptions o;
  o.loss = fit_loss_from_string(GetParam());
  o.fixed = {{"oren-nayar.weight", 1.0}, {"torrance-sparrow.weight", 1.0}};
  o.warm_start = false;  // every wavelength from the same start, as in the reduced fits below
  const FitResult with_nan = fit_model(*model, holed, o);
  EXPECT_EQ(with_nan.missing_values, 1u);
  EXPECT_EQ(with_nan.points_total, grid.size() * wl.size() - 1);

  // The wavelength with the hole: the same as the fit of the data without that geometry there.
  const SpectralDataset reduced = subset_wavelengths(without_geometry(full, g_missing), {w_missing});
  const FitResult ref = fit_model(*model, reduced, o);
  EXPECT_EQ(ref.missing_values, 0u);
  expect_same_fit(with_nan.wavelengths[w_missing], ref.wavelengths[0]);
  EXPECT_EQ(with_nan.wavelengths[w_missing].points, grid.size() - 1);
  // ... and not the fit of the complete data there (the comparison can fail).
  const FitResult complete_w = fit_model(*model, subset_wavelengths(full, {w_missing}), o);
  double largest = 0.0;
  for (std::size_t k = 0; k < ref.wavelengths[0].parameters.size(); ++k) {
    largest = std::max(largest, std::fabs(complete_w.wavelengths[0].parameters[k] - ref.wavelengths[0].parameters[k]));
  }
  EXPECT_GT(largest, 1e-5);
  EXPECT_GT(ref.wavelengths[0].iterations, 1);

  // The other wavelengths: the same as the fit of the complete data.
  for (std::size_t w : {std::size_t{0}, std::size_t{2}}) {
    const FitResult complete = fit_model(*model, subset_wavelengths(full, {w}), o);
    expect_same_fit(with_nan.wavelengths[w], complete.wavelengths[0]);
  }
}

INSTANTIATE_TEST_SUITE_P(Losses, FitMissing, ::testing::Values("plain", "relative", "log", "cosine"));

// Through a file: a CSV with a NaN cell (and an empty one) is read, fitted and summarised, never refused.
TEST(FitMissingFile, CsvWithMissingCellsIsFittedAndCounted) {
  auto model = make_model("lambert");
  const std::string path = test::scratch_path("missing_cells.csv");
  {
    std::ofstream f(path);
    f << "theta_i,phi_i,theta_r,phi_r,500,600\n"
         "0,0,10,180,0.050,0.100\n"
         "0,0,30,180,nan,0.110\n"
         "30,0,30,180,0.060,\n"
         "30,0,50,0,0.055,NA\n";
  }
  DatasetReadOptions read;
  read.warn = [](const std::string&) {};
  const SpectralDataset d = read_dataset(path, read);
  EXPECT_EQ(missing_value_count(d), 3u);
  FitRequest request;
  request.models = {"lambert"};
  const FitSummary s = run_fit(request, d);
  EXPECT_EQ(s.missing_values, 3u);
  EXPECT_NE(s.table().find("3 of 8 values missing"), std::string::npos) << s.table();
  const FitResult& f = s.fits[0];
  EXPECT_EQ(f.wavelengths[0].points, 3u);
  EXPECT_EQ(f.wavelengths[1].points, 2u);
  // Lambert by linear least squares: the albedo is pi times the mean of the measured values.
  EXPECT_NEAR(f.wavelengths[0].parameters[0], kPi * (0.050 + 0.060 + 0.055) / 3.0, 1e-9);
  EXPECT_NEAR(f.wavelengths[1].parameters[0], kPi * (0.100 + 0.110) / 2.0, 1e-9);
}

TEST(FitMissingFile, TooFewMeasuredGeometriesAtAWavelengthNamesIt) {
  auto model = make_model("oren-nayar");
  SpectralDataset d;
  d.geometries = test::test_grid(2, 2, 1);
  d.wavelengths = {500.0, 600.0};
  d.brdf = {0.1, kNaN, 0.1, kNaN, 0.1, kNaN, 0.1, 0.2};
  try {
    fit_model(*model, d, FitOptions{});
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at 600 nm only 1 of 4 geometries were measured"), std::string::npos)
        << e.what();
  }
}

TEST(FitMissingFile, InfiniteValueIsStillAnError) {
  auto model = make_model("lambert");
  SpectralDataset d;
  d.geometries = test::test_grid(1, 2, 1);
  d.wavelengths = {500.0};
  d.brdf = {0.1, std::numeric_limits<double>::infinity()};
  EXPECT_THROW(fit_model(*model, d, FitOptions{}), InputError);
}

}  // namespace
}  // namespace roadbrdf
