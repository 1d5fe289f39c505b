// The r-table request and report (photometry/rtable_request.h): one validation naming fields, the
// figures of a Lambertian surface against their closed forms, and the notes and warnings that the
// command line and Python both print. The command line's own translation is checked at the end.
#include "roadbrdf/photometry/rtable_request.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "roadbrdf/core/error.h"
#include "roadbrdf/models/registry.h"
#include "support/cli.h"

namespace roadbrdf::photometry {
namespace {

std::string field_of(const RTableRequest& request, bool import = false) {
  try {
    import ? request.validate_for_import() : request.validate();
  } catch (const FieldError& e) {
    return e.field();
  }
  return "";
}

SpectralModel lambert(double albedo) {
  return SpectralModel(std::shared_ptr<const Model>(make_model("lambert")), std::vector<double>{albedo});
}

TEST(RTableRequest, ValidationNamesTheField) {
  RTableRequest ok;
  EXPECT_EQ(field_of(ok), "");
  RTableRequest r = ok;
  r.alpha = 0.0;
  EXPECT_EQ(field_of(r), "alpha");
  r.alpha = 90.0;
  EXPECT_EQ(field_of(r), "alpha");
  r = ok;
  r.wavelength = 550.0;
  r.band = std::pair{500.0, 600.0};
  EXPECT_EQ(field_of(r), "band");
  r = ok;
  r.band = std::pair{600.0, 500.0};
  EXPECT_EQ(field_of(r), "band");
  r = ok;
  r.wavelength = -1.0;
  EXPECT_EQ(field_of(r), "wavelength");
  r = ok;
  r.wavelength = 550.0;
  r.illuminant = "D65";
  EXPECT_EQ(field_of(r), "illuminant");
  r = ok;
  r.q0_region = "everything";
  EXPECT_EQ(field_of(r), "q0_region");
  r = ok;
  r.class_system = "Q";
  EXPECT_EQ(field_of(r), "class_system");
  r = ok;
  r.wavelength = 550.0;
  EXPECT_EQ(field_of(r), "");
  EXPECT_EQ(field_of(r, /*import=*/true), "wavelength");
}

// Lambertian surface of albedo rho: q = rho/pi everywhere, so Q0 = rho/pi on any region,
// r(0, 0) = rho/pi, S1 = r(beta 0, tan gamma 2) / r(0, 0) = cos^3(atan 2) = 5^-3/2 = 0.0894 (class R1,
// S1 < 0.42; N1, S1 < 0.28; C1, S1 < 0.40) and S2 = Q0 / r(0, 0) = 1.
TEST(RTableRequest, LambertianReportMatchesClosedForms) {
  const double rho = 0.3;
  RTableRequest request;
  request.class_system = "N";
  const RTableReport report = rtable_report(lambert(rho), request);
  EXPECT_NEAR(report.summary.q0, rho / std::numbers::pi, 1e-12);
  EXPECT_NEAR(report.summary.r00, rho / std::numbers::pi, 1e-12);
  EXPECT_NEAR(report.summary.s1, std::pow(5.0, -1.5), 1e-12);
  EXPECT_NEAR(report.summary.s2, 1.0, 1e-12);
  EXPECT_EQ(report.chosen.name, "N1");
  EXPECT_EQ(report.summary.r_class.name, "R1");
  const nlohmann::json j = report.to_json();
  EXPECT_EQ(j.at("class"), "N1");
  EXPECT_EQ(j.at("class_system"), "N");
  EXPECT_EQ(j.at("weighting").at("kind"), "none (wavelength-independent model)");
  EXPECT_EQ(j.at("r").size(), kRows);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(RTableRequest, SpectralChoiceOnAConstantModelIsAWarning) {
  RTableRequest request;
  request.wavelength = 550.0;
  const RTableReport report = rtable_report(lambert(0.2), request);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("do not depend on wavelength"), std::string::npos);
}

// An imported table of r = 1 sr^-1 in every cell: q = r / cos^3(gamma) >= 1, so Q0 >= 1 sr^-1, far
// above any road surface, and a declared q0 of 0.07 disagrees with it.
TEST(RTableRequest, ImplausibleAndInconsistentImportsAreWarnedAbout) {
  RTableFile file;
  for (double& cell : file.table.scaled) cell = kRScale * 1.0;
  file.declared_q0 = 0.07;
  const RTableReport report = rtable_report(file, RTableRequest{});
  EXPECT_GE(report.summary.q0, 1.0);
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("implausibly large"), std::string::npos);
  EXPECT_NE(report.warnings[1].find("declares q0 = 0.07"), std::string::npos);
  EXPECT_TRUE(report.weighting.is_null());
}

TEST(RTableRequest, ComparisonWithItselfIsZero) {
  RTableReport report = rtable_report(lambert(0.25), RTableRequest{});
  const RTable same = report.table;
  report.compare_with(same, "same");
  ASSERT_TRUE(report.comparison);
  EXPECT_EQ(report.comparison->max_relative, 0.0);
  EXPECT_EQ(report.comparison->compared_cells, kRows * kColumns);
  EXPECT_EQ(report.to_json().at("comparison").at("other"), "same");
}

// The command line names its flags for the library's fields, and prints the report's warnings.
TEST(RTableRequest, CommandLineMapsFieldsToFlags) {
  using roadbrdf::test::run_cli;
  auto r = run_cli("rtable lambert -p albedo=0.3 --alpha 95");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("roadbrdf: error: --alpha: must lie in (0, 90) deg"), std::string::npos) << r.output;
  r = run_cli("rtable lambert -p albedo=0.3 --wavelength 550 --band 500:600");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--band: excludes a single wavelength"), std::string::npos) << r.output;
  r = run_cli("rtable lambert -p albedo=0.3 --wavelength 550");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("roadbrdf: warning: the model's parameters do not depend on wavelength"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace roadbrdf::photometry
