// Implausible files are read as they are, with a warning: BRDF values above
// 1e3 sr^-1, wavelengths that all look like micrometres or metres, angles that all look like radians
// (zeniths and azimuths judged separately); and a
// fit that reports convergence without leaving its start is warned about.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/dataset_io.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

struct Read {
  SpectralDataset data;
  DatasetReadStats stats;
  std::vector<std::string> warnings;
};

Read read_text(const std::string& name, const std::string& content) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path) << content;
  Read r;
  DatasetReadOptions o;
  o.warn = [&r](const std::string& w) { r.warnings.push_back(w); };
  r.data = read_dataset(path, o, r.stats);
  return r;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& l : lines) {
    if (l.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(Implausible, BrdfAboveAThousandIsWarnedAboutAndKept) {
  const Read r =
      read_text("large.csv", "theta_i,phi_i,theta_r,phi_r,500,600\n0,0,30,180,0.1,0.2\n10,0,30,180,1500,0.3\n");
  EXPECT_EQ(r.stats.implausible_values, 1u);
  EXPECT_EQ(r.data.value(1, 0), 1500.0);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("1 of 4 BRDF values are above 1000 sr^-1 (largest 1500, first at "), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("large.csv:3:13"), std::string::npos) << r.warnings[0];
}

TEST(Implausible, MicrometreWavelengths) {
  const Read r = read_text("um.csv", "theta_i,phi_i,theta_r,phi_r,0.45,0.55,2.5\n0,0,30,180,0.1,0.2,0.3\n");
  EXPECT_TRUE(r.stats.micrometre_wavelengths);
  EXPECT_FALSE(r.stats.metre_wavelengths);
  EXPECT_TRUE(any_contains(r.warnings, "they look like micrometres")) << r.warnings.size();
  EXPECT_TRUE(any_contains(r.warnings, "multiply the wavelengths in the header by 1000"));
  const Read nm = read_text("nm.csv", "theta_i,phi_i,theta_r,phi_r,350,2500\n0,0,30,180,0.1,0.2\n");
  EXPECT_FALSE(nm.stats.micrometre_wavelengths);
  EXPECT_TRUE(nm.warnings.empty());
}

// 1 nm = 1e-9 m: a spectrometer export in metres (4.5e-7 ... 2.5e-6) needs a factor 1e9, not 1000; a long
// file says the wavelengths are in its column.
TEST(Implausible, MetreWavelengthsInTheHeaderOrInTheColumn) {
  const Read wide = read_text("m.csv", "theta_i,phi_i,theta_r,phi_r,4.5e-7,5.5e-7,2.5e-6\n0,0,30,180,0.1,0.2,0.3\n");
  EXPECT_TRUE(wide.stats.metre_wavelengths);
  EXPECT_FALSE(wide.stats.micrometre_wavelengths);
  EXPECT_TRUE(any_contains(wide.warnings, "they look like metres"));
  EXPECT_TRUE(any_contains(wide.warnings, "multiply the wavelengths in the header by 1e9"));
  EXPECT_FALSE(any_contains(wide.warnings, "by 1000"));
  const Read long_file = read_text("m_long.csv",
                                   "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n"
                                   "0,0,30,180,5e-7,0.1\n0,0,30,180,6e-7,0.2\n");
  EXPECT_TRUE(long_file.stats.metre_wavelengths);
  EXPECT_TRUE(any_contains(long_file.warnings, "multiply the wavelengths in the 'wavelength' column by 1e9"));
  const Read um_long = read_text("um_long.csv",
                                 "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n"
                                 "0,0,30,180,0.5,0.1\n0,0,30,180,0.6,0.2\n");
  EXPECT_TRUE(any_contains(um_long.warnings, "multiply the wavelengths in the 'wavelength' column by 1000"));
}

TEST(Implausible, RadianAngles) {
  const Read r = read_text("rad.csv", "theta_i,phi_i,theta_r,phi_r,500\n0.26,0,0.52,1.57,0.1\n0.52,0,0.26,0,0.2\n");
  EXPECT_TRUE(r.stats.radian_angles);
  EXPECT_TRUE(any_contains(r.warnings, "every zenith angle is within 1.6 deg (largest 0.52)"));
  EXPECT_TRUE(any_contains(r.warnings, "they look like radians"));
  // Road angles too; and one angle of 10 deg is enough to be degrees.
  EXPECT_TRUE(read_text("rad_road.csv", "gamma,alpha,beta,delta,500\n0.5,1.5,0,0,0.1\n").stats.radian_angles);
  EXPECT_FALSE(
      read_text("deg.csv", "theta_i,phi_i,theta_r,phi_r,500\n0,0,1,0,0.1\n10,0,1,0,0.1\n").stats.radian_angles);
}

// A goniometer table in radians whose azimuths reach pi (the whole principal plane) or 2 pi: zeniths
// within pi/2 and azimuths within 2 pi are judged separately (pi = 3.14 is above the zenith limit).
TEST(Implausible, RadianAnglesWithAzimuthsUpToPiAndTwoPi) {
  const Read pi = read_text("rad_pi.csv",
                            "theta_i,phi_i,theta_r,phi_r,500\n0.52,0,0.26,3.14159,0.1\n0.52,0,0.79,0,0.2\n"
                            "1.05,0,1.31,3.14159,0.3\n");
  EXPECT_TRUE(pi.stats.radian_angles);
  EXPECT_TRUE(any_contains(pi.warnings, "largest 3.14159"));
  const Read two_pi =
      read_text("rad_2pi.csv", "theta_i,phi_i,theta_r,phi_r,500\n0.52,0,0.26,6.2,0.1\n0.52,4.71,0.79,-1.5,0.2\n");
  EXPECT_TRUE(two_pi.stats.radian_angles);
  // Degrees with small zeniths but real azimuths stay degrees.
  EXPECT_FALSE(read_text("deg_small.csv", "theta_i,phi_i,theta_r,phi_r,500\n1,0,1.5,180,0.1\n").stats.radian_angles);
}

TEST(Implausible, FitThatNeverLeavesItsStartIsWarnedAbout) {
  // With the specular weight held at 0 the Torrance-Sparrow parameters have no effect: the
  // optimiser reports convergence at once, with those parameters where they started.
  std::string content = "theta_i,phi_i,theta_r,phi_r,500\n";
  for (int ti : {0, 20, 40, 60}) {
    for (int tr : {10, 30, 50, 70}) content += std::to_string(ti) + ",0," + std::to_string(tr) + ",180,0.1\n";
  }
  const Read r = read_text("flat.csv", content);
  FitRequest request;
  request.models = {"lambert+torrance-sparrow"};
  request.fixed = {{"torrance-sparrow.weight", 0.0}, {"lambert.weight", 1.0}};
  const FitSummary s = run_fit(request, r.data);
  EXPECT_EQ(s.fits[0].converged_count, 1u);
  EXPECT_EQ(s.fits[0].stayed_at_start_count, 1u);
  EXPECT_TRUE(any_contains(s.warnings("f.json"), "never left their starting values"));
  // A fit that moves is not flagged.
  FitRequest moving;
  moving.models = {"oren-nayar"};
  EXPECT_EQ(run_fit(moving, r.data).fits[0].stayed_at_start_count, 0u);
}

}  // namespace
}  // namespace roadbrdf
