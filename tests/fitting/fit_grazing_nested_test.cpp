// Rows measured at exactly 90 deg (no irradiance, or nothing in view) are left out of a fit with a
// note, so that Oren-Nayar fits the rest (its closed form diverges when both directions are grazing);
// and a fit worse than a fit of a model it contains is flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/fit_request.h"

namespace roadbrdf {
namespace {

// A Lambertian surface of albedo 0.3 measured at theta_i, theta_r in {0, 20, 40, 60, 80} deg (retro and
// forward planes), plus the rows a goniometer table had at exactly 90 deg, with the instrument's zero
// (no signal) as their value.
SpectralDataset lambert_with_grazing_rows() {
  SpectralDataset d;
  d.wavelengths = {500.0, 600.0};
  auto add = [&d](double ti, double tr, double dphi, double value) {
    d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    d.brdf.insert(d.brdf.end(), {value, value});
  };
  for (double ti : {0.0, 20.0, 40.0, 60.0, 80.0}) {
    for (double tr : {0.0, 20.0, 40.0, 60.0, 80.0}) {
      for (double dphi : {0.0, 180.0}) add(ti, tr, dphi, 0.3 / std::numbers::pi);
    }
  }
  add(90.0, 90.0, 0.0, 0.0);
  add(90.0, 30.0, 180.0, 0.0);
  add(45.0, 90.0, 180.0, 0.0);
  return d;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& l : lines) {
    if (l.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(FitGrazing, RowsAtNinetyDegreesAreLeftOutWithANote) {
  const SpectralDataset d = lambert_with_grazing_rows();
  EXPECT_EQ(grazing_geometries(d), (std::vector<std::size_t>{50, 51, 52}));
  FitRequest request;
  request.models = {"oren-nayar", "lambert"};
  const FitSummary s = run_fit(request, d);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("3 of 53 geometries have a direction at 90 deg"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("#51 (theta_i 90, phi_i 0, theta_r 90, phi_r 0 deg)"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.table().find("# note: 3 of 53 geometries"), std::string::npos);
  EXPECT_EQ(s.geometry_count, 50u);
  // Both recover the albedo of the data (Oren-Nayar at sigma = 0 is Lambert), exactly as a closed form.
  for (const FitResult& f : s.fits) {
    EXPECT_NEAR(f.wavelengths[0].parameters[0], 0.3, 1e-4) << f.model;
    EXPECT_EQ(f.points_total, 100u) << f.model;
    EXPECT_TRUE(f.worse_than_nested.empty()) << f.model;
  }
  // The residuals file's spectra are the fitted ones.
  EXPECT_EQ(fitted_spectra(request, d).geometry_count(), 50u);
}

TEST(FitGrazing, OnlyGrazingRowsIsRefused) {
  SpectralDataset d;
  d.wavelengths = {500.0};
  d.geometries = {geometry_from_degrees(90.0, 0.0, 30.0, 0.0), geometry_from_degrees(30.0, 0.0, 90.0, 0.0)};
  d.brdf = {0.1, 0.1};
  FitRequest request;
  request.models = {"lambert"};
  EXPECT_THROW(run_fit(request, d), InputError);
}

TEST(NestedModels, ContainmentFromCompositesAndReducesTo) {
  EXPECT_TRUE(model_contains("oren-nayar", "lambert"));  // sigma = 0
  EXPECT_TRUE(model_contains("oren-nayar+torrance-sparrow", "oren-nayar"));
  EXPECT_TRUE(model_contains("oren-nayar+torrance-sparrow", "torrance-sparrow"));
  EXPECT_TRUE(model_contains("oren-nayar+torrance-sparrow", "lambert"));
  EXPECT_TRUE(model_contains("lambert+torrance-sparrow", "lambert"));
  EXPECT_FALSE(model_contains("lambert", "oren-nayar"));
  EXPECT_FALSE(model_contains("oren-nayar", "oren-nayar"));
  EXPECT_FALSE(model_contains("oren-nayar", "lambert+torrance-sparrow"));
  EXPECT_FALSE(model_contains("hapke", "lambert"));
  EXPECT_FALSE(model_contains("lambert+lambert", "oren-nayar"));
}

// Two fits of one request: Oren-Nayar ending worse than Lambert (as the fit with the 90 deg rows did) is
// flagged in FitResult, the summary table and the fit file; the reverse is not a flag.
TEST(NestedModels, WorseThanAContainedModelIsFlagged) {
  FitSummary s;
  s.wavelengths = {500.0};
  FitResult on, lambert;
  on.model = "oren-nayar";
  on.rmse_total = 0.02;
  on.relative_rmse_total = 0.2;
  lambert.model = "lambert";
  lambert.rmse_total = 0.01;
  lambert.relative_rmse_total = 0.1;
  s.fits = {on, lambert};
  flag_worse_than_nested(s.fits, 0);
  EXPECT_EQ(s.fits[0].worse_than_nested, (std::vector<std::string>{"lambert"}));
  EXPECT_TRUE(s.fits[1].worse_than_nested.empty());
  s.ranking = {1, 0};
  EXPECT_NE(s.table().find("# flag: oren-nayar fits worse (RMSE 0.02) than lambert (RMSE 0.01), a model it contains"),
            std::string::npos)
      << s.table();
  EXPECT_EQ(fit_to_json(s.fits[0]).at("worse_than_nested"), nlohmann::json::array({"lambert"}));
  // Better or equal (to rounding): no flag.
  s.fits[0].worse_than_nested.clear();
  s.fits[0].rmse_total = 0.01;
  s.fits[0].relative_rmse_total = 0.1 * (1.0 + 1e-4);  // within the convergence margin
  flag_worse_than_nested(s.fits, 0);
  EXPECT_TRUE(s.fits[0].worse_than_nested.empty());
  EXPECT_FALSE(any_contains({s.table()}, "# flag:"));
}

}  // namespace
}  // namespace roadbrdf
