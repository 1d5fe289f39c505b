// Tests of the CIE photometric tables and weights (photometry/cie.h).
// References: CIE 1931 V(lambda) definition (peak 1 at 555 nm), the Planck formula that defines CIE
// illuminant A (CIE 15: S_A(l) = 100 (560/l)^5 (exp(c2/(2848*560e-9)) - 1) / (exp(c2/(2848 l)) - 1),
// c2 = 1.435e-2 m K), the integral of V(lambda) over 360-830 nm (106.857 nm, CIE 1 nm table),
// the CIE 1931 5 nm y-bar values at odd 5 nm wavelengths, and closed-form integrals of simple spectra.
#include "roadbrdf/spectra/cie.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "roadbrdf/core/error.h"

namespace roadbrdf::photometry {
namespace {

std::string temp_file(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::path(roadbrdf::test::scratch_path("photometry_cie_" + name));
  std::ofstream(path) << content;
  return path.string();
}

double planck_a(double nm) {
  const double c2 = 1.435e-2;  // m K, as in the CIE definition of illuminant A
  const double t = 2848.0;
  const double l = nm * 1e-9;
  return 100.0 * std::pow(560.0 / nm, 5) * (std::exp(c2 / (t * 560e-9)) - 1.0) / (std::exp(c2 / (t * l)) - 1.0);
}

TEST(Cie, VLambdaPeakIsOneAt555) {
  EXPECT_NEAR(v_lambda().value(555.0), 1.0, 5e-4);
  // tabulated points are reproduced exactly
  EXPECT_DOUBLE_EQ(v_lambda().value(550.0), 0.9949501);
  EXPECT_DOUBLE_EQ(v_lambda().value(560.0), 0.995);
  // and nothing exceeds the peak by more than the interpolation error
  for (double l = 500.0; l <= 600.0; l += 0.5) EXPECT_LE(v_lambda().value(l), 1.0 + 5e-4) << l;
}

TEST(Cie, VLambdaBetweenTheTenNanometrePoints) {
  // CIE 1931 y-bar at the odd 5 nm wavelengths (CIE 15 5 nm table), which the bundled 10 nm table lacks:
  // Sprague interpolation reproduces them to 0.0015.
  const double table[][2] = {{505, 0.40730}, {515, 0.60820}, {525, 0.79320}, {535, 0.91486},
                             {545, 0.98000}, {565, 0.97860}, {575, 0.91540}, {585, 0.81630},
                             {595, 0.69490}, {605, 0.56680}, {615, 0.44120}};
  for (const auto& row : table) EXPECT_NEAR(v_lambda().value(row[0]), row[1], 1.5e-3) << row[0];
}

TEST(Cie, VLambdaIsZeroOutsideItsTable) {
  EXPECT_EQ(v_lambda().value(200.0), 0.0);
  EXPECT_EQ(v_lambda().value(1000.0), 0.0);
  for (double l = 330.0; l <= 840.0; l += 0.25) EXPECT_GE(v_lambda().value(l), 0.0) << l;
}

TEST(Cie, VLambdaIntegral) {
  // CIE 1931 y-bar summed over the 1 nm table 360-830 nm: 106.857 nm.
  double sum = 0.0;
  for (int l = 360; l <= 830; ++l) sum += v_lambda().value(l);
  EXPECT_NEAR(sum, 106.857, 0.05);
}

TEST(Cie, IlluminantAFollowsPlanck) {
  for (double l : {380.0, 432.0, 555.0, 589.0, 640.5, 777.0}) {
    EXPECT_NEAR(illuminant_a().value(l) / planck_a(l), 1.0, 2e-3) << l;
  }
  EXPECT_DOUBLE_EQ(illuminant_d65().value(560.0), 100.0);
  EXPECT_THROW(illuminant_d65().value(900.0), InputError);
}

TEST(Cie, IlluminantByName) {
  EXPECT_DOUBLE_EQ(illuminant_from_name("a").value(560.0), 100.0);
  EXPECT_DOUBLE_EQ(illuminant_from_name("D65").value(500.0), 109.33);
}

TEST(Cie, WeightsSumToOneAndReproduceAFlatSpectrum) {
  std::vector<double> grid;
  for (double l = 300.0; l <= 1000.0; l += 5.0) grid.push_back(l);
  const auto w = photometric_weights(grid, illuminant_d65());
  ASSERT_EQ(w.size(), grid.size());
  EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-12);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (grid[k] < 340.0 || grid[k] > 830.0) {
      EXPECT_EQ(w[k], 0.0) << grid[k];
    }
    EXPECT_GE(w[k], 0.0);
  }
  // weighted mean of a constant = the constant
  double mean = 0.0;
  for (std::size_t k = 0; k < grid.size(); ++k) mean += w[k] * 0.37;
  EXPECT_NEAR(mean, 0.37, 1e-14);
}

TEST(Cie, WeightsFollowVTimesSTimesWidth) {
  // Non-uniform grid: w_k proportional to V S dl_k with trapezoid widths.
  const std::vector<double> grid = {400.0, 500.0, 550.0, 560.0, 600.0, 700.0, 800.0};
  const auto w = photometric_weights(grid, illuminant_a());
  const auto raw = [&](std::size_t k, double width) {
    return v_lambda().value(grid[k]) * illuminant_a().value(grid[k]) * width;
  };
  EXPECT_NEAR(w[2] / w[3], raw(2, 30.0) / raw(3, 25.0), 1e-12);
  EXPECT_NEAR(w[0] / w[6], raw(0, 50.0) / raw(6, 50.0), 1e-12);
}

TEST(Cie, WeightsRefuseAGridMissingMostOfTheVisible) {
  EXPECT_THROW(photometric_weights({340.0, 400.0, 500.0}, illuminant_d65()), InputError);
  EXPECT_THROW(photometric_weights({550.0}, illuminant_d65()), InputError);
  EXPECT_THROW(photometric_weights({600.0, 500.0}, illuminant_d65()), InputError);
}

TEST(Cie, CoverageOfTheWholeRangeIsOne) {
  EXPECT_NEAR(luminous_coverage(300.0, 900.0, illuminant_a()), 1.0, 1e-12);
  // V(lambda) is symmetric enough that 555 nm splits the luminous integral of an equal-energy
  // spectrum roughly in half; under illuminant A (red-rich) more lies above.
  const double below = luminous_coverage(0.0, 555.0, illuminant_a());
  EXPECT_GT(below, 0.3);
  EXPECT_LT(below, 0.5);
}

TEST(Cie, LampFile) {
  // Equal-energy lamp: the weighted mean of V over it is int V^2 / int V.
  const std::string path = temp_file("flat.csv", "# flat lamp\nwavelength_nm,power\n360,2\n830,2\n");
  const spectra::Spectrum lamp = read_lamp_spectrum(path);
  EXPECT_DOUBLE_EQ(lamp.value(555.0), 2.0);
  EXPECT_FALSE(lamp.uses_sprague());
  std::vector<double> grid;
  for (double l = 360.0; l <= 830.0; l += 1.0) grid.push_back(l);
  const auto w = photometric_weights(grid, lamp);
  double v_mean = 0.0, v2 = 0.0, v1 = 0.0;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    v_mean += w[k] * v_lambda().value(grid[k]);
    v2 += std::pow(v_lambda().value(grid[k]), 2);
    v1 += v_lambda().value(grid[k]);
  }
  EXPECT_NEAR(v_mean, v2 / v1, 1e-3);
  std::filesystem::remove(path);
}

TEST(Cie, LampFileErrorsNameLineAndColumn) {
  const std::string bad = temp_file("bad.csv", "wavelength_nm,power\n400,1\n500,x\n");
  try {
    read_lamp_spectrum(bad);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 5);
  }
  const std::string narrow = temp_file("narrow.csv", "500,1\n600,1\n");
  EXPECT_THROW(read_lamp_spectrum(narrow), FileError);  // covers too little of V(lambda)
  const std::string negative = temp_file("negative.csv", "380,1\n500,-1\n780,1\n");
  EXPECT_THROW(read_lamp_spectrum(negative), FileError);
  const std::string order = temp_file("order.csv", "380,1\n500,1\n490,1\n780,1\n");
  EXPECT_THROW(read_lamp_spectrum(order), FileError);
  for (const auto& p : {bad, narrow, negative, order}) std::filesystem::remove(p);
}

}  // namespace
}  // namespace roadbrdf::photometry
