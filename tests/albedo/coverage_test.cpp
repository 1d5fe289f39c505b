// Angular coverage of a fit's data and how much of an albedo or r-table lies outside it.
// References: closed forms for a Lambertian surface (the share of int cos(theta) dw beyond
// a zenith angle T is cos^2 T; an azimuth sector of width W holds W/360 of it) and hand-made
// tables; the fit file round trip is checked against the coverage computed here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/albedo/coverage.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/coverage.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/photometry/rtable_coverage.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

std::vector<Geometry> grid(double ti_max, double tr_max, const std::vector<double>& dphi) {
  std::vector<Geometry> g;
  for (double ti = 0.0; ti <= ti_max + 1e-9; ti += 5.0) {
    for (double tr = 0.0; tr <= tr_max + 1e-9; tr += 5.0) {
      for (double d : dphi) g.push_back(geometry_from_degrees(ti, 0.0, tr, d));
    }
  }
  return g;
}

std::vector<double> every_5_deg() {
  std::vector<double> v;
  for (double d = 0.0; d <= 180.0; d += 5.0) v.push_back(d);
  return v;
}

TEST(Coverage, RangesPlanesAndCovers) {
  const AngularCoverage c = angular_coverage(grid(40.0, 60.0, {0.0, 90.0, 180.0}));
  EXPECT_NEAR(c.theta_i_min_deg, 0.0, 1e-9);
  EXPECT_NEAR(c.theta_i_max_deg, 40.0, 1e-9);
  EXPECT_NEAR(c.theta_r_max_deg, 60.0, 1e-9);
  EXPECT_EQ(c.azimuth_planes_deg, (std::vector<double>{0.0, 90.0, 180.0}));  // beta = 180 - dphi
  EXPECT_EQ(c.geometries, 9u * 13u * 3u);
  EXPECT_TRUE(c.covers(geometry_from_degrees(44.0, 0.0, 30.0, 176.0)));   // within 5 deg of the plane and range
  EXPECT_FALSE(c.covers(geometry_from_degrees(46.0, 0.0, 30.0, 180.0)));  // theta_i beyond 40 + 5
  EXPECT_FALSE(c.covers(geometry_from_degrees(30.0, 0.0, 66.0, 180.0)));  // theta_r beyond 60 + 5
  EXPECT_FALSE(c.covers(geometry_from_degrees(30.0, 0.0, 30.0, 135.0)));  // between the planes
  EXPECT_TRUE(c.covers(geometry_from_degrees(30.0, 0.0, 3.0, 135.0)));    // near the normal: any plane
  EXPECT_TRUE(c.covers(geometry_from_degrees(30.0, 10.0, 30.0, 280.0)));  // |dphi| = 270 -> 90: the plane 90
}

TEST(Coverage, LambertianOutsideFractionsAreClosedForms) {
  auto lambert = make_model("lambert");
  const double p[1] = {0.5};
  // Every plane, theta_r measured to 45 deg (covered to 50): cos^2(50 deg) of the integral is outside.
  const AngularCoverage to45 = angular_coverage(grid(80.0, 45.0, every_5_deg()));
  const double expected = std::pow(std::cos(50.0 * kDegree), 2);
  EXPECT_NEAR(albedo::black_sky_outside(*lambert, p, 30.0 * kDegree, to45).fraction, expected, 2e-3);
  // White-sky: the same for every incidence inside the theta_i range (covered to 85 deg); the
  // incidences beyond 85 deg (weight cos^2 85 of the white-sky integral) are all outside.
  const double beyond = std::pow(std::cos(85.0 * kDegree), 2);
  EXPECT_NEAR(albedo::white_sky_outside(*lambert, p, to45).fraction, (1.0 - beyond) * expected + beyond, 2e-3);
  // Incidence outside the measured range: all of it.
  const AngularCoverage low = angular_coverage(grid(20.0, 85.0, every_5_deg()));
  EXPECT_DOUBLE_EQ(albedo::black_sky_outside(*lambert, p, 60.0 * kDegree, low).fraction, 1.0);
  // Principal plane only (dphi 0 and 180): 4 sectors of 5 deg of 360 are covered, plus the cap
  // theta_r <= 5 deg, which the 2-deg grid resolves as 4 or 6 deg (a cell midpoint sits at 5 deg):
  // outside = (1 - sin^2 cap)(1 - 1/18).
  const AngularCoverage plane = angular_coverage(grid(80.0, 85.0, {0.0, 180.0}));
  const double cap4 = std::pow(std::sin(4.0 * kDegree), 2), cap6 = std::pow(std::sin(6.0 * kDegree), 2);
  const double pp = albedo::black_sky_outside(*lambert, p, 30.0 * kDegree, plane).fraction;
  EXPECT_GE(pp, (1.0 - cap6) * 17.0 / 18.0 - 1e-3);
  EXPECT_LE(pp, (1.0 - cap4) * 17.0 / 18.0 + 1e-3);
  // Complete coverage: nothing outside.
  const AngularCoverage all = angular_coverage(grid(90.0, 90.0, every_5_deg()));
  EXPECT_EQ(albedo::white_sky_outside(*lambert, p, all).fraction, 0.0);
}

TEST(Coverage, FitFileRecordsItAndAlbedoReportsIt) {
  const double cap4 = std::pow(std::sin(4.0 * kDegree), 2), cap6 = std::pow(std::sin(6.0 * kDegree), 2);
  auto model = make_model("lambert");
  SpectralDataset d;
  d.geometries = grid(60.0, 45.0, {0.0, 180.0});
  d.wavelengths = {550.0};
  d.brdf.assign(d.geometries.size(), 0.3 / kPi);
  d.brdf[4] = std::nan("");  // one wavelength: geometry 5 was measured at none, so it is not in the coverage
  const FitResult fit = fit_model(*model, d, FitOptions{});
  const std::string path = test::scratch_path("coverage.fit.json");
  write_fit_file(path, {fit});
  const SpectralModel sm = read_fit_file(path);
  ASSERT_TRUE(sm.coverage().has_value());
  const AngularCoverage& c = *sm.coverage();
  EXPECT_NEAR(c.theta_i_max_deg, 60.0, 1e-9);
  EXPECT_NEAR(c.theta_r_max_deg, 45.0, 1e-9);
  EXPECT_EQ(c.azimuth_planes_deg, (std::vector<double>{0.0, 180.0}));
  EXPECT_EQ(c.geometries, d.geometries.size() - 1);  // geometry 5 was measured at no wavelength
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = {30.0, 80.0};
  // Progress: one unit per integral (each black-sky one and the white-sky one), then finish. The fit
  // has a covariance, and Lambert declares no mirror lobe, so each value is integrated with its
  // gradient in one pass (report_stages.h): nothing is added to the total. One thread, so that no
  // report is skipped while another is being made (core/progress.h).
  request.threads = 1;
  std::vector<std::pair<std::size_t, std::size_t>> progress;
  request.progress = [&](std::size_t done, std::size_t total) { progress.emplace_back(done, total); };
  const nlohmann::json report = albedo::compute_albedo(sm, request);
  EXPECT_EQ(progress, (std::vector<std::pair<std::size_t, std::size_t>>{{1, 3}, {2, 3}, {3, 3}, {3, 3}}));
  EXPECT_TRUE(report["uncertainty"].is_object());
  const auto& cov = report.at("coverage");
  // Planes 0 and 180 only, theta_r covered to 50 deg (see LambertianOutsideFractionsAreClosedForms).
  const double to50 = std::pow(std::sin(50.0 * kDegree), 2);
  const double b0 = cov.at("black_sky_outside_fraction")[0].get<double>();
  EXPECT_GE(b0, 1.0 - (cap6 + (to50 - cap6) / 18.0) - 1e-3);
  EXPECT_LE(b0, 1.0 - (cap4 + (to50 - cap4) / 18.0) + 1e-3);
  EXPECT_DOUBLE_EQ(cov.at("black_sky_outside_fraction")[1].get<double>(), 1.0);  // 80 > 60 + 5
  bool warned = false;
  for (const auto& w : report.at("warnings")) warned = warned || w.at("kind") == "mostly_extrapolated";
  EXPECT_TRUE(warned) << report.at("warnings").dump();
}

TEST(Coverage, RTableOutsideCellsAndNegativeCells) {
  auto lambert = make_model("lambert");
  const photometry::RTable t = photometry::compute_rtable(*lambert, {0.3}, 1.0);
  // Measured to theta_r 60: the r-table's theta_r = 89 deg is never covered.
  const auto c60 = photometry::rtable_coverage(t, angular_coverage(grid(80.0, 60.0, every_5_deg())));
  EXPECT_EQ(c60.cells, 580u);
  EXPECT_EQ(c60.outside, 580u);
  EXPECT_EQ(c60.standard_cells, 396u);
  EXPECT_EQ(c60.negative, 0u);
  ASSERT_EQ(c60.notes().size(), 2u);
  EXPECT_EQ(c60.notes()[1].rfind("WARNING: mostly extrapolation", 0), 0u);
  // Measured to theta_r 85 (covered to 90), theta_i to 85 (90), every plane of the table's 20 betas.
  const AngularCoverage full = angular_coverage(grid(85.0, 85.0, every_5_deg()));
  const auto cf = photometry::rtable_coverage(t, full);
  EXPECT_EQ(cf.outside, 0u);
  EXPECT_EQ(cf.notes().size(), 1u);
  // Unknown coverage: only the negative cells are reported.
  photometry::RTable neg = t;
  neg.at(3, 4) = -1.0;
  const auto cn = photometry::rtable_coverage(neg, std::nullopt);
  EXPECT_EQ(cn.negative, 1u);
  ASSERT_EQ(cn.notes().size(), 1u);
  EXPECT_EQ(cn.notes()[0], "WARNING: non-physical: 1 r-table cells are negative");
}

TEST(Coverage, AlbedoAboveOneIsFlagged) {
  Diagnostics diagnostics;
  albedo::flag_non_physical({0.0, 60.0}, {500.0, 600.0}, {{0.4, 0.5}, {1.2, 0.9}}, {0.6, 0.7}, diagnostics);
  ASSERT_EQ(diagnostics.warnings.size(), 1u);
  EXPECT_EQ(diagnostics.warnings[0].kind, "albedo_above_one");
  const std::string& message = diagnostics.warnings[0].message;
  EXPECT_NE(message.find("largest black-sky 1.2 at sun zenith 60 deg, 500 nm"), std::string::npos) << message;
  EXPECT_TRUE(diagnostics.notes.empty());
  diagnostics = {};
  albedo::flag_non_physical({0.0}, {500.0}, {{0.99}}, {0.98}, diagnostics);
  EXPECT_TRUE(diagnostics.warnings.empty());
}

}  // namespace
}  // namespace roadbrdf
