// fit --bounds: a parameter's range may be narrowed or widened inside its physical range, which the
// model metadata declares once. On the real CEA 3M retroreflective tape
// (data/third-party/retroreflective, ALTA format) retro-phong's Phong exponent stops at the default
// upper bound n = 1000; widened, the fit moves beyond it and its cost can only fall.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

TEST(FitBounds, PhysicalRangeComesFromTheMetadata) {
  auto model = make_model("retro-phong");
  const ModelDescription& d = model->description();
  const std::size_t n = *d.parameter_index("n");
  EXPECT_EQ(d.parameters[n].upper, 1000.0);  // the default fitting range
  EXPECT_EQ(d.physical_range(n), (std::pair<double, double>{0.0, 1e6}));
  const std::size_t kd = *d.parameter_index("kd");
  EXPECT_EQ(d.physical_range(kd), (std::pair<double, double>{0.0, 1.0}));  // not declared: the bounds
  // A composite keeps its components' physical ranges under their prefixed names.
  auto composite = make_model("lambert+retro-phong");
  const auto& cd = composite->description();
  EXPECT_EQ(cd.physical_range(*cd.parameter_index("retro-phong.n")).second, 1e6);
  // Values beyond the fitting range but inside the physical one are valid parameters.
  std::vector<double> p = d.default_parameters();
  p[n] = 5000.0;
  EXPECT_NO_THROW(check_parameters(d, p));
  p[n] = 2e6;
  EXPECT_THROW(check_parameters(d, p), InputError);
}

TEST(FitBounds, OutsideThePhysicalRangeIsAFieldError) {
  auto model = make_model("retro-phong");
  SpectralDataset data;
  data.geometries = {geometry_from_degrees(10, 0, 20, 180), geometry_from_degrees(20, 0, 30, 180)};
  data.wavelengths = {550.0};
  data.brdf = {0.2, 0.3};
  FitOptions o;
  o.fixed = {{"k1", 0.1}, {"k2", 0.01}, {"k3", 0.001}, {"k4", 1.0}};
  o.bounds = {{"n", {0.0, 2e6}}};
  try {
    fit_model(*model, data, o);
    FAIL();
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "bounds.n");
    EXPECT_NE(std::string(e.what()).find("physical range [0, 1000000]"), std::string::npos) << e.what();
  }
  o.bounds = {{"kd", {0.0, 1.5}}};  // an albedo above 1: not physical
  EXPECT_THROW(fit_model(*model, data, o), FieldError);
}

TEST(FitBounds, ThreeMTapeExponentMovesBeyondTheDefaultRangeWhenWidened) {
  const std::string path = roadbrdf::data_directory() + "/third-party/retroreflective/retro-3M-yellow.dat";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "retroreflective data not bundled";
  AltaReadOptions ro;
  ro.wavelength_nm = 550.0;
  ro.exclude_grazing = true;
  ro.assumed_output = "INV_STERADIAN_COSINE_FACTOR";
  ro.average_duplicates = true;
  ro.warn = [](const std::string&) {};
  const SpectralDataset data = read_alta(path, ro);
  auto model = make_model("retro-phong");
  FitOptions o;
  o.multistart = 8;  // plain loss, as `roadbrdf fit` by default
  const FitResult narrow = fit_model(*model, data, o);
  const std::size_t n = *model->description().parameter_index("n");
  ASSERT_EQ(narrow.wavelengths[0].parameters[n], 1000.0);  // the problem of the issue: stuck at the bound
  o.bounds = {{"n", {0.0, 1e5}}};
  const FitResult wide = fit_model(*model, data, o);
  const WavelengthFit& w = wide.wavelengths[0];
  EXPECT_GT(w.parameters[n], 1000.0);
  EXPECT_LT(w.chi2, narrow.wavelengths[0].chi2);  // a wider range can only fit better; here strictly
  for (const auto& b : w.at_bounds) EXPECT_NE(b, "n=upper");
}

}  // namespace
}  // namespace roadbrdf
