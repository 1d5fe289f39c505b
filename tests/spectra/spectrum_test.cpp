// Tests of the spectrum type, its interpolator and its file reader (spectra/spectrum.h,
// spectra/interpolation.h, spectra/spectrum_file.h). Expectations are closed forms: linear
// interpolation of a linear function is exact; Sprague's quintic reproduces polynomials of degree
// <= 4 on a uniform grid (its end points extrapolate lines exactly); file errors are placed by
// counting lines and characters of the text written here.
#include "roadbrdf/spectra/spectrum.h"
#include "roadbrdf/spectra/spectrum_file.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"

namespace roadbrdf::spectra {
namespace {

std::string temp_file(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::path(roadbrdf::test::scratch_path("spectrum_" + name));
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// The FileError of reading `content` with `options`; fails the test when the file is accepted.
FileError read_error(const std::string& name, const std::string& content, const SpectrumReadOptions& options = {}) {
  const std::string path = temp_file(name, content);
  try {
    read_spectrum(path, options);
  } catch (const FileError& e) {
    std::filesystem::remove(path);
    return e;
  }
  std::filesystem::remove(path);
  ADD_FAILURE() << name << ": accepted";
  return FileError("", 0, 0, "");
}

std::vector<double> uniform_grid(double first, double step, int n) {
  std::vector<double> x;
  for (int k = 0; k < n; ++k) x.push_back(first + step * k);
  return x;
}

TEST(Interpolation, LinearIsExactForLinearFunctions) {
  const std::vector<double> x = {300.0, 312.5, 400.0, 401.0, 650.0, 1000.0};  // uneven on purpose
  auto f = [](double l) { return 0.25 - 0.0015 * l; };
  std::vector<double> y;
  for (double l : x) y.push_back(f(l));
  const Spectrum s("line", x, y);
  for (double l : {300.0, 305.0, 312.5, 355.5, 400.7, 999.9, 1000.0}) {
    EXPECT_NEAR(s.value(l), f(l), 1e-14) << l;
    EXPECT_NEAR(interpolate_linear(x, y, l, Extrapolation::kRefuse, "line"), f(l), 1e-14) << l;
  }
  EXPECT_FALSE(Spectrum("line", x, y, Interpolation::kSprague).uses_sprague());  // not uniform
}

TEST(Interpolation, StencilWeightsBracketTheWavelength) {
  const std::vector<double> x = {400.0, 500.0, 700.0};
  const auto s = linear_stencil(x, 650.0, Extrapolation::kRefuse, "x");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->lower, 1u);
  EXPECT_EQ(s->upper, 2u);
  EXPECT_DOUBLE_EQ(s->t, 0.75);
  const auto end = linear_stencil(x, 700.0, Extrapolation::kRefuse, "x");
  EXPECT_EQ(end->upper, 2u);
  EXPECT_DOUBLE_EQ(end->t, 1.0);
  const auto one = linear_stencil({550.0}, 550.0, Extrapolation::kRefuse, "x");
  EXPECT_EQ(one->lower, 0u);
  EXPECT_EQ(one->upper, 0u);
}

TEST(Interpolation, SpragueReproducesQuarticsOnUniformGrids) {
  // p(l) = 2 + u - 3 u^2 + 0.5 u^3 + 0.25 u^4, u = (l - 500)/100, on 400..700 nm every 10 nm.
  auto p = [](double l) {
    const double u = (l - 500.0) / 100.0;
    return 2.0 + u - 3.0 * u * u + 0.5 * u * u * u + 0.25 * u * u * u * u;
  };
  const std::vector<double> x = uniform_grid(400.0, 10.0, 31);
  std::vector<double> y;
  for (double l : x) y.push_back(p(l));
  const Spectrum s("quartic", x, y, Interpolation::kSprague);
  ASSERT_TRUE(s.uses_sprague());
  // Where the six points are all tabulated (from the third interval to the third last).
  for (double l = 420.0; l <= 680.0; l += 0.7) EXPECT_NEAR(s.value(l), p(l), 1e-12) << l;
  // A quintic is exact at the middle of each interval (the formula is symmetric there), not elsewhere.
  auto q = [](double l) { return std::pow((l - 500.0) / 100.0, 5) + 1.0; };
  std::vector<double> yq;
  for (double l : x) yq.push_back(q(l));
  const Spectrum quintic("quintic", x, yq, Interpolation::kSprague);
  for (double l = 425.0; l <= 675.0; l += 10.0) EXPECT_NEAR(quintic.value(l), q(l), 1e-12) << l;
  // The tabulated values themselves, whatever the polynomial.
  for (std::size_t k = 0; k < x.size(); ++k) EXPECT_EQ(quintic.value(x[k]), yq[k]);
}

TEST(Interpolation, SpragueEndPointsExtrapolateLinesExactly) {
  auto f = [](double l) { return 3.0 - 0.002 * l; };  // positive on the grid
  const std::vector<double> x = uniform_grid(380.0, 5.0, 8);
  std::vector<double> y;
  for (double l : x) y.push_back(f(l));
  const Spectrum s("line", x, y, Interpolation::kSprague);
  ASSERT_TRUE(s.uses_sprague());
  for (double l = 380.0; l <= 415.0; l += 0.3) EXPECT_NEAR(s.value(l), f(l), 1e-12) << l;
  // Fewer than 6 points: linear.
  const Spectrum few("few", uniform_grid(380.0, 5.0, 5), {1, 2, 4, 8, 16}, Interpolation::kSprague);
  EXPECT_FALSE(few.uses_sprague());
  EXPECT_DOUBLE_EQ(few.value(382.5), 1.5);
}

TEST(Interpolation, SpragueDipsOfANonNegativeTableAreZero) {
  // A single spike: the quintic rings below zero next to it; a non-negative table stays so.
  const std::vector<double> x = uniform_grid(400.0, 10.0, 9);
  const std::vector<double> y = {0, 0, 0, 0, 1, 0, 0, 0, 0};
  const Spectrum s("spike", x, y, Interpolation::kSprague);
  for (double l = 400.0; l <= 480.0; l += 0.5) EXPECT_GE(s.value(l), 0.0) << l;
  // The same spike on a negative base is not clipped: between 420 and 430 nm the ringing shows.
  std::vector<double> shifted;
  for (double v : y) shifted.push_back(v - 1.0);
  const Spectrum t("shifted", x, shifted, Interpolation::kSprague);
  EXPECT_LT(t.value(425.0), -1.0);
  EXPECT_DOUBLE_EQ(s.value(425.0), 0.0);
}

TEST(Interpolation, ExtrapolationIsRefusedOrZeroAsStated) {
  const std::vector<double> x = {400.0, 500.0, 600.0};
  const std::vector<double> y = {1.0, 2.0, 4.0};
  const Spectrum refuse("panel", x, y);
  try {
    refuse.value(600.5);
    FAIL() << "extrapolated";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("panel"), std::string::npos) << m;
    EXPECT_NE(m.find("no extrapolation"), std::string::npos) << m;
  }
  EXPECT_THROW(refuse.value(399.999), InputError);
  EXPECT_THROW(refuse.value(std::nan("")), InputError);
  EXPECT_THROW(interpolate_linear(x, y, 300.0, Extrapolation::kRefuse, "t"), InputError);

  const Spectrum zero("lamp", x, y, Interpolation::kLinear, Extrapolation::kZero);
  EXPECT_EQ(zero.value(300.0), 0.0);
  EXPECT_EQ(zero.value(700.0), 0.0);
  EXPECT_DOUBLE_EQ(zero.value(550.0), 3.0);

  // Within rounding of the ends (1e-9 of 600 nm), the end value; beyond, refused.
  const Spectrum rounding("panel", x, y, Interpolation::kLinear, Extrapolation::kRefuseBeyondRounding);
  EXPECT_EQ(rounding.value(600.0 + 1e-7), 4.0);
  EXPECT_EQ(rounding.value(400.0 - 1e-7), 1.0);
  EXPECT_THROW(rounding.value(600.0 + 1e-5), InputError);
  EXPECT_THROW(Spectrum("panel", x, y).value(600.0 + 1e-7), InputError);
}

TEST(Spectrum, RefusesTablesThatAreNoSpectra) {
  EXPECT_THROW(Spectrum("s", {400, 500}, {1}), InputError);
  EXPECT_THROW(Spectrum("s", {}, {}), InputError);
  EXPECT_THROW(Spectrum("s", {500, 400}, {1, 1}), InputError);
  EXPECT_THROW(Spectrum("s", {400, 400}, {1, 1}), InputError);
  EXPECT_THROW(Spectrum("s", {400, 500}, {1, INFINITY}), InputError);
  EXPECT_THROW(Spectrum("s", {400, 500}, {1, 1}, Interpolation::kLinear, Extrapolation::kRefuse, {0.1, -0.1}),
               InputError);
}

TEST(Spectrum, TrapezoidIntegralAndUncertainty) {
  const Spectrum s("s", {400, 500, 700}, {1, 3, 1}, Interpolation::kLinear, Extrapolation::kRefuse, {0.1, 0.3, 0.1});
  EXPECT_DOUBLE_EQ(trapezoid_integral(s), 100.0 * 2.0 + 200.0 * 2.0);
  EXPECT_DOUBLE_EQ(s.sigma_at(450.0, "s"), 0.2);
  EXPECT_EQ(Spectrum("t", {400, 500}, {1, 1}).sigma_at(450.0, "t"), 0.0);
}

TEST(SpectrumFile, TwoColumnsWithHeaderCommentsAndAnySeparator) {
  const std::string path = temp_file("two.csv",
                                     "\xEF\xBB\xBF# a lamp\n"
                                     "wavelength [nm], power\n"
                                     "400,1\n"
                                     "450 ; 2\n"
                                     "\n"
                                     "500\t4\n");
  const Spectrum s = read_spectrum(path);
  EXPECT_EQ(s.name(), path);
  EXPECT_EQ(s.wavelengths(), (std::vector<double>{400, 450, 500}));
  EXPECT_EQ(s.values(), (std::vector<double>{1, 2, 4}));
  EXPECT_TRUE(s.sigma().empty());
  std::filesystem::remove(path);
}

TEST(SpectrumFile, ThreeColumnsCarryUncertainties) {
  const std::string path = temp_file("three.txt", "350 0.98 0.005\n351 0.99 0.006\n");
  const Spectrum s = read_spectrum(path);
  EXPECT_EQ(s.sigma(), (std::vector<double>{0.005, 0.006}));
  SpectrumReadOptions two;
  two.uncertainties = false;
  const FileError e = read_error("three-refused.txt", "350 0.98 0.005\n", two);
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.column(), 10);
  std::filesystem::remove(path);
}

TEST(SpectrumFile, OneColumnFilesNeedTheirGrid) {
  const std::string path = temp_file("one.txt", "0.5\n0.6\n0.7\n");
  SpectrumReadOptions o;
  o.first_wavelength = 350.0;
  o.step = 2.0;
  const Spectrum s = read_spectrum(path, o);
  EXPECT_EQ(s.wavelengths(), (std::vector<double>{350, 352, 354}));
  EXPECT_EQ(s.values(), (std::vector<double>{0.5, 0.6, 0.7}));
  EXPECT_EQ(read_error("one-no-grid.txt", "0.5\n0.6\n").line(), 1);
  o.step = 0.0;
  EXPECT_EQ(read_error("one-zero-step.txt", "0.5\n0.6\n", o).line(), 1);
  SpectrumReadOptions solar;
  solar.one_column = false;
  solar.first_wavelength = 350.0;
  solar.step = 1.0;
  EXPECT_EQ(read_error("one-refused.txt", "# values\n0.5\n0.6\n", solar).line(), 2);
  std::filesystem::remove(path);
}

TEST(SpectrumFile, ErrorsNameFileLineAndColumn) {
  // "500,x": line 3, the 'x' at column 5.
  FileError e = read_error("bad.csv", "wavelength,power\n400,1\n500,x\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), 5);
  EXPECT_NE(std::string(e.what()).find("spectrum_bad.csv:3:5"), std::string::npos) << e.what();
  // A typo in a wavelength is no header row: line 2, column 1.
  e = read_error("typo.csv", "wavelength,irradiance\n4OO,1\n500,1.2\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 1);
  EXPECT_NE(std::string(e.what()).find("4OO"), std::string::npos) << e.what();
  // Wavelengths going back: the wavelength's cell.
  e = read_error("order.txt", "380 1\n500 1\n  490 1\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), 3);
  // A row of another length than the first: its first extra cell.
  e = read_error("ragged.csv", "380,1\n500,1,0.1\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 7);
  // An empty cell between two commas.
  e = read_error("empty-cell.csv", "380,,1\n");
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.column(), 5);
  // Negative values where they must not be, named as the quantity.
  SpectrumReadOptions o;
  o.non_negative = true;
  o.quantity = "irradiance";
  e = read_error("negative.csv", "400,1\n500,-1.2\n", o);
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 5);
  EXPECT_NE(std::string(e.what()).find("negative irradiance '-1.2'"), std::string::npos) << e.what();
  // A negative uncertainty.
  e = read_error("negative-sigma.txt", "400 1 0.1\n500 1 -0.1\n");
  EXPECT_EQ(e.column(), 7);
  // Nothing but comments.
  EXPECT_NE(std::string(read_error("empty.txt", "# nothing\n").what()).find("empty"), std::string::npos);
}

TEST(SpectrumFile, CountsAndIntegralChecks) {
  SpectrumReadOptions o;
  o.min_points = 2;
  EXPECT_EQ(read_error("single.csv", "400,1\n", o).line(), 0);
  o.positive_integral = true;
  o.quantity = "irradiance";
  const FileError zero = read_error("zero.csv", "400,0\n500,0\n", o);
  EXPECT_NE(std::string(zero.what()).find("must be finite and > 0"), std::string::npos) << zero.what();
  EXPECT_NE(std::string(zero.what()).find("irradiance"), std::string::npos) << zero.what();
  read_error("huge.csv", "400,1e308\n500,1e308\n", o);
}

TEST(SpectrumFile, WideTablesGiveTheNamedColumn) {
  const std::string path = temp_file("wide.csv",
                                     "Title of the table,,,\n"
                                     "wavelength,a,b,c\n"
                                     "400,1,10,100\n"
                                     "410,2,20,200\n");
  SpectrumReadOptions o;
  o.value_column = "b";
  o.name = "table b";
  const Spectrum s = read_spectrum(path, o);
  EXPECT_EQ(s.name(), "table b");
  EXPECT_EQ(s.values(), (std::vector<double>{10, 20}));
  o.value_column = "d";
  EXPECT_THROW(read_spectrum(path, o), FileError);
  std::filesystem::remove(path);
}

TEST(SpectrumFile, RulesComeFromTheOptions) {
  const std::string path = temp_file("rules.csv", "400,0\n410,1\n420,2\n430,1\n440,0\n450,0\n");
  SpectrumReadOptions o;
  o.interpolation = Interpolation::kSprague;
  o.outside = Extrapolation::kZero;
  const Spectrum s = read_spectrum(path, o);
  EXPECT_TRUE(s.uses_sprague());
  EXPECT_EQ(s.value(300.0), 0.0);
  // Sprague at the middle of [410, 420] nm: (3 f-2 - 25 f-1 + 150 f0 + 150 f1 - 25 f2 + 3 f3) / 256
  // with f-2 the end point (508*0 - 540*1 + 488*2 - 367*1 + 144*0 - 24*0)/209 = 69/209.
  const double fm2 = 69.0 / 209.0;
  EXPECT_NEAR(s.value(415.0), (3 * fm2 - 25 * 0 + 150 * 1 + 150 * 2 - 25 * 1 + 3 * 0) / 256.0, 1e-13);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace roadbrdf::spectra
